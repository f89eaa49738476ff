#include "RbmProblem.hpp"

#include "NodeExchange.hpp"
#include "OrderedSums.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rbm::motion {

EdgeWeighting edgeWeightingFromName(std::string_view name)
{
    if (name == "uniform") return EdgeWeighting::uniform;
    if (name == "inverseDistance") return EdgeWeighting::inverseDistance;
    if (name == "inverseDistanceSquared") return EdgeWeighting::inverseDistanceSquared;
    throw std::invalid_argument("Unknown edge weighting " + std::string(name) +
                                ". Valid weightings are: uniform inverseDistance inverseDistanceSquared");
}

std::string_view edgeWeightingName(EdgeWeighting weighting)
{
    switch (weighting) {
    case EdgeWeighting::uniform: return "uniform";
    case EdgeWeighting::inverseDistance: return "inverseDistance";
    case EdgeWeighting::inverseDistanceSquared: return "inverseDistanceSquared";
    }
    return "?";
}

RbmProblem::RbmProblem(int dimension, std::vector<Vector3> referencePoints,
                       std::shared_ptr<const CellNeighbourGraph> graph, std::vector<NodeConstraint> constraints,
                       EdgeWeighting weighting)
    : dimension_(dimension), referencePoints_(std::move(referencePoints)), graph_(std::move(graph)),
      constraints_(std::move(constraints)), weighting_(weighting)
{
    build();
}

RbmProblem::RbmProblem(int dimension, std::vector<Vector3> referencePoints, CellNeighbourGraph graph,
                       std::vector<NodeConstraint> constraints, EdgeWeighting weighting)
    : RbmProblem(dimension, std::move(referencePoints), std::make_shared<const CellNeighbourGraph>(std::move(graph)),
                 std::move(constraints), weighting)
{}

RbmProblem::RbmProblem(int dimension, std::vector<Vector3> referencePoints,
                       std::shared_ptr<const CellNeighbourGraph> graph, std::vector<NodeConstraint> constraints,
                       EdgeWeighting weighting, ProblemPart part)
    : dimension_(dimension), referencePoints_(std::move(referencePoints)), graph_(std::move(graph)),
      constraints_(std::move(constraints)), weighting_(weighting), part_(std::move(part))
{
    if (!part_.exchange) throw std::invalid_argument("RBM problem: a part needs its node exchange");
    if (part_.ownedNodeCount < 0 || part_.ownedNodeCount > static_cast<int>(referencePoints_.size()))
        throw std::invalid_argument("RBM problem: owned node count " + std::to_string(part_.ownedNodeCount) +
                                    " out of range");
    build();
}

namespace {

// The owned unknown nodes' entries of a compact vector of `unknownCount` nodes.
std::span<const double> ownedEntries(std::span<const double> values, int unknownCount, int ownedCount)
{
    if (unknownCount == 0 || ownedCount == unknownCount) return values;
    return values.first(values.size() / static_cast<std::size_t>(unknownCount) * static_cast<std::size_t>(ownedCount));
}

} // namespace

double RbmProblem::compactDot(std::span<const double> a, std::span<const double> b) const
{
    const double local = dotProduct(ownedEntries(a, unknownNodeCount(), ownedUnknownCount_),
                                    ownedEntries(b, unknownNodeCount(), ownedUnknownCount_));
    return sumOverRanks(local);
}

double RbmProblem::compactNorm(std::span<const double> a) const { return std::sqrt(compactDot(a, a)); }

double RbmProblem::sumOverRanks(double value) const { return isPart() ? part_.exchange->sum(value) : value; }

double RbmProblem::maximumOverRanks(double value) const { return isPart() ? part_.exchange->maximum(value) : value; }

void RbmProblem::updateGhostNodes(std::span<Vector3> nodeValues) const
{
    if (isPart()) part_.exchange->updateGhosts({&nodeValues.front().x, nodeValues.size() * 3}, 3);
}

RbmProblem RbmProblem::withReferencePoints(std::vector<Vector3> referencePoints) const
{
    RbmProblem moved = isPart() ? RbmProblem(dimension_, std::move(referencePoints), graph_, constraints_, weighting_, part_)
                                : RbmProblem(dimension_, std::move(referencePoints), graph_, constraints_, weighting_);
    moved.coupledPairs_ = coupledPairs_;  // checked already
    if (edgeWeightFactors_) {
        moved.edgeWeightFactors_ = edgeWeightFactors_;  // checked already
        moved.computeEdgeWeights();
    } else if (edgeWeightFactorsReleased_) {
        // The factors are in the weights only: taken back out of them for the new positions
        // (to a few units in the last place), then let go of again.
        moved.edgeWeightFactors_ = std::make_shared<const std::vector<double>>(edgeWeightFactorsFromWeights());
        moved.computeEdgeWeights();
        moved.releaseEdgeWeightFactors();
    }
    return moved;
}

void RbmProblem::setEdgeWeightFactors(std::span<const double> factors)
{
    setEdgeWeightFactors(factors.empty() ? nullptr
                                         : std::make_shared<const std::vector<double>>(factors.begin(), factors.end()));
}

void RbmProblem::releaseEdgeWeightFactors()
{
    if (!edgeWeightFactors_) return;
    edgeWeightFactors_.reset();
    edgeWeightFactorsReleased_ = true;
}

const std::vector<double>& RbmProblem::edgeWeightFactors() const
{
    static const std::vector<double> none;
    return edgeWeightFactors_ ? *edgeWeightFactors_ : none;
}

void RbmProblem::setEdgeWeightFactors(std::shared_ptr<const std::vector<double>> shared)
{
    const CellNeighbourGraph& g = *graph_;
    if (shared && shared->empty()) shared.reset();
    if (shared) {
        const std::vector<double>& factors = *shared;
        if (factors.size() != g.neighbours.size())
            throw std::invalid_argument("RBM problem: " + std::to_string(factors.size()) +
                                        " edge weight factors given, expected one per graph edge (" +
                                        std::to_string(g.neighbours.size()) + ")");
        for (int i = 0; i < nodeCount(); ++i) {
            for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e) {
                const double factor = factors[e];
                if (!(factor > 0.0) || !std::isfinite(factor))
                    throw std::invalid_argument("RBM problem: the weight factor of edge " + std::to_string(i) + "–" +
                                                std::to_string(g.neighbours[e]) + " is not positive and finite");
                const int j = g.neighbours[e];
                const auto begin = g.neighbours.begin() + g.offsets[j];
                const auto end = g.neighbours.begin() + g.offsets[j + 1];
                const auto reverse = std::lower_bound(begin, end, i);
                if (reverse == end || *reverse != i) continue;  // not symmetric: reported by build()
                const double other = factors[reverse - g.neighbours.begin()];
                if (std::abs(factor - other) > 1e-12 * std::max(factor, other))
                    throw std::invalid_argument("RBM problem: the weight factors of edges " + std::to_string(i) + "–" +
                                                std::to_string(j) + " and " + std::to_string(j) + "–" +
                                                std::to_string(i) + " differ (they must be symmetric)");
            }
        }
    }
    edgeWeightFactors_ = std::move(shared);
    edgeWeightFactorsReleased_ = false;
    computeEdgeWeights();
}

void RbmProblem::checkNodeArray(std::span<const Vector3> values, std::string_view what) const
{
    if (static_cast<int>(values.size()) != nodeCount())
        throw std::invalid_argument("RBM problem: " + std::string(what) + " has " + std::to_string(values.size()) +
                                    " entries, expected one per node (" + std::to_string(nodeCount()) + ")");
}

// Builds the derived data of the problem, checking its inputs.
void RbmProblem::build()
{
    checkSizes();
    computeSlidingNormals();
    numberUnknowns();
    totalUnknownNodeCount_ = static_cast<long long>(sumOverRanks(ownedUnknownCount_));  // collective for a part
    computeEdgeWeights();
    if (!isPart()) checkUnknownsHeld();
    buildBlockPattern();
    checkBlockPattern();
}

// The dimension, the graph and the constraints fit the reference points.
void RbmProblem::checkSizes() const
{
    if (dimension_ != 2 && dimension_ != 3)
        throw std::invalid_argument("RBM problem: dimension must be 2 or 3, got " + std::to_string(dimension_));
    if (!graph_) throw std::invalid_argument("RBM problem: no cell-neighbour graph");
    const CellNeighbourGraph& g = *graph_;
    const int n = nodeCount();
    if (g.nodeCount() != n)
        throw std::invalid_argument("RBM problem: the graph has " + std::to_string(g.nodeCount()) + " nodes but " +
                                    std::to_string(n) + " reference points were given");
    if (static_cast<int>(constraints_.size()) != n)
        throw std::invalid_argument("RBM problem: " + std::to_string(constraints_.size()) +
                                    " node constraints given, expected one per node (" + std::to_string(n) + ")");
}

// Unit normals of the sliding nodes' planes (and second planes along a line), checked.
void RbmProblem::computeSlidingNormals()
{
    const int n = nodeCount();
    slidingNodeCount_ = 0;
    const bool anySliding = std::any_of(constraints_.begin(), constraints_.end(),
                                        [](const NodeConstraint& c) { return c.kind == NodeKind::sliding; });
    unitNormals_.assign(anySliding ? n : 0, Vector3{});
    secondUnitNormals_.assign(anySliding ? n : 0, Vector3{});
    for (int node = 0; node < n; ++node) {
        if (constraints_[node].kind != NodeKind::sliding) continue;
        Vector3 normal = constraints_[node].normal;
        if (dimension_ == 2) normal.z = 0.0;
        const double length = norm(normal);
        if (!(length > 0.0) || !std::isfinite(length))
            throw std::invalid_argument("RBM problem: sliding node " + std::to_string(node) +
                                        " has a zero or invalid plane normal");
        unitNormals_[node] = normal / length;
        ++slidingNodeCount_;
        const Vector3& second = constraints_[node].secondNormal;
        if (second == Vector3{}) continue;
        if (dimension_ == 2)
            throw std::invalid_argument("RBM problem: sliding node " + std::to_string(node) +
                                        " has a second plane in 2D (two lines meet in a point: hold it)");
        // Gram–Schmidt: m̂ ⟂ n, so that P = I − n nᵀ − m̂ m̂ᵀ is the projector onto the line.
        const double secondLength = norm(second);
        const Vector3 m = second / secondLength - dot(second / secondLength, unitNormals_[node]) * unitNormals_[node];
        const double orthogonal = norm(m);
        if (!(secondLength > 0.0) || !std::isfinite(secondLength) || !(orthogonal > 1e-6))
            throw std::invalid_argument("RBM problem: sliding node " + std::to_string(node) +
                                        " has a second plane normal that is invalid or parallel to the first");
        secondUnitNormals_[node] = m / orthogonal;
    }
}

// Unknown numbering: the nodes not prescribed, in node order.
void RbmProblem::numberUnknowns()
{
    const int n = nodeCount();
    unknownIndex_.assign(n, -1);
    unknownNodes_.clear();
    ownedUnknownCount_ = 0;
    for (int node = 0; node < n; ++node) {
        if (constraints_[node].kind == NodeKind::prescribed) continue;
        unknownIndex_[node] = static_cast<int>(unknownNodes_.size());
        unknownNodes_.push_back(node);
        if (node < ownedNodeCount()) ownedUnknownCount_ = static_cast<int>(unknownNodes_.size());
    }
}

// Every unknown node needs neighbours, and every connected group of unknown nodes
// needs a prescribed neighbour; otherwise the group floats and the system is singular.
void RbmProblem::checkUnknownsHeld() const
{
    const CellNeighbourGraph& g = *graph_;
    const int n = nodeCount();
    std::vector<int> component(n, -1);
    std::vector<int> stack;
    for (int start : unknownNodes_) {
        if (g.offsets[start + 1] == g.offsets[start])
            throw std::invalid_argument("RBM problem: unknown node " + std::to_string(start) +
                                        " has no neighbours");
        if (component[start] >= 0) continue;
        bool held = false;
        component[start] = start;
        stack.assign(1, start);
        while (!stack.empty()) {
            const int i = stack.back();
            stack.pop_back();
            for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e) {
                const int j = g.neighbours[e];
                if (constraints_[j].kind == NodeKind::prescribed) {
                    held = true;
                } else if (component[j] < 0) {
                    component[j] = start;
                    stack.push_back(j);
                }
            }
        }
        if (!held)
            throw std::invalid_argument("RBM problem: the unknown nodes connected to node " + std::to_string(start) +
                                        " have no prescribed neighbour, so their motion is undetermined");
    }
}

// Block pattern over unknown nodes: graph neighbours that are unknown, plus the diagonal.
void RbmProblem::buildBlockPattern()
{
    const CellNeighbourGraph& g = *graph_;
    const int m = unknownNodeCount();
    blockPattern_ = BlockPattern{};
    blockPattern_.rowOffsets.assign(m + 1, 0);
    blockPattern_.diagonal.assign(m, -1);
    for (int a = 0; a < m; ++a) {
        const int i = unknownNodes_[a];
        int count = 1;
        for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e)
            if (unknownIndex_[g.neighbours[e]] >= 0) ++count;
        blockPattern_.rowOffsets[a + 1] = blockPattern_.rowOffsets[a] + count;
    }
    blockPattern_.columns.assign(blockPattern_.rowOffsets[m], -1);
    for (int a = 0; a < m; ++a) {
        const int i = unknownNodes_[a];
        int position = blockPattern_.rowOffsets[a];
        bool diagonalPlaced = false;
        // Neighbours are sorted by node, and unknown indices grow with node numbers, so
        // the columns come out sorted; the diagonal goes where node i would be.
        for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e) {
            const int j = g.neighbours[e];
            const int b = unknownIndex_[j];
            if (b < 0) continue;
            if (!diagonalPlaced && b > a) {
                blockPattern_.diagonal[a] = position;
                blockPattern_.columns[position++] = a;
                diagonalPlaced = true;
            }
            blockPattern_.columns[position++] = b;
        }
        if (!diagonalPlaced) {
            blockPattern_.diagonal[a] = position;
            blockPattern_.columns[position++] = a;
        }
    }
}

// The pattern's rows are sorted and the graph is symmetric between unknowns.
void RbmProblem::checkBlockPattern() const
{
    const int m = unknownNodeCount();
    for (int a = 0; a < m; ++a) {
        const auto begin = blockPattern_.columns.begin() + blockPattern_.rowOffsets[a];
        const auto end = blockPattern_.columns.begin() + blockPattern_.rowOffsets[a + 1];
        if (!std::is_sorted(begin, end))
            throw std::invalid_argument("RBM problem: the neighbour lists of the graph are not sorted ascending");
    }
    // The graph's symmetry: block (j, i) of every edge (i → j) between unknowns exists (its
    // position is edgeTransposeBlock()'s, kept only where asked for).
    forEachEdgeBetweenUnknowns([&](int, int a, int b) {
        if (reversePosition(a, b) < 0)
            throw std::invalid_argument("RBM problem: the cell-neighbour graph is not symmetric (node " +
                                        std::to_string(unknownNodes_[a]) + " lists " +
                                        std::to_string(unknownNodes_[b]) + " but not the reverse)");
    });
}

int RbmProblem::reversePosition(int a, int b) const
{
    const auto begin = blockPattern_.columns.begin() + blockPattern_.rowOffsets[b];
    const auto end = blockPattern_.columns.begin() + blockPattern_.rowOffsets[b + 1];
    const auto found = std::lower_bound(begin, end, a);
    return found == end || *found != a ? -1 : static_cast<int>(found - blockPattern_.columns.begin());
}

template <typename Visit>
void RbmProblem::forEachEdgeBetweenUnknowns(Visit&& visit) const
{
    const CellNeighbourGraph& g = *graph_;
    for (int a = 0; a < unknownNodeCount(); ++a) {
        const int i = unknownNodes_[a];
        for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e) {
            const int b = unknownIndex_[g.neighbours[e]];
            if (b >= 0) visit(e, a, b);
        }
    }
}

const std::vector<int>& RbmProblem::edgeBlock() const
{
    std::call_once(edgeBlock_->built, [this] {
        std::vector<int>& positions = edgeBlock_->positions;
        positions.assign(graph_->neighbours.size(), -1);
        // Row a's unknown neighbours in graph order take its positions in order, skipping the
        // diagonal's (buildBlockPattern).
        int row = -1, position = 0;
        forEachEdgeBetweenUnknowns([&](int e, int a, int) {
            if (a != row) row = a, position = blockPattern_.rowOffsets[a];
            if (position == blockPattern_.diagonal[a]) ++position;
            positions[e] = position++;
        });
    });
    return edgeBlock_->positions;
}

const std::vector<int>& RbmProblem::edgeTransposeBlock() const
{
    std::call_once(edgeTransposeBlock_->built, [this] {
        std::vector<int>& positions = edgeTransposeBlock_->positions;
        positions.assign(graph_->neighbours.size(), -1);
        forEachEdgeBetweenUnknowns([&](int e, int a, int b) { positions[e] = reversePosition(a, b); });
    });
    return edgeTransposeBlock_->positions;
}

double RbmProblem::plainEdgeWeight(int i, int j) const
{
    Vector3 d = referencePoints_[j] - referencePoints_[i];
    if (dimension_ == 2) d.z = 0.0;  // planar problems ignore z, also in distances
    const double length = norm(d);
    switch (weighting_) {
    case EdgeWeighting::uniform: return 1.0;
    case EdgeWeighting::inverseDistance: return 1.0 / length;
    case EdgeWeighting::inverseDistanceSquared: return 1.0 / (length * length);
    }
    return 1.0;
}

std::vector<double> RbmProblem::edgeWeightFactorsFromWeights() const
{
    // w_ij and the plain weight are the same bits in both directions (p_j − p_i and p_i − p_j
    // differ in sign only): the recovered factors are symmetric.
    const CellNeighbourGraph& g = *graph_;
    std::vector<double> factors(g.neighbours.size(), 1.0);
    for (int i = 0; i < nodeCount(); ++i)
        for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e)
            factors[e] = edgeWeights_[e] / plainEdgeWeight(i, g.neighbours[e]);
    return factors;
}

void RbmProblem::computeEdgeWeights()
{
    const CellNeighbourGraph& g = *graph_;
    edgeWeights_.assign(g.neighbours.size(), 0.0);
    double lengthSum = 0.0;
    minimumEdgeLength_ = std::numeric_limits<double>::infinity();
    for (int i = 0; i < nodeCount(); ++i) {
        for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e) {
            const int j = g.neighbours[e];
            Vector3 d = referencePoints_[j] - referencePoints_[i];
            if (dimension_ == 2) d.z = 0.0;  // planar problems ignore z, also in distances
            const double length = norm(d);
            if (!(length > 0.0))
                throw std::invalid_argument("RBM problem: neighbouring nodes " + std::to_string(i) + " and " +
                                            std::to_string(j) + " are at the same position");
            lengthSum += length;
            minimumEdgeLength_ = std::min(minimumEdgeLength_, length);
            switch (weighting_) {
            case EdgeWeighting::uniform: edgeWeights_[e] = 1.0; break;
            case EdgeWeighting::inverseDistance: edgeWeights_[e] = 1.0 / length; break;
            case EdgeWeighting::inverseDistanceSquared: edgeWeights_[e] = 1.0 / (length * length); break;
            }
            if (edgeWeightFactors_) edgeWeights_[e] *= (*edgeWeightFactors_)[e];
        }
    }
    if (g.neighbours.empty()) minimumEdgeLength_ = 0.0;
    meanEdgeLength_ = g.neighbours.empty() ? 0.0 : lengthSum / static_cast<double>(g.neighbours.size());
}

double RbmProblem::shortestNeighbourDistance(int node) const
{
    const CellNeighbourGraph& g = *graph_;
    double shortest = std::numeric_limits<double>::infinity();
    for (int e = g.offsets[node]; e < g.offsets[node + 1]; ++e) {
        Vector3 d = referencePoints_[g.neighbours[e]] - referencePoints_[node];
        if (dimension_ == 2) d.z = 0.0;
        shortest = std::min(shortest, norm(d));
    }
    return shortest;
}

void RbmProblem::setCoupledPairs(std::vector<CoupledPair> pairs)
{
    std::vector<char> paired(static_cast<std::size_t>(nodeCount()), 0);
    for (const CoupledPair& pair : pairs) checkCoupledPair(pair, paired);
    coupledPairs_ = std::move(pairs);
}

void RbmProblem::checkCoupledPair(const CoupledPair& pair, std::vector<char>& paired) const
{
    const std::string name = "RBM problem: coupled pair " + std::to_string(pair.a) + "–" + std::to_string(pair.b);
    if (pair.a < 0 || pair.b < 0 || pair.a >= nodeCount() || pair.b >= nodeCount() || pair.a == pair.b)
        throw std::invalid_argument(name + ": not two different nodes of the problem");
    if (!isUnknown(pair.a) || !isUnknown(pair.b)) throw std::invalid_argument(name + ": a node is prescribed");
    if (paired[pair.a] || paired[pair.b]) throw std::invalid_argument(name + ": a node is in two pairs");
    paired[pair.a] = paired[pair.b] = 1;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (std::abs(dot(pair.q[i], pair.q[j]) - (i == j ? 1.0 : 0.0)) > 1e-9)
                throw std::invalid_argument(name + ": q is not orthogonal");
    if (dimension_ == 2 && std::abs(pair.q[2].z - 1.0) > 1e-9)
        throw std::invalid_argument(name + ": q turns the plane of the 2D problem");
    // P_b = q P_a qᵀ: the same number of planes, and q maps a's normals into b's.
    const int planesA = kind(pair.a) != NodeKind::sliding ? 0 : slidesOnLine(pair.a) ? 2 : 1;
    const int planesB = kind(pair.b) != NodeKind::sliding ? 0 : slidesOnLine(pair.b) ? 2 : 1;
    bool consistent = planesA == planesB;
    for (const Vector3* n : {&slidingNormal(pair.a), &secondSlidingNormal(pair.a)}) {
        if (!consistent || *n == Vector3{}) continue;
        const Vector3 mapped = pair.map(*n);
        consistent = norm(slidingNormalPart(pair.b, mapped) - mapped) <= 1e-9;
    }
    if (!consistent)
        throw std::invalid_argument(name + ": the sliding constraints of the two nodes do not correspond under q");
}

void RbmProblem::enforceCoupledPairs(std::span<Vector3> displacement) const
{
    for (const CoupledPair& pair : coupledPairs_) {
        Vector3 mapped = pair.map(displacement[pair.a]);
        if (dimension_ == 2) mapped.z = 0.0;
        displacement[pair.b] = mapped;
    }
}

void RbmProblem::projectCoupledPairs(std::span<double> blockVector, int bs) const
{
    // The orthogonal projector onto {u_b = q u_a}: the nearest (a', q a') to (a, b) has
    // a' = (a + qᵀ b)/2 (q orthogonal). In 2D the z entries are absent and q's z column unused.
    for (const CoupledPair& pair : coupledPairs_) {
        double* a = blockVector.data() + static_cast<std::size_t>(unknownIndex_[pair.a]) * bs;
        double* b = blockVector.data() + static_cast<std::size_t>(unknownIndex_[pair.b]) * bs;
        Vector3 va{}, vb{};
        for (int k = 0; k < dimension_; ++k) {
            va[k] = a[k];
            vb[k] = b[k];
        }
        const Vector3 mean = 0.5 * (va + pair.mapBack(vb));
        const Vector3 mapped = pair.map(mean);
        for (int k = 0; k < dimension_; ++k) {
            a[k] = mean[k];
            b[k] = mapped[k];
        }
    }
}

void RbmProblem::projectSliding(std::span<double> blockVector, int bs) const
{
    // Pairs first, then the planes: with P_b = q P_a qᵀ (setCoupledPairs) the two projectors
    // commute, so the product is the orthogonal projector onto both constraints.
    projectCoupledPairs(blockVector, bs);
    if (slidingNodeCount_ == 0) return;
    const bool hasRotations = bs == blockSize();
    for (int a = 0; a < unknownNodeCount(); ++a) {
        const int node = unknownNodes_[a];
        if (constraints_[node].kind != NodeKind::sliding) continue;
        double* u = blockVector.data() + static_cast<std::size_t>(a) * bs;
        for (const Vector3* normal : {&unitNormals_[node], &secondUnitNormals_[node]}) {
            const Vector3& n = *normal;  // orthonormal, so removing one after the other is P
            double normalPart = 0.0;
            for (int k = 0; k < dimension_; ++k) normalPart += u[k] * n[k];
            for (int k = 0; k < dimension_; ++k) u[k] -= normalPart * n[k];
        }
        const Vector3& n = unitNormals_[node];
        if (hasRotations && rotatesAboutNormalOnly(node)) {
            double* omega = u + 3;
            double along = 0.0;
            for (int k = 0; k < 3; ++k) along += omega[k] * n[k];
            for (int k = 0; k < 3; ++k) omega[k] = along * n[k];
        }
    }
}

void RbmProblem::slidingOffset(std::span<const Vector3> prescribedDisplacement, std::span<double> blockVector,
                               int bs) const
{
    checkNodeArray(prescribedDisplacement, "prescribed displacement");
    std::fill(blockVector.begin(), blockVector.end(), 0.0);
    for (int a = 0; a < unknownNodeCount(); ++a) {
        const int node = unknownNodes_[a];
        if (constraints_[node].kind != NodeKind::sliding) continue;
        Vector3 given = prescribedDisplacement[node];
        if (dimension_ == 2) given.z = 0.0;
        const Vector3 offset = slidingNormalPart(node, given);  // c n (+ c' m̂ on a line)
        for (int k = 0; k < dimension_; ++k) blockVector[static_cast<std::size_t>(a) * bs + k] = offset[k];
    }
    // A pair's offsets correspond too, so that offset + projected direction keeps u_b = q u_a.
    for (const CoupledPair& pair : coupledPairs_) {
        const std::size_t a = static_cast<std::size_t>(unknownIndex_[pair.a]) * bs;
        const std::size_t b = static_cast<std::size_t>(unknownIndex_[pair.b]) * bs;
        Vector3 offset{};
        for (int k = 0; k < dimension_; ++k) offset[k] = blockVector[a + k];
        const Vector3 mapped = pair.map(offset);
        for (int k = 0; k < dimension_; ++k) blockVector[b + k] = mapped[k];
    }
}

void RbmProblem::projectSlidingBlocks(std::span<double> blockValues, int bs) const
{
    if (slidingNodeCount_ == 0) return;
    const int dim = dimension_;
    const bool hasRotations = bs == blockSize();
    const std::size_t area = static_cast<std::size_t>(bs) * bs;
    // A sliding node's projector P is block diagonal: I − n nᵀ on the displacement and, for
    // a mirror node with rotations in the system, n nᵀ on the rotation (identity otherwise).
    // project(v) applies P to a strided vector of bs entries.
    struct NodeProjector {
        const Vector3* normal = nullptr;
        const Vector3* second = nullptr;  // line nodes: m̂ (zero vector otherwise, removing nothing)
        bool rotationToo = false;
        void apply(double* v, int stride) const
        {
            for (const Vector3* plane : {normal, second}) {
                const Vector3& n = *plane;
                double normalPart = 0.0;
                for (int q = 0; q < 3; ++q) normalPart += n[q] * v[q * stride];
                for (int q = 0; q < 3; ++q) v[q * stride] -= normalPart * n[q];
            }
            if (!rotationToo) return;
            const Vector3& n = *normal;
            double along = 0.0;
            for (int q = 0; q < 3; ++q) along += n[q] * v[(3 + q) * stride];
            for (int q = 0; q < 3; ++q) v[(3 + q) * stride] = along * n[q];
        }
    };
    auto projectorOf = [&](int unknown) {
        const int node = unknownNodes_[unknown];
        NodeProjector projector;
        if (constraints_[node].kind != NodeKind::sliding) return projector;
        projector.normal = &unitNormals_[node];
        projector.second = &secondUnitNormals_[node];
        projector.rotationToo = hasRotations && rotatesAboutNormalOnly(node);
        return projector;
    };
    for (int a = 0; a < unknownNodeCount(); ++a) {
        const NodeProjector rowProjector = projectorOf(a);
        for (int position = blockPattern_.rowOffsets[a]; position < blockPattern_.rowOffsets[a + 1]; ++position) {
            const NodeProjector columnProjector = projectorOf(blockPattern_.columns[position]);
            if (!rowProjector.normal && !columnProjector.normal) continue;
            double* block = blockValues.data() + area * position;
            const bool isDiagonal = position == blockPattern_.diagonal[a];
            // s: the mean diagonal of the displacement part and of the rotation part, so the
            // added s (I − P) has the scale of the block it fills.
            double displacementScale = 0.0, rotationScale = 0.0;
            if (isDiagonal) {
                for (int q = 0; q < dim; ++q) displacementScale += block[q * bs + q];
                displacementScale /= dim;
                if (rowProjector.rotationToo) {
                    for (int q = 3; q < 6; ++q) rotationScale += block[q * bs + q];
                    rotationScale /= 3.0;
                }
            }
            if (dim == 2) {  // the projector above is written for 3D; 2D only projects displacements
                auto project2D = [&](const Vector3& n, double* v, int stride) {
                    const double normalPart = n.x * v[0] + n.y * v[stride];
                    v[0] -= normalPart * n.x;
                    v[stride] -= normalPart * n.y;
                };
                if (rowProjector.normal)
                    for (int column = 0; column < bs; ++column) project2D(*rowProjector.normal, block + column, bs);
                if (columnProjector.normal)
                    for (int row = 0; row < bs; ++row) project2D(*columnProjector.normal, block + row * bs, 1);
            } else {
                if (rowProjector.normal)  // P_a H: project every column
                    for (int column = 0; column < bs; ++column) rowProjector.apply(block + column, bs);
                if (columnProjector.normal)  // H P_b: project every row
                    for (int row = 0; row < bs; ++row) columnProjector.apply(block + row * bs, 1);
            }
            if (isDiagonal) {
                const Vector3& n = *rowProjector.normal;
                const Vector3& m = *rowProjector.second;  // s (I − P) = s (n nᵀ + m̂ m̂ᵀ)
                for (int p = 0; p < dim; ++p)
                    for (int q = 0; q < dim; ++q)
                        block[p * bs + q] += displacementScale * (n[p] * n[q] + m[p] * m[q]);
                if (rowProjector.rotationToo)
                    for (int p = 0; p < 3; ++p)
                        for (int q = 0; q < 3; ++q)
                            block[(3 + p) * bs + 3 + q] += rotationScale * ((p == q ? 1.0 : 0.0) - n[p] * n[q]);
            }
        }
    }
}

RbmResult prescribedOnlyResult(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement)
{
    RbmResult result;
    static_cast<RbmState&>(result) = unpackUnknowns(problem, prescribedDisplacement, {});
    result.converged = true;
    result.reason = "NO_UNKNOWNS";
    return result;
}

void packUnknowns(const RbmProblem& problem, const RbmState& state, std::span<double> unknowns)
{
    problem.checkNodeArray(state.displacement, "state displacement");
    problem.checkNodeArray(state.rotation, "state rotation");
    const int bs = problem.blockSize();
    const int dim = problem.dimension();
    for (int a = 0; a < problem.unknownNodeCount(); ++a) {
        const int node = problem.unknownNodes()[a];
        double* block = unknowns.data() + static_cast<std::size_t>(a) * bs;
        for (int k = 0; k < dim; ++k) block[k] = state.displacement[node][k];
        if (dim == 2) {
            block[2] = state.rotation[node].z;
        } else {
            for (int k = 0; k < 3; ++k) block[3 + k] = state.rotation[node][k];
        }
    }
}

RbmState unpackUnknowns(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement,
                        std::span<const double> unknowns)
{
    problem.checkNodeArray(prescribedDisplacement, "prescribed displacement");
    const int n = problem.nodeCount();
    const int bs = problem.blockSize();
    const int dim = problem.dimension();
    RbmState state;
    state.displacement.assign(n, Vector3{});
    state.rotation.assign(n, Vector3{});
    for (int node = 0; node < n; ++node) {
        if (problem.isUnknown(node)) continue;
        state.displacement[node] = prescribedDisplacement[node];
        if (dim == 2) state.displacement[node].z = 0.0;
    }
    for (int a = 0; a < problem.unknownNodeCount(); ++a) {
        const int node = problem.unknownNodes()[a];
        const double* block = unknowns.data() + static_cast<std::size_t>(a) * bs;
        for (int k = 0; k < dim; ++k) state.displacement[node][k] = block[k];
        if (dim == 2) {
            state.rotation[node].z = block[2];
        } else {
            for (int k = 0; k < 3; ++k) state.rotation[node][k] = block[3 + k];
        }
    }
    return state;
}

} // namespace rbm::motion

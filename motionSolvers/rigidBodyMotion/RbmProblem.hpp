#pragma once
// The RBM problem without any file behind it (docs/method.md §1–2): reference node positions
// x_k, the cell-neighbour graph N(k), a class per node (prescribed / free / sliding on a
// plane), the dimension (2 or 3) and the edge weights w_ij.
//
// Unknowns. Every free or sliding node ("unknown node") carries a block of unknowns:
//   2D: (u_x, u_y, θ)                       block size 3
//   3D: (u_x, u_y, u_z, ω_x, ω_y, ω_z)      block size 6
// u is the node's displacement, p = x + u its new position; the rotation is about the
// node's OWN reference position (node-local): the ideal position of neighbour j seen from
// centre i is p_i + R_i (x_j − x_i). Sign conventions: θ is counter-clockwise positive
// (R(θ) = [cos −sin; sin cos], the transpose of the thesis' eq 2.1 matrix); ω is a
// rotation vector (axis × angle, right-hand rule, R = exp([ω]×), Rodrigues' formula).
// Unknown nodes are numbered compactly in increasing node order ("unknown index").
//
// Sliding nodes: the displacement is confined to a plane, u·n = c, with n the node's unit
// normal and c = n·(the displacement given for that node in the prescribed-displacement
// array). In 2D the "plane" is a line. The rotation stays free.
// Line nodes (3D only): a sliding node with a second normal m lies on two planes and moves
// along their intersection line, u = c n + c' m̂ + (u·d) d with d = n × m̂ and m̂ the unit
// part of m normal to n (Gram–Schmidt), c' = m̂·(given displacement). Every projection
// below removes both normal components (P = I − n nᵀ − m̂ m̂ᵀ = d dᵀ). A node on two mirror
// planes would have to keep a zero rotation (a rotation vector is mirrored into −R ω by
// each plane, only ω = 0 is invariant under two); the core does not impose that: a line
// node's rotation stays free and `mirror` is ignored for it.
//
// Coupled pairs: two unknown nodes a and b tied by a cyclic patch (src/CyclicPairs.hpp) move
// together, u_b = q u_a with q orthogonal (I for a translational cyclic, the rotation of a
// rotational one). Only the reduced Newton solver honours them (its iteration stays in the
// subspace through projectSliding); the other variants' callers refuse them.
//
// 2D problems use x and y of the points; z is ignored and z displacements are zero.

#include "CellNeighbourGraph.hpp"
#include "Vector3.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rbm::motion {

class NodeExchange;

// One rank's part of a distributed problem (docs/parallel.md, "Distributed data"): the nodes of
// a MeshPart, its owned nodes first. The rank evaluates the terms, rotation fits and rows of
// the owned nodes only; the ghosts are the owned nodes' neighbours that other ranks own, and
// `exchange` brings their values. A serial problem has no part (it owns every node).
struct ProblemPart {
    int ownedNodeCount = 0;
    std::shared_ptr<const NodeExchange> exchange;
};

enum class NodeKind : std::uint8_t {
    prescribed,  // displacement given (fixed = prescribed zero); only ever a neighbour, never a centre
    free,        // displacement and rotation unknown
    sliding,     // unknown, displacement held on a plane u·n = c
};

struct NodeConstraint {
    NodeKind kind = NodeKind::free;
    Vector3 normal{};  // sliding only: normal of the plane (need not be unit length; 2D uses x, y)
    bool mirror = false;  // sliding only: a mirror (symmetry) plane; in 3D the rotation is held to the normal
    // Sliding only, 3D only: the normal of a second plane (zero: none). Nonzero makes the node
    // slide on the line where both planes meet (see the header comment).
    Vector3 secondNormal{};
};

// Two unknown nodes whose displacements are tied: u_b = q u_a (see the header comment). In 2D
// q turns about z only (its z row and column are those of I).
struct CoupledPair {
    int a = -1;
    int b = -1;
    // q by rows (plain vectors: this header is below both 3×3 matrix types of rbm).
    std::array<Vector3, 3> q{Vector3{1.0, 0.0, 0.0}, Vector3{0.0, 1.0, 0.0}, Vector3{0.0, 0.0, 1.0}};

    Vector3 map(const Vector3& v) const { return {dot(q[0], v), dot(q[1], v), dot(q[2], v)}; }  // q v
    Vector3 mapBack(const Vector3& v) const { return v.x * q[0] + v.y * q[1] + v.z * q[2]; }   // qᵀ v
};

// Edge weights w_ij (docs/method.md §1): the thesis uses uniform; 1/|d|² makes every
// neighbour's relative deformation count alike on stretched cells and is the default.
enum class EdgeWeighting {
    uniform,                 // w_ij = 1 (thesis)
    inverseDistance,         // w_ij = 1/|x_j − x_i|
    inverseDistanceSquared,  // w_ij = 1/|x_j − x_i|²
};

// "uniform", "inverseDistance", "inverseDistanceSquared"; throws std::invalid_argument
// listing the valid names otherwise.
EdgeWeighting edgeWeightingFromName(std::string_view name);
std::string_view edgeWeightingName(EdgeWeighting weighting);

// Block sparsity of the coupled matrices over unknown nodes (compact numbering): row a
// holds blocks at columns[rowOffsets[a] .. rowOffsets[a+1]), sorted ascending, the
// diagonal block included (its position is diagonal[a]). Unknown nodes a and b share a
// block when they are graph neighbours.
struct BlockPattern {
    std::vector<int> rowOffsets{0};
    std::vector<int> columns;
    std::vector<int> diagonal;

    int rowCount() const { return static_cast<int>(rowOffsets.size()) - 1; }
    int blockCount() const { return static_cast<int>(columns.size()); }
};

class RbmProblem {
public:
    // Throws std::invalid_argument for: dimension not 2 or 3, sizes that do not match the
    // graph, a sliding node with a zero normal, a second normal in 2D or parallel to the first, two neighbours at the same position, an
    // unknown node without neighbours, or a group of connected unknown nodes that no
    // prescribed node holds (its motion would be undetermined).
    RbmProblem(int dimension, std::vector<Vector3> referencePoints, std::shared_ptr<const CellNeighbourGraph> graph,
               std::vector<NodeConstraint> constraints, EdgeWeighting weighting = EdgeWeighting::inverseDistanceSquared);
    RbmProblem(int dimension, std::vector<Vector3> referencePoints, CellNeighbourGraph graph,
               std::vector<NodeConstraint> constraints, EdgeWeighting weighting = EdgeWeighting::inverseDistanceSquared);
    // One rank's part (ProblemPart). Whether every group of unknown nodes is held by a prescribed
    // node is a property of the whole problem, not of a part: it is not checked here.
    RbmProblem(int dimension, std::vector<Vector3> referencePoints, std::shared_ptr<const CellNeighbourGraph> graph,
               std::vector<NodeConstraint> constraints, EdgeWeighting weighting, ProblemPart part);

    // The same graph, node classes and weighting around other reference positions (the
    // next sub-step's mesh, thesis §2.6); weights are recomputed from the new positions.
    RbmProblem withReferencePoints(std::vector<Vector3> referencePoints) const;

    int dimension() const { return dimension_; }
    int blockSize() const { return dimension_ == 2 ? 3 : 6; }
    int rotationSize() const { return dimension_ == 2 ? 1 : 3; }
    int nodeCount() const { return static_cast<int>(referencePoints_.size()); }
    int unknownNodeCount() const { return static_cast<int>(unknownNodes_.size()); }
    int unknownCount() const { return unknownNodeCount() * blockSize(); }
    EdgeWeighting weighting() const { return weighting_; }
    // Distributed problems: the owned nodes (0 … ownedNodeCount() − 1) and their unknowns (the
    // first ownedUnknownCount(): unknowns are numbered in node order); the node exchange (null
    // for a serial problem, which owns everything).
    bool isPart() const { return part_.exchange != nullptr; }
    int ownedNodeCount() const { return isPart() ? part_.ownedNodeCount : nodeCount(); }
    int ownedUnknownCount() const { return ownedUnknownCount_; }
    // The unknown nodes of the whole problem (a part: every rank's owned ones). Decisions that
    // skip collective work (no unknowns: nothing to solve) must use this, not the local count,
    // so that all ranks take them alike.
    long long totalUnknownNodeCount() const { return totalUnknownNodeCount_; }
    const NodeExchange* nodeExchange() const { return part_.exchange.get(); }
    const ProblemPart& part() const { return part_; }
    // Reductions over the owned unknown nodes, summed (or maximised) over the ranks of a part;
    // vectors are compact (the same number of entries per unknown node). In a serial problem
    // these are OrderedSums' dotProduct and euclideanNorm and the value itself.
    double compactDot(std::span<const double> a, std::span<const double> b) const;
    double compactNorm(std::span<const double> a) const;
    double sumOverRanks(double value) const;
    double maximumOverRanks(double value) const;
    // Ghost nodes ← their owners' values (a node array, 3 doubles per node); nothing when serial.
    void updateGhostNodes(std::span<Vector3> nodeValues) const;

    const std::vector<Vector3>& referencePoints() const { return referencePoints_; }
    const CellNeighbourGraph& graph() const { return *graph_; }
    const std::shared_ptr<const CellNeighbourGraph>& sharedGraph() const { return graph_; }
    const std::vector<NodeConstraint>& constraints() const { return constraints_; }
    NodeKind kind(int node) const { return constraints_[node].kind; }
    bool isUnknown(int node) const { return unknownIndex_[node] >= 0; }

    // Weight of the directed edge stored at position e of graph().neighbours (w_ij = w_ji).
    const std::vector<double>& edgeWeights() const { return edgeWeights_; }

    // Multiplies every edge weight by a factor: one per directed graph edge, in the order of
    // graph().neighbours, positive and symmetric (f_ij = f_ji, so the systems stay
    // symmetric); used to stiffen the mesh near chosen patches. Empty restores the plain
    // weights. Kept by withReferencePoints(). Create solvers after this call: they assemble
    // their matrices from the weights. Throws std::invalid_argument for a wrong size, a
    // factor that is not positive and finite, or f_ij ≠ f_ji.
    void setEdgeWeightFactors(std::span<const double> factors);
    // The same, sharing the caller's array instead of copying it (null: the plain weights):
    // one array per directed edge is 210 MB at 10⁶ hexahedra, and the motion solver, every
    // problem it rebuilds and every sub-step's problem hold the same factors.
    void setEdgeWeightFactors(std::shared_ptr<const std::vector<double>> factors);
    const std::vector<double>& edgeWeightFactors() const;
    // Lets go of the factors once the weights hold them (edgeWeightFactors() is then empty;
    // withReferencePoints() takes them back out of the weights, edgeWeightFactorsFromWeights).
    // With the stiffening's own copy released too (EdgeStiffening::releaseFactors) that is 8
    // bytes per directed edge, about 200 bytes a node of a hexahedral mesh, no longer alive
    // through the solver's set-up, its solves, the quality check and the output.
    void releaseEdgeWeightFactors();
    // The factors the weights hold: each weight over the weighting's plain weight of its edge
    // (equal to the factors given to a few units in the last place; symmetric).
    std::vector<double> edgeWeightFactorsFromWeights() const;
    // Ties pairs of unknown nodes, u_b = q u_a (replacing any pairs set before; empty: none);
    // kept by withReferencePoints(). Create solvers after this call. Throws
    // std::invalid_argument for a node that is prescribed, in two pairs or paired with itself,
    // a q that is not orthogonal (or turns the plane in 2D), or sliding constraints of a and b
    // that q does not map onto each other (the projection below is symmetric only then).
    void setCoupledPairs(std::vector<CoupledPair> pairs);
    const std::vector<CoupledPair>& coupledPairs() const { return coupledPairs_; }
    bool hasCoupledPairs() const { return !coupledPairs_.empty(); }
    // u_b ← q u_a for every pair, exactly (the last rounding of an iteration, untangling).
    void enforceCoupledPairs(std::span<Vector3> displacement) const;
    // Unit normal of a sliding node (zero vector for other nodes), in the problem's dimension.
    const Vector3& slidingNormal(int node) const { return unitNormals_.empty() ? noNormal : unitNormals_[node]; }
    // Unit second normal m̂ of a line node, orthogonal to slidingNormal(node); zero for every
    // other node.
    const Vector3& secondSlidingNormal(int node) const
    {
        return secondUnitNormals_.empty() ? noNormal : secondUnitNormals_[node];
    }
    bool slidesOnLine(int node) const { return !(secondSlidingNormal(node) == Vector3{}); }
    // The part of v that a sliding node may not change: (v·n) n (+ (v·m̂) m̂ on a line), zero
    // for other nodes; v minus it is the admissible (tangential) part.
    Vector3 slidingNormalPart(int node, const Vector3& v) const
    {
        const Vector3& n = slidingNormal(node);
        const Vector3& m = secondSlidingNormal(node);
        return dot(v, n) * n + dot(v, m) * m;
    }
    // True for a sliding node on a mirror plane in 3D (not on a line): its rotation vector
    // must stay along slidingNormal(node) (see the header comment).
    bool rotatesAboutNormalOnly(int node) const
    {
        return dimension_ == 3 && constraints_[node].kind == NodeKind::sliding && constraints_[node].mirror &&
               !slidesOnLine(node);
    }

    // Node → unknown index (−1 for prescribed nodes) and unknown index → node.
    const std::vector<int>& unknownIndex() const { return unknownIndex_; }
    const std::vector<int>& unknownNodes() const { return unknownNodes_; }

    // Block pattern of the coupled matrices and, per graph edge e = (i → j) with i and j
    // both unknown, the positions of blocks (i, j) and (j, i) in it (−1 otherwise).
    // Both built at the first call (thread-safe): only the assembled matrices (Newton,
    // linearized, decoupled, local/global) use them, and one int per directed edge is 105 MB at
    // 10⁶ hexahedra; the reduced Newton solver walks the pattern alongside the graph instead.
    const BlockPattern& blockPattern() const { return blockPattern_; }
    const std::vector<int>& edgeBlock() const;
    const std::vector<int>& edgeTransposeBlock() const;

    // Shortest and mean reference edge length (mesh size for tolerances).
    double minimumEdgeLength() const { return minimumEdgeLength_; }
    double meanEdgeLength() const { return meanEdgeLength_; }
    // Shortest reference distance from a node to any of its neighbours (thesis §2.6).
    double shortestNeighbourDistance(int node) const;

    // Sliding constraint in the unknown space. A block vector has blockSize entries per
    // unknown node with the displacement first (blockSize() for the coupled unknowns,
    // dimension() for displacement-only systems). projectSliding first puts every coupled
    // pair's displacements onto u_b = q u_a, orthogonally (a ← (a + qᵀ b)/2, b ← q a; the
    // rotations are left alone), then removes the normal
    // component of every sliding node's displacement (P = I − n nᵀ; on a line
    // P = I − n nᵀ − m̂ m̂ᵀ) and, when the vector
    // holds rotations (blockSize == blockSize()), the in-plane components of a mirror node's
    // rotation (P = n nᵀ there); other rotations and free nodes are untouched.
    void projectSliding(std::span<double> blockVector, int blockSize) const;
    void projectSliding(std::span<double> blockVector) const { projectSliding(blockVector, blockSize()); }
    // The same projection on a matrix in blockPattern() order: H ← P H P + s (I − P), with
    // s the mean displacement diagonal of the node's block, so the matrix stays
    // nonsingular (and symmetric positive definite if it was) and its solutions satisfy
    // (I − P) δ = 0 for projected right-hand sides.
    void projectSlidingBlocks(std::span<double> blockValues, int blockSize) const;
    // The u-part offset c n of every sliding node (c = n·prescribed displacement), zero
    // elsewhere, and q times a's offset at b of every coupled pair: states with u − offset tangential satisfy every sliding constraint.
    void slidingOffset(std::span<const Vector3> prescribedDisplacement, std::span<double> blockVector,
                       int blockSize) const;
    void slidingOffset(std::span<const Vector3> prescribedDisplacement, std::span<double> blockVector) const
    {
        slidingOffset(prescribedDisplacement, blockVector, blockSize());
    }
    bool hasSlidingNodes() const { return slidingNodeCount_ > 0; }

    // Throws std::invalid_argument unless the array has one entry per node.
    void checkNodeArray(std::span<const Vector3> values, std::string_view what) const;

private:
    void build();
    void checkSizes() const;
    void computeSlidingNormals();
    void numberUnknowns();
    void checkUnknownsHeld() const;
    void buildBlockPattern();
    void checkBlockPattern() const;
    void computeEdgeWeights();
    void checkCoupledPair(const CoupledPair& pair, std::vector<char>& paired) const;
    void projectCoupledPairs(std::span<double> blockVector, int blockSize) const;
    // The position of block (b, a) in row b of the pattern, −1 if there is none.
    int reversePosition(int a, int b) const;
    // visit(e, a, b) for every graph edge e = (i → j) with i and j unknown (a, b their indices).
    template <typename Visit>
    void forEachEdgeBetweenUnknowns(Visit&& visit) const;

    int dimension_;
    std::vector<Vector3> referencePoints_;
    std::shared_ptr<const CellNeighbourGraph> graph_;
    std::vector<NodeConstraint> constraints_;
    EdgeWeighting weighting_;

    double plainEdgeWeight(int i, int j) const;  // the weighting's weight, without factors

    std::vector<double> edgeWeights_;
    std::shared_ptr<const std::vector<double>> edgeWeightFactors_;  // null: none
    bool edgeWeightFactorsReleased_ = false;  // releaseEdgeWeightFactors: in the weights only
    // Per node; empty without sliding nodes (two arrays of 25 MB at 10⁶ points for zeros).
    std::vector<Vector3> unitNormals_;
    std::vector<Vector3> secondUnitNormals_;
    static constexpr Vector3 noNormal{};
    std::vector<int> unknownIndex_;
    std::vector<int> unknownNodes_;
    BlockPattern blockPattern_;
    // Per directed edge, a block position and the flag of its one build, shared by copies of
    // the problem (which have the same pattern).
    struct EdgePositions {
        std::once_flag built;
        std::vector<int> positions;
    };
    std::shared_ptr<EdgePositions> edgeBlock_ = std::make_shared<EdgePositions>();
    std::shared_ptr<EdgePositions> edgeTransposeBlock_ = std::make_shared<EdgePositions>();
    double minimumEdgeLength_ = 0.0;
    double meanEdgeLength_ = 0.0;
    int slidingNodeCount_ = 0;
    std::vector<CoupledPair> coupledPairs_;
    ProblemPart part_;
    int ownedUnknownCount_ = 0;
    long long totalUnknownNodeCount_ = 0;
};

// Per-node state: displacements and rotations of ALL nodes (prescribed nodes hold their
// prescribed displacement and a zero rotation). 2D rotations are stored in z (θ, CCW
// positive), 3D rotations as rotation vectors.
struct RbmState {
    std::vector<Vector3> displacement;
    std::vector<Vector3> rotation;
};

// What every RBM variant returns: the state (per node, see RbmState) and how it got there.
struct RbmResult : RbmState {
    int iterations = 0;        // nonlinear iterations (Newton steps, local/global or fixed-point rounds); 1 for a linear solve
    int linearIterations = 0;  // Krylov iterations summed over all linear solves (0 for direct factorisations)
    double energy = 0.0;       // the exact coupled energy E at the result (see RbmEnergy.hpp)
    double residualNorm = 0.0; // the variant's own optimality residual at the result (documented per solver)
    bool converged = false;
    std::string reason;        // why the iteration stopped, e.g. "CONVERGED_FNORM_ABS" or "maximum iterations (500)"
};

// The common interface of the variants. A solver keeps a reference to its problem (which
// must outlive it) and may keep matrices and factorisations between solve() calls.
class RbmSolver {
public:
    virtual ~RbmSolver() = default;
    virtual const RbmProblem& problem() const = 0;
    // Displacements and rotations of every node for the given prescribed displacements (one
    // per node; entries of free nodes are ignored, sliding nodes use their normal component).
    // initialGuess (optional) warm-starts the iterative variants.
    virtual RbmResult solve(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess = nullptr) = 0;
};

// The result for a problem without unknown nodes: the prescribed displacements, zero
// energy, converged ("NO_UNKNOWNS"). Every solver returns it in that case.
RbmResult prescribedOnlyResult(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement);

// Packs the unknown nodes' (u, rotation) into a compact block vector of unknownCount()
// entries, and back (prescribedDisplacement fills the prescribed nodes of the state).
void packUnknowns(const RbmProblem& problem, const RbmState& state, std::span<double> unknowns);
RbmState unpackUnknowns(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement,
                        std::span<const double> unknowns);

} // namespace rbm::motion

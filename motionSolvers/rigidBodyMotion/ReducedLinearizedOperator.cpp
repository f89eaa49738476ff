#include "ReducedLinearizedOperator.hpp"

#include "ThreadCount.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rbm::motion {

namespace {

Vector3 times(const std::array<double, 9>& m, const Vector3& v)
{
    return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[3] * v.x + m[4] * v.y + m[5] * v.z,
            m[6] * v.x + m[7] * v.y + m[8] * v.z};
}

// n nᵀ / (nᵀ M n): the best rotation restricted to the axis n.
std::array<double, 9> axisMap(const std::array<double, 9>& m, const Vector3& n)
{
    const double stiffness = dot(n, times(m, n));
    std::array<double, 9> map{};
    if (!(stiffness > 0.0)) return map;
    for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q) map[3 * p + q] = n[p] * n[q] / stiffness;
    return map;
}

} // namespace

ReducedLinearizedOperator::ReducedLinearizedOperator(const RbmProblem& problem) : problem_(problem)
{
    const CellNeighbourGraph& graph = problem.graph();
    const std::vector<Vector3>& x = problem.referencePoints();
    const std::vector<double>& weights = problem.edgeWeights();
    const bool planar = problem.dimension() == 2;
    const int unknownNodes = problem.unknownNodeCount();
    rotationMaps_.assign(unknownNodes, {});
    workDisplacement_.assign(problem.nodeCount(), Vector3{});
    workRotation_.assign(problem.nodeCount(), Vector3{});

    for (int a = 0; a < unknownNodes; ++a) {
        const int i = problem.unknownNodes()[a];
        // M_i = Σ_j w_ij (|d|² I − d dᵀ): the rotation block H_ωω of node i.
        std::array<double, 9> m{};
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            Vector3 d = x[graph.neighbours[e]] - x[i];
            if (planar) d.z = 0.0;
            const double w = weights[e];
            const double lengthSquared = normSquared(d);
            for (int p = 0; p < 3; ++p)
                for (int q = 0; q < 3; ++q) m[3 * p + q] += w * ((p == q ? lengthSquared : 0.0) - d[p] * d[q]);
        }
        std::array<double, 9>& map = rotationMaps_[a];
        if (planar) {
            map = axisMap(m, Vector3{0.0, 0.0, 1.0});
        } else if (problem.rotatesAboutNormalOnly(i)) {
            map = axisMap(m, problem.slidingNormal(i));
        } else {
            // Symmetric inverse by cofactors.
            const double c00 = m[4] * m[8] - m[5] * m[7];
            const double c01 = m[5] * m[6] - m[3] * m[8];
            const double c02 = m[3] * m[7] - m[4] * m[6];
            const double determinant = m[0] * c00 + m[1] * c01 + m[2] * c02;
            const double scale = (m[0] + m[4] + m[8]) / 3.0;
            if (!(determinant > 1e-12 * scale * scale * scale)) {
                map = {};
            } else {
                map[0] = c00 / determinant;
                map[1] = (m[2] * m[7] - m[1] * m[8]) / determinant;
                map[2] = (m[1] * m[5] - m[2] * m[4]) / determinant;
                map[3] = c01 / determinant;
                map[4] = (m[0] * m[8] - m[2] * m[6]) / determinant;
                map[5] = (m[2] * m[3] - m[0] * m[5]) / determinant;
                map[6] = c02 / determinant;
                map[7] = (m[1] * m[6] - m[0] * m[7]) / determinant;
                map[8] = (m[0] * m[4] - m[1] * m[3]) / determinant;
            }
        }
        bool fixed = false;
        for (double value : map) fixed = fixed || value != 0.0;
        if (!fixed)
            throw std::invalid_argument("RBM problem: the neighbours of node " + std::to_string(i) +
                                        " lie on one line through it, so its rotation is undetermined");
    }
}

void ReducedLinearizedOperator::bestRotations(std::span<const Vector3> displacement, std::span<Vector3> rotation) const
{
    const CellNeighbourGraph& graph = problem_.graph();
    const std::vector<Vector3>& x = problem_.referencePoints();
    const std::vector<double>& weights = problem_.edgeWeights();
    const std::vector<int>& unknownNodes = problem_.unknownNodes();
    const bool planar = problem_.dimension() == 2;
    const int count = problem_.unknownNodeCount();
#pragma omp parallel for schedule(static) if (worthThreading(graph.neighbours.size()))
    for (int a = 0; a < count; ++a) {
        const int i = unknownNodes[a];
        Vector3 b{};
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int j = graph.neighbours[e];
            Vector3 d = x[j] - x[i];
            Vector3 relative = displacement[j] - displacement[i];
            if (planar) d.z = relative.z = 0.0;
            b += weights[e] * cross(d, relative);
        }
        rotation[i] = times(rotationMaps_[a], b);
    }
}

void ReducedLinearizedOperator::gradient(std::span<const Vector3> displacement, std::span<double> gradient) const
{
    problem_.checkNodeArray(displacement, "displacement");
    if (static_cast<int>(gradient.size()) != size())
        throw std::invalid_argument("ReducedLinearizedOperator: the gradient has the wrong size");
    bestRotations(displacement, workRotation_);  // prescribed nodes keep ω = 0: they are no centres

    const CellNeighbourGraph& graph = problem_.graph();
    const std::vector<Vector3>& x = problem_.referencePoints();
    const std::vector<double>& weights = problem_.edgeWeights();
    const std::vector<int>& unknownNodes = problem_.unknownNodes();
    const std::vector<int>& unknownIndex = problem_.unknownIndex();
    const int dimension = problem_.dimension();
    const bool planar = dimension == 2;
    const int count = problem_.unknownNodeCount();
    const std::vector<Vector3>& rotation = workRotation_;
#pragma omp parallel for schedule(static) if (worthThreading(graph.neighbours.size()))
    for (int a = 0; a < count; ++a) {
        const int k = unknownNodes[a];
        Vector3 g{};
        for (int e = graph.offsets[k]; e < graph.offsets[k + 1]; ++e) {
            const int j = graph.neighbours[e];
            Vector3 d = x[j] - x[k];
            Vector3 relative = displacement[k] - displacement[j];
            if (planar) d.z = relative.z = 0.0;
            const double terms = unknownIndex[j] >= 0 ? 2.0 : 1.0;  // as centre k and, if unknown, as centre j
            g += weights[e] * (terms * relative + cross(rotation[k] + rotation[j], d));
        }
        for (int q = 0; q < dimension; ++q) gradient[static_cast<std::size_t>(a) * dimension + q] = g[q];
    }
}

void ReducedLinearizedOperator::apply(std::span<const double> xValues, std::span<double> y) const
{
    if (static_cast<int>(xValues.size()) != size() || static_cast<int>(y.size()) != size())
        throw std::invalid_argument("ReducedLinearizedOperator: apply with vectors of the wrong size");
    const int dimension = problem_.dimension();
    const std::vector<int>& unknownNodes = problem_.unknownNodes();
    const int count = problem_.unknownNodeCount();
    // Prescribed entries of the work array stay zero: S acts on the unknowns alone.
    for (int a = 0; a < count; ++a) {
        Vector3& u = workDisplacement_[unknownNodes[a]];
        for (int q = 0; q < dimension; ++q) u[q] = xValues[static_cast<std::size_t>(a) * dimension + q];
    }
    gradient(workDisplacement_, y);
}

std::vector<double> coupledDisplacementLaplacian(const RbmProblem& problem)
{
    const CellNeighbourGraph& graph = problem.graph();
    const BlockPattern& pattern = problem.blockPattern();
    const std::vector<double>& weights = problem.edgeWeights();
    std::vector<double> values(pattern.blockCount(), 0.0);
    for (int a = 0; a < problem.unknownNodeCount(); ++a) {
        const int k = problem.unknownNodes()[a];
        double diagonal = 0.0;
        // The row's unknown neighbours, in graph order, fill its positions in order around the
        // diagonal (RbmProblem::buildBlockPattern): no per-edge position array is needed.
        int position = pattern.rowOffsets[a];
        for (int e = graph.offsets[k]; e < graph.offsets[k + 1]; ++e) {
            const bool unknown = problem.isUnknown(graph.neighbours[e]);
            diagonal += weights[e] * (unknown ? 2.0 : 1.0);
            if (!unknown) continue;
            if (position == pattern.diagonal[a]) ++position;
            values[position++] = -2.0 * weights[e];
        }
        values[pattern.diagonal[a]] = diagonal;
    }
    return values;
}

std::vector<double> ReducedLinearizedOperator::displacementLaplacianValues() const
{
    return coupledDisplacementLaplacian(problem_);
}

} // namespace rbm::motion

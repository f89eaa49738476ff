#include "ReducedEnergy.hpp"

#include "LocalGlobalSolver.hpp"
#include "NodeExchange.hpp"
#include "PlanarReducedKernels.hpp"
#include "ReducedHessian3D.hpp"
#include "ThreadCount.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace rbm::motion {

ReducedEnergy::ReducedEnergy(const RbmProblem& problem, NeighbourhoodScaling scaling, double transverseStiffness)
    : problem_(problem), transverse_(problem, transverseStiffness)
{
    const int dim = problem.dimension();
    if (dim != 2 && !scaling.rigid())
        throw std::invalid_argument("neighbourhoods that scale (scaling) are implemented for planar (2D and "
                                    "pseudo-2D) cases only; this case is 3D");
    if (dim == 2 && problem.isPart())
        throw std::invalid_argument("the distributed reduced energy is implemented for 3D problems only");
    const CellNeighbourGraph& graph = problem.graph();
    weightSums_.assign(problem.unknownNodeCount(), 0.0);
    weightedLengths_.assign(problem.unknownNodeCount(), 0.0);
    for (int a = 0; a < problem.unknownNodeCount(); ++a) {
        const int i = problem.unknownNodes()[a];
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            Vector3 d = problem.referencePoints()[graph.neighbours[e]] - problem.referencePoints()[i];
            if (dim == 2) d.z = 0.0;
            weightSums_[a] += problem.edgeWeights()[e];
            weightedLengths_[a] += problem.edgeWeights()[e] * norm(d);
        }
    }
    if (problem.totalUnknownNodeCount() == 0) return;
    if (dim == 2) planar_ = std::make_unique<PlanarReducedKernels>(problem, scaling);
    else hessian3D_ = std::make_unique<ReducedHessian3D>(problem);
}

ReducedEnergy::~ReducedEnergy() = default;

double ReducedEnergy::sumOverRanks(double value) const
{
    const NodeExchange* exchange = problem_.nodeExchange();
    return exchange ? exchange->sum(value) : value;
}

bool ReducedEnergy::setTranslation(const Vector3& direction)
{
    transverse_.setDirection(direction);
    return transverse_.active();
}

double ReducedEnergy::fitAndEnergy(std::span<const Vector3> displacement, std::vector<Matrix3>& rotations) const
{
    if (planar_) return planar_->fitAndEnergy(displacement, rotations) + transverse_.energy(displacement);
    fitNodeRotations(problem_, displacement, rotations);
    const CellNeighbourGraph& graph = problem_.graph();
    const std::vector<Vector3>& x = problem_.referencePoints();
    const std::vector<int>& nodes = problem_.unknownNodes();
    const int m = problem_.ownedUnknownCount();  // a part sums its owned nodes' terms
    const bool planar = problem_.dimension() == 2;
    std::vector<double> nodeEnergy(static_cast<std::size_t>(m));
#pragma omp parallel for schedule(static) if (worthThreading(graph.neighbours.size()))
    for (int a = 0; a < m; ++a) {
        const int i = nodes[a];
        double sum = 0.0;
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int j = graph.neighbours[e];
            Vector3 d = x[j] - x[i];
            Vector3 relative = displacement[j] - displacement[i];
            if (planar) d.z = relative.z = 0.0;
            sum += problem_.edgeWeights()[e] * normSquared(relative + d - rotations[i] * d);
        }
        nodeEnergy[a] = sum;
    }
    double sum = 0.0;
    for (double value : nodeEnergy) sum += value;
    return 0.5 * sumOverRanks(sum) + transverse_.energy(displacement);
}

void ReducedEnergy::gradient(std::span<const Vector3> displacement, std::span<const Matrix3> rotations,
                                   std::span<double> g) const
{
    if (planar_) {
        planar_->gradient(displacement, rotations, g);
        transverse_.addGradient(displacement, g);
        problem_.projectSliding(g, problem_.dimension());
        return;
    }
    const CellNeighbourGraph& graph = problem_.graph();
    const std::vector<Vector3>& x = problem_.referencePoints();
    const std::vector<int>& nodes = problem_.unknownNodes();
    const int m = problem_.ownedUnknownCount();  // a part's ghost rows are their owners'
    const int dim = problem_.dimension();
    const bool planar = dim == 2;
    std::fill(g.begin() + static_cast<std::ptrdiff_t>(m) * dim, g.end(), 0.0);
#pragma omp parallel for schedule(static) if (worthThreading(graph.neighbours.size()))
    for (int a = 0; a < m; ++a) {
        const int k = nodes[a];
        Vector3 sum{};
        for (int e = graph.offsets[k]; e < graph.offsets[k + 1]; ++e) {
            const int j = graph.neighbours[e];
            Vector3 d = x[j] - x[k];
            Vector3 relative = displacement[k] - displacement[j];
            if (planar) d.z = relative.z = 0.0;
            const bool unknown = problem_.isUnknown(j);
            Vector3 term = (unknown ? 2.0 : 1.0) * (relative - d) + rotations[k] * d;
            if (unknown) term += rotations[j] * d;
            sum += problem_.edgeWeights()[e] * term;
        }
        for (int q = 0; q < dim; ++q) g[static_cast<std::size_t>(a) * dim + q] = sum[q];
    }
    transverse_.addGradient(displacement, g);
    problem_.projectSliding(g, dim);
}

void ReducedEnergy::prepareHessian(std::span<const Vector3> displacement, std::span<const Matrix3> rotations)
{
    if (planar_) {
        planar_->prepareHessian(displacement, rotations);
        return;
    }
    hessian3D_->prepare(displacement, rotations);
}

void ReducedEnergy::releaseHessian()
{
    if (hessian3D_) hessian3D_->release();
    std::vector<double>().swap(projected_);
}

void ReducedEnergy::applyHessian(std::span<const double> v, std::span<double> y)
{
    const int dim = problem_.dimension();
    std::vector<double>& projected = projected_;
    if (hessian3D_) {
        hessian3D_->apply(v, y);  // projects onto sliding planes itself
        if (!transverse_.active()) return;
        projected.assign(v.begin(), v.end());
        problem_.projectSliding(projected, dim);
        std::vector<double> added(y.size(), 0.0);
        transverse_.addHessianProduct(projected, added);
        problem_.projectSliding(added, dim);
        for (std::size_t k = 0; k < y.size(); ++k) y[k] += added[k];
        return;
    }
    projected.assign(v.begin(), v.end());
    problem_.projectSliding(projected, dim);
    planar_->applyHessian(projected, y);
    transverse_.addHessianProduct(projected, y);
    problem_.projectSliding(y, dim);
}

double ReducedEnergy::gradientRoundoffNorm(std::span<const Vector3> displacement)
{
    const int n = problem_.nodeCount();
    const int m = problem_.ownedUnknownCount();
    const int dim = problem_.dimension();
    const std::vector<int>& nodes = problem_.unknownNodes();
    const CellNeighbourGraph& graph = problem_.graph();
    // |u| once per node, then per unknown node |u_i| Σ_j w + Σ_j w |u_j| + Σ_j w |d|.
    // Local: not alive through the CG that follows (the solve's peak).
    std::vector<double> nodeNorms(static_cast<std::size_t>(n)), magnitudes(static_cast<std::size_t>(m));
    for (int node = 0; node < n; ++node) nodeNorms[node] = norm(displacement[node]);
#pragma omp parallel for schedule(static) if (worthThreading(graph.neighbours.size()))
    for (int a = 0; a < m; ++a) {
        const int i = nodes[a];
        double neighbourNorms = 0.0;
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e)
            neighbourNorms += problem_.edgeWeights()[e] * nodeNorms[graph.neighbours[e]];
        magnitudes[a] = nodeNorms[i] * weightSums_[a] + neighbourNorms + weightedLengths_[a];
    }
    double sum = 0.0;
    for (double magnitude : magnitudes) sum += dim * magnitude * magnitude;
    return std::numeric_limits<double>::epsilon() * std::sqrt(sumOverRanks(sum));
}

} // namespace rbm::motion

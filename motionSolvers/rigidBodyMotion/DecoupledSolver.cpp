#include "DecoupledSolver.hpp"

#include "RbmEnergy.hpp"
#include "ThreadCount.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace rbm::motion {

namespace {

// a_k = ∂(R d)/∂θ_k at R = I: 2D e_z × d, 3D e_k × d (eqs 2.48, 2.92).
int smallAngleDirections(int dimension, const Vector3& d, std::array<Vector3, 3>& directions)
{
    if (dimension == 2) {
        directions[0] = {-d.y, d.x, 0.0};
        return 1;
    }
    directions[0] = cross({1.0, 0.0, 0.0}, d);
    directions[1] = cross({0.0, 1.0, 0.0}, d);
    directions[2] = cross({0.0, 0.0, 1.0}, d);
    return 3;
}

LaggedRotationIteration::Options iterationOptions(const DecoupledOptions& options)
{
    LaggedRotationIteration::Options result;
    result.linearSolver = options.linearSolver;
    result.linearRelativeTolerance = options.linearRelativeTolerance;
    result.maximumIterations = options.maximumIterations;
    result.displacementTolerance = options.displacementTolerance;
    result.accelerationDepth = options.accelerationDepth;
    return result;
}

} // namespace

DecoupledSolver::DecoupledSolver(const RbmProblem& problem, DecoupledOptions options)
    : problem_(problem), options_(options)
{
    if (options.model == DecoupledModel::nonlinear) {
        iteration_ = std::make_unique<LaggedRotationIteration>(problem, LaplacianForm::decoupled,
                                                               iterationOptions(options), "decoupled");
        return;
    }
    // Linearized: row block i holds ∂F_i/∂(u_i, θ_i) = 0 with
    //   r_ij = u_j − u_i − Σ_k θ_ik a_k(d_ij):
    //   [Σ w I,  Σ w a_l ] (u_i)     Σ_{j unknown} [w I ] u_j   =   Σ_{j prescribed} [w ū_j     ]
    //   [Σ w a_kᵀ, Σ w a_k·a_l] (θ_i) −             [w a_kᵀ]            ...         [w a_k·ū_j ]
    // Columns of the neighbours' rotations are zero: their rotation does not enter F_i.
    const BlockPattern& pattern = problem.blockPattern();
    const CellNeighbourGraph& graph = problem.graph();
    const int dim = problem.dimension();
    const int bs = problem.blockSize();
    const std::size_t area = static_cast<std::size_t>(bs) * bs;
    linearBlocks_.assign(area * pattern.blockCount(), 0.0);
    const int unknownNodeCount = problem.unknownNodeCount();
    // Row block i gets only centre i's terms: threads write only their own rows.
#pragma omp parallel for schedule(static) if (worthThreading(graph.neighbours.size()))
    for (int row = 0; row < unknownNodeCount; ++row) {
        std::array<Vector3, 3> a;
        const int i = problem.unknownNodes()[row];
        double* diagonal = linearBlocks_.data() + area * pattern.diagonal[row];
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const double w = problem.edgeWeights()[e];
            Vector3 d = problem.referencePoints()[graph.neighbours[e]] - problem.referencePoints()[i];
            if (dim == 2) d.z = 0.0;
            const int count = smallAngleDirections(dim, d, a);
            for (int q = 0; q < dim; ++q) diagonal[q * bs + q] += w;
            for (int k = 0; k < count; ++k) {
                for (int q = 0; q < dim; ++q) {
                    diagonal[q * bs + dim + k] += w * a[k][q];
                    diagonal[(dim + k) * bs + q] += w * a[k][q];
                }
                for (int l = 0; l < count; ++l) diagonal[(dim + k) * bs + dim + l] += w * dot(a[k], a[l]);
            }
            const int block = problem.edgeBlock()[e];
            if (block < 0) continue;
            double* offDiagonal = linearBlocks_.data() + area * block;
            for (int q = 0; q < dim; ++q) offDiagonal[q * bs + q] -= w;
            for (int k = 0; k < count; ++k)
                for (int q = 0; q < dim; ++q) offDiagonal[(dim + k) * bs + q] -= w * a[k][q];
        }
    }
    linearSystem_ = std::make_unique<BlockSystemSolver>(pattern.rowOffsets, pattern.columns, bs, MatrixSymmetry::general,
                                                        options.linearSolver, dim, options.linearRelativeTolerance,
                                                        "decoupled");
    std::vector<double> projected = linearBlocks_;
    problem.projectSlidingBlocks(projected, bs);
    linearSystem_->setMatrix(projected);
}

RbmResult DecoupledSolver::solve(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess)
{
    if (problem_.unknownNodeCount() == 0) return prescribedOnlyResult(problem_, prescribedDisplacement);
    if (iteration_) return iteration_->run(prescribedDisplacement, initialGuess);
    return solveLinearized(prescribedDisplacement, initialGuess);
}

RbmResult DecoupledSolver::solveLinearized(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess)
{
    problem_.checkNodeArray(prescribedDisplacement, "prescribed displacement");
    const BlockPattern& pattern = problem_.blockPattern();
    const CellNeighbourGraph& graph = problem_.graph();
    const int dim = problem_.dimension();
    const int bs = problem_.blockSize();
    const std::size_t area = static_cast<std::size_t>(bs) * bs;
    const std::size_t size = static_cast<std::size_t>(problem_.unknownCount());

    // b: the prescribed neighbours' terms.
    std::vector<double> b(size, 0.0);
    const int unknownNodeCount = problem_.unknownNodeCount();
#pragma omp parallel for schedule(static) if (worthThreading(graph.neighbours.size()))
    for (int row = 0; row < unknownNodeCount; ++row) {
        std::array<Vector3, 3> a;
        const int i = problem_.unknownNodes()[row];
        double* bi = b.data() + static_cast<std::size_t>(row) * bs;
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int j = graph.neighbours[e];
            if (problem_.isUnknown(j)) continue;
            const double w = problem_.edgeWeights()[e];
            Vector3 d = problem_.referencePoints()[j] - problem_.referencePoints()[i];
            Vector3 given = prescribedDisplacement[j];
            if (dim == 2) {
                d.z = 0.0;
                given.z = 0.0;
            }
            const int count = smallAngleDirections(dim, d, a);
            for (int q = 0; q < dim; ++q) bi[q] += w * given[q];
            for (int k = 0; k < count; ++k) bi[dim + k] += w * dot(a[k], given);
        }
    }
    auto multiply = [&](const std::vector<double>& z, std::vector<double>& out) {  // out = A z (unprojected)
        std::fill(out.begin(), out.end(), 0.0);
#pragma omp parallel for schedule(static) if (worthThreading(static_cast<std::size_t>(pattern.blockCount())))
        for (int row = 0; row < pattern.rowCount(); ++row)
            for (int position = pattern.rowOffsets[row]; position < pattern.rowOffsets[row + 1]; ++position) {
                const double* block = linearBlocks_.data() + area * position;
                const double* zc = z.data() + static_cast<std::size_t>(pattern.columns[position]) * bs;
                double* o = out.data() + static_cast<std::size_t>(row) * bs;
                for (int p = 0; p < bs; ++p)
                    for (int q = 0; q < bs; ++q) o[p] += block[p * bs + q] * zc[q];
            }
    };

    // z = z0 + v: z0 the sliding offsets, v tangential with (P A P + s(I−P)) v = P (b − A z0).
    std::vector<double> start(size, 0.0), product(size), rhs(size);
    problem_.slidingOffset(prescribedDisplacement, start);
    multiply(start, product);
    for (std::size_t k = 0; k < size; ++k) rhs[k] = b[k] - product[k];
    problem_.projectSliding(rhs);
    std::vector<double> step(size, 0.0);
    const bool useGuess = initialGuess != nullptr && !linearSystem_->isDirect();
    if (useGuess) {
        packUnknowns(problem_, *initialGuess, step);
        for (std::size_t k = 0; k < size; ++k) step[k] -= start[k];
        problem_.projectSliding(step);
    }
    const BlockSystemSolver::Report report = linearSystem_->solve(rhs, step, useGuess);
    problem_.projectSliding(step);
    for (std::size_t k = 0; k < size; ++k) start[k] += step[k];

    RbmResult result;
    static_cast<RbmState&>(result) = unpackUnknowns(problem_, prescribedDisplacement, start);
    result.iterations = 1;
    result.linearIterations = report.iterations;
    result.converged = report.converged;
    result.reason = report.reason;
    multiply(start, product);
    for (std::size_t k = 0; k < size; ++k) product[k] -= b[k];
    problem_.projectSliding(product);
    double sum = 0.0;
    for (double value : product) sum += value * value;
    result.residualNorm = std::sqrt(sum);
    result.energy = RbmEnergy(problem_, RotationModel::exact, prescribedDisplacement).value(start);
    return result;
}

} // namespace rbm::motion

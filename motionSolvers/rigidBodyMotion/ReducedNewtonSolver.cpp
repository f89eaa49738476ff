#include "ReducedNewtonSolver.hpp"

#include "BacktrackingLineSearch.hpp"
#include "BlockRowLayout.hpp"
#include "ConjugateGradients.hpp"
#include "GramSchmidt.hpp"
#include "LocalGlobalSolver.hpp"
#include "PlanarReducedKernels.hpp"
#include "ReducedHessian3D.hpp"
#include "ThreeVectorMultigrid.hpp"
#include "ReducedLinearizedOperator.hpp"
#include "SparseCholesky.hpp"
#include "ThreadCount.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace rbm::motion {

ReducedNewtonSolver::ReducedNewtonSolver(const RbmProblem& problem, ReducedNewtonOptions options)
    : problem_(problem), options_(options), reducedEnergy_(problem),
      preconditioner_(problem, options.linearSolver, options.laplacianRelativeTolerance)
{
    const int n = problem.nodeCount();
    const int dim = problem.dimension();
    const CellNeighbourGraph& graph = problem.graph();
    absoluteTolerance_ = options.absoluteTolerance;
    if (absoluteTolerance_ < 0.0) {
        // CoupledNewtonSolver's default: about 1e-11 of a cell per node.
        double sum = 0.0;
        for (int i = 0; i < n; ++i)
            for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
                Vector3 d = problem.referencePoints()[graph.neighbours[e]] - problem.referencePoints()[i];
                if (dim == 2) d.z = 0.0;
                sum += problem.edgeWeights()[e] * norm(d);
            }
        const double meanWeightedLength = graph.edgeCount() > 0 ? sum / graph.edgeCount() : 1.0;
        absoluteTolerance_ = 1e-11 * meanWeightedLength * std::sqrt(std::max(1, problem.unknownNodeCount()));
    }
    {
        PetscInt memory = options_.correctionMemory;
        RBM_CHECK_PETSC(PetscOptionsGetInt(nullptr, "rbm_reduced_", "-correction_memory", &memory, nullptr));
        options_.correctionMemory = std::max<int>(0, static_cast<int>(memory));
        PetscBool harmonicBasis = options_.harmonicBasis ? PETSC_TRUE : PETSC_FALSE;
        RBM_CHECK_PETSC(PetscOptionsGetBool(nullptr, "rbm_reduced_", "-harmonic_basis", &harmonicBasis, nullptr));
        options_.harmonicBasis = harmonicBasis == PETSC_TRUE;
    }
    // Only the displacement test needs the nodes' shortest edges.
    if (options.displacementTolerance > 0.0) inverseShortestEdge_.assign(problem.unknownNodeCount(), 0.0);
    for (int a = 0; a < static_cast<int>(inverseShortestEdge_.size()); ++a) {
        const int i = problem.unknownNodes()[a];
        double shortest = std::numeric_limits<double>::infinity();
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            Vector3 d = problem.referencePoints()[graph.neighbours[e]] - problem.referencePoints()[i];
            if (dim == 2) d.z = 0.0;
            if (norm(d) > 0.0) shortest = std::min(shortest, norm(d));
        }
        inverseShortestEdge_[a] = std::isfinite(shortest) ? 1.0 / shortest : 0.0;
    }
    if (dim == 3) {
        // 3D: Eisenstat–Walker's exponent (1 + √5)/2 instead of 2 (PETSc's SNES default), and the
        // last step solved to 0.2 instead of 0.1 of the final tolerance. On the twisted 10⁶-cell
        // hexahedral cube the squared ratio oversolved every step: ‖∇Ẽ‖ fell by 0.057, 0.028 and
        // 0.0039 where CG had been asked for 0.0079, 0.0029 and 0.00068 (the nonlinearity, not
        // the linear solve, limited the step). CG iterations 59 → 50 (4 9 12 14 20 → 4 8 10 12 16),
        // still 5 Newton steps, the same energy to 5e-14; at 10⁵ cells 50 → 45.
        forcingExponent_ = 0.5 * (1.0 + std::sqrt(5.0));
        finalForcingFactor_ = 0.2;
    }
}

ReducedNewtonSolver::~ReducedNewtonSolver() = default;

double ReducedNewtonSolver::largestRelativeDisplacement(std::span<const double> v) const
{
    const int dim = problem_.dimension();
    double largest = 0.0;
    for (int a = 0; a < problem_.unknownNodeCount(); ++a) {
        double squared = 0.0;
        for (int q = 0; q < dim; ++q) squared += v[static_cast<std::size_t>(a) * dim + q] * v[static_cast<std::size_t>(a) * dim + q];
        largest = std::max(largest, std::sqrt(squared) * inverseShortestEdge_[a]);
    }
    return largest;
}

bool ReducedNewtonSolver::newtonDirection(std::span<const double> g, double forcing,
                                          const std::vector<double>* firstPreconditioned, std::span<double> step,
                                          int& iterations, bool& negativeCurvature)
{
    // Flexible (Polak–Ribière) preconditioned CG, so that an iterative K⁻¹ is allowed too.
    const std::size_t size = g.size();
    // Work vectors kept between calls (no allocation and page faults per Newton step).
    std::vector<double>& r = cgResidual_;
    std::vector<double>& z = cgPreconditioned_;
    std::vector<double>& previousZ = cgPreviousPreconditioned_;
    std::vector<double>& p = cgDirection_;
    std::vector<double>& sp = cgProduct_;
    for (std::vector<double>* work : {&r, &z, &previousZ, &p, &sp}) work->resize(size);
    for (std::size_t k = 0; k < size; ++k) r[k] = -g[k];
    std::fill(step.begin(), step.end(), 0.0);
    const double target = forcing * euclideanNorm(g);
    if (firstPreconditioned) z = *firstPreconditioned;
    else if (!preconditioner_.apply(r, z)) return false;
    p = z;
    // The step is good enough once K⁻¹ of its residual, the gradient it leaves to first order,
    // is half the displacement tolerance: the next Newton iteration then stops.
    const double displacementTarget = 0.5 * options_.displacementTolerance;
    double rz = dotProduct(r, z);
    negativeCurvature = false;
    for (int iteration = 0; iteration < options_.maximumLinearIterations; ++iteration) {
        reducedEnergy_.applyHessian(p, sp);
        const double curvature = dotProduct(p, sp);
        if (!(curvature > 0.0)) {
            // Steihaug: stop at a direction of negative curvature. With nothing yet, the
            // preconditioned gradient −K⁻¹∇Ẽ (a local/global step).
            negativeCurvature = true;
            if (iteration == 0) std::copy(z.begin(), z.end(), step.begin());
            return true;
        }
        const double alpha = rz / curvature;
        for (std::size_t k = 0; k < size; ++k) {
            step[k] += alpha * p[k];
            r[k] -= alpha * sp[k];
        }
        ++iterations;
        if (euclideanNorm(r) <= target) return true;
        previousZ.swap(z);
        if (!preconditioner_.apply(r, z)) return false;
        if (displacementTarget > 0.0 && largestRelativeDisplacement(z) <= displacementTarget) return true;
        double numerator = 0.0;
        for (std::size_t k = 0; k < size; ++k) numerator += r[k] * (z[k] - previousZ[k]);
        const double beta = std::max(0.0, numerator / rz);
        rz = dotProduct(r, z);
        for (std::size_t k = 0; k < size; ++k) p[k] = z[k] + beta * p[k];
    }
    return true;  // the iteration limit: the step so far still is a descent direction
}

bool ReducedNewtonSolver::turnedHarmonicStart(std::span<const Vector3> prescribedDisplacement, std::vector<Vector3>& u,
                                              std::span<const Vector3> base)
{
    // One rank, no sliding nodes, K factorised by rbm or its 3D multigrid cycle; every prescribed
    // node either fixed (no change) or moved by one rigid motion y = R (x − c) + c', fitted here
    // (2D: the best angle; 3D: Kabsch). x: the reference positions, or those displaced by base.
    if (!preconditioner_.hasScalarSolve()) return false;
    const int dim = problem_.dimension();
    const int n = problem_.nodeCount();
    auto flat = [dim](Vector3 v) {
        if (dim == 2) v.z = 0.0;
        return v;
    };
    std::vector<Vector3> x = problem_.referencePoints();
    std::vector<Vector3> change(prescribedDisplacement.begin(), prescribedDisplacement.end());
    if (!base.empty()) {
        for (int node = 0; node < n; ++node) {
            x[node] += flat(base[node]);
            change[node] = flat(change[node]) - flat(base[node]);
        }
    }
    prescribedDisplacement = change;  // from here on: the change since x
    auto moves = [&](int node) {
        const Vector3 d = flat(prescribedDisplacement[node]);
        return d.x != 0.0 || d.y != 0.0 || d.z != 0.0;
    };
    Vector3 centre{}, moved{};
    int count = 0;
    for (int node = 0; node < n; ++node) {
        if (problem_.isUnknown(node) || !moves(node)) continue;
        centre += flat(x[node]);
        moved += flat(x[node] + prescribedDisplacement[node]);
        ++count;
    }
    if (count < dim) return false;
    centre /= static_cast<double>(count);
    moved /= static_cast<double>(count);
    double crossSum = 0.0, dotSum = 0.0, size = 0.0;
    Matrix3 covariance{};  // Σ b aᵀ, a = x − c, b = y − c'
    for (int node = 0; node < n; ++node) {
        if (problem_.isUnknown(node) || !moves(node)) continue;
        const Vector3 a = flat(x[node]) - centre;
        const Vector3 b = flat(x[node] + prescribedDisplacement[node]) - moved;
        crossSum += a.x * b.y - a.y * b.x;
        dotSum += a.x * b.x + a.y * b.y;
        for (int row = 0; row < 3; ++row)
            for (int column = 0; column < 3; ++column) covariance.m[row][column] += b[row] * a[column];
        size = std::max(size, norm(a));
    }
    // The turn as a rotation vector ω (R = exp([ω]×)).
    Matrix3 rotation;
    Vector3 turn{};
    if (dim == 2) {
        const double angle = std::atan2(crossSum, dotSum);
        rotation = planarRotation(angle);
        turn = {0.0, 0.0, angle};
    } else {
        rotation = bestRotation(covariance);
        turn = rotationVectorFromMatrix(rotation);
        // Near a half turn the axis (and the sense of the interpolation) is ambiguous.
        if (norm(turn) > 0.99 * std::numbers::pi) return false;
    }
    for (int node = 0; node < n; ++node) {
        if (problem_.isUnknown(node) || !moves(node)) continue;
        const Vector3 target = flat(x[node] + prescribedDisplacement[node]);
        if (norm(rotation * (flat(x[node]) - centre) + moved - target) > 1e-9 * std::max(size, 1e-300))
            return false;  // not one rigid motion
    }
    // s: harmonic, 1 on the moving nodes, 0 on the fixed ones (K s = b, b_a = Σ_moving w).
    const CellNeighbourGraph& graph = problem_.graph();
    const std::vector<int>& nodes = problem_.unknownNodes();
    const int m = problem_.unknownNodeCount();
    std::vector<double> b(static_cast<std::size_t>(m), 0.0), share(static_cast<std::size_t>(m));
    for (int a = 0; a < m; ++a) {
        const int i = nodes[a];
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int j = graph.neighbours[e];
            if (!problem_.isUnknown(j) && moves(j)) b[a] += problem_.edgeWeights()[e];
        }
    }
    if (!preconditioner_.solveScalar(b, share)) return false;
    for (int a = 0; a < m; ++a) {
        const int i = nodes[a];
        const Vector3 offset = flat(x[i]) - centre;
        const Vector3 turned = rotationFromVector(share[a] * turn) * offset;
        u[i] = flat(turned + centre + share[a] * (moved - centre) - flat(problem_.referencePoints()[i]));
    }
    return true;
}

namespace {

// The prescribed change b − u_0 and the differences u_0 − u_j (j ≥ 1) on the prescribed nodes,
// flattened (2D: in-plane components only).
struct BoundaryDifferences {
    std::vector<double> target;
    std::vector<std::vector<double>> columns;
};

BoundaryDifferences boundaryDifferences(const RbmProblem& problem, std::span<const Vector3> prescribed,
                                        const std::vector<std::vector<Vector3>>& history)
{
    const int dim = problem.dimension();
    BoundaryDifferences d;
    d.columns.resize(history.size() - 1);
    for (int node = 0; node < problem.nodeCount(); ++node) {
        if (problem.isUnknown(node)) continue;
        for (int q = 0; q < dim; ++q) {
            d.target.push_back(prescribed[node][q] - history[0][node][q]);
            for (std::size_t j = 1; j < history.size(); ++j) d.columns[j - 1].push_back(history[0][node][q] - history[j][node][q]);
        }
    }
    return d;
}

} // namespace

std::vector<double> ReducedNewtonSolver::bestPredictorOnBoundary(std::span<const Vector3> prescribedDisplacement,
                                                                 std::vector<double> secant) const
{
    // Candidates c (G = u_0 + Σ_j c_j (u_0 − u_j)): the clamped secant; each older result j alone,
    // c_j fitted; all together by least squares (orthonormalise: a nearly dependent column is
    // left out, as a result repeated at a reversal gives a zero difference). Every c_j clamped
    // to ±2. The smallest misfit |b − G| on the prescribed nodes wins; within 1e-9 of it, the candidate
    // that extrapolates least (the smallest largest |c_j|): where the boundary moves along one
    // fixed field, every candidate fits it exactly and the nearest result is the right start.
    const BoundaryDifferences d = boundaryDifferences(problem_, prescribedDisplacement, solutionHistory_);
    const std::size_t columns = d.columns.size();
    std::vector<std::vector<double>> candidates;
    secant.resize(columns, 0.0);
    candidates.push_back(std::move(secant));
    for (std::size_t j = 1; j < columns; ++j) {
        const double squared = dotProduct(d.columns[j], d.columns[j]);
        if (!(squared > 0.0)) continue;
        std::vector<double> alone(columns, 0.0);
        alone[j] = std::clamp(dotProduct(d.target, d.columns[j]) / squared, -2.0, 2.0);
        candidates.push_back(std::move(alone));
    }
    const auto [basis, r, kept] = orthonormalise(d.columns);
    std::vector<double> all(columns, 0.0);
    for (std::size_t i = basis.size(); i-- > 0;) {  // R c = Qᵀ target, R upper triangular
        double value = dotProduct(basis[i], d.target);
        for (std::size_t l = i + 1; l < basis.size(); ++l) value -= r[l][i] * all[kept[l]];
        all[kept[i]] = value / r[i][i];
    }
    for (double& c : all) c = std::clamp(c, -2.0, 2.0);
    candidates.push_back(std::move(all));

    auto misfit = [&](const std::vector<double>& c) {
        std::vector<double> left = d.target;
        for (std::size_t j = 0; j < columns; ++j)
            if (c[j] != 0.0)
                for (std::size_t k = 0; k < left.size(); ++k) left[k] -= c[j] * d.columns[j][k];
        return euclideanNorm(left);
    };
    auto reach = [](const std::vector<double>& c) {
        double largest = 0.0;
        for (double value : c) largest = std::max(largest, std::abs(value));
        return largest;
    };
    std::vector<double> misfits;
    double best = std::numeric_limits<double>::infinity();
    for (const std::vector<double>& c : candidates) {
        misfits.push_back(misfit(c));
        best = std::min(best, misfits.back());
    }
    const double scale = euclideanNorm(d.target);
    std::size_t chosen = 0;
    bool found = false;
    for (std::size_t k = 0; k < candidates.size(); ++k) {
        if (misfits[k] > best + 1e-9 * scale) continue;
        if (!found || reach(candidates[k]) < reach(candidates[chosen])) chosen = k;
        found = true;
    }
    return candidates[chosen];
}

bool ReducedNewtonSolver::harmonicChangeFromBasis(std::span<const Vector3> prescribed, std::span<const Vector3> base,
                                                  std::vector<double>& boundaryChange, std::vector<double>& correction)
{
    boundaryChange.clear();
    // Only where K⁻¹ is one fixed linear map (a factorisation, or the 3D cycle without sliding
    // nodes, not an inner iteration) and the boundary enters b linearly (no sliding offsets),
    // and where the kept extensions stay small against the problem (12 of them).
    const int dim = problem_.dimension();
    const std::size_t size = static_cast<std::size_t>(problem_.unknownNodeCount()) * dim;
    const bool linear = preconditioner_.isFixedLinearMap();
    if (!options_.harmonicBasis || !linear || problem_.hasSlidingNodes() || size > maximumHarmonicBasisEntries)
        return false;
    if (prescribedNodes_.empty())
        for (int node = 0; node < problem_.nodeCount(); ++node)
            if (!problem_.isUnknown(node)) prescribedNodes_.push_back(node);
    boundaryChange.resize(prescribedNodes_.size() * dim);
    double scale = 0.0;  // |new| + |base| on the prescribed nodes
    {
        double newSquared = 0.0, baseSquared = 0.0;
        for (std::size_t p = 0; p < prescribedNodes_.size(); ++p)
            for (int q = 0; q < dim; ++q) {
                const double value = prescribed[prescribedNodes_[p]][q], guess = base[prescribedNodes_[p]][q];
                boundaryChange[p * dim + q] = value - guess;
                newSquared += value * value;
                baseSquared += guess * guess;
            }
        scale = std::sqrt(newSquared) + std::sqrt(baseSquared);
    }
    // A change at the rounding level of the displacements (the predictor at a reversal of the
    // motion reproduces an earlier boundary): no correction, and no noise kept as a direction.
    const double changeNorm = euclideanNorm(boundaryChange);
    if (changeNorm <= roundingChangeShare * scale) {
        correction.assign(size, 0.0);
        ++correctionsFromHarmonicBasis_;
        return true;
    }
    // The change's coordinates in the orthonormal basis of the changes met before, and what is
    // left outside it (two Gram–Schmidt passes: the part left can be small against the change).
    std::vector<double> left = boundaryChange;
    std::vector<double> coordinates(boundaryBasis_.size(), 0.0);
    for (int pass = 0; pass < 2; ++pass)
        for (std::size_t i = 0; i < boundaryBasis_.size(); ++i) {
            const double c = dotProduct(boundaryBasis_[i], left);
            coordinates[i] += c;
            for (std::size_t k = 0; k < left.size(); ++k) left[k] -= c * boundaryBasis_[i][k];
        }
    if (euclideanNorm(left) > harmonicBasisTolerance * changeNorm) return false;
    correction.assign(size, 0.0);
    for (std::size_t i = 0; i < boundaryBasis_.size(); ++i)
        for (std::size_t k = 0; k < size; ++k) correction[k] += coordinates[i] * harmonicBasis_[i][k];
    ++correctionsFromHarmonicBasis_;
    return true;
}

void ReducedNewtonSolver::rememberHarmonicChange(std::vector<double> boundaryChange, std::span<const double> correction)
{
    if (boundaryChange.empty() || boundaryBasis_.size() >= maximumHarmonicBasisSize) return;
    // The part of the change outside the basis, normed, and K⁻¹ B of it: the same combination
    // of `correction` (K⁻¹ B of the whole change) and the kept extensions.
    std::vector<double> extension(correction.begin(), correction.end());
    for (int pass = 0; pass < 2; ++pass)
        for (std::size_t i = 0; i < boundaryBasis_.size(); ++i) {
            const double c = dotProduct(boundaryBasis_[i], boundaryChange);
            for (std::size_t k = 0; k < boundaryChange.size(); ++k) boundaryChange[k] -= c * boundaryBasis_[i][k];
            for (std::size_t k = 0; k < extension.size(); ++k) extension[k] -= c * harmonicBasis_[i][k];
        }
    const double leftNorm = euclideanNorm(boundaryChange);
    if (!(leftNorm > 0.0)) return;
    for (double& value : boundaryChange) value /= leftNorm;
    for (double& value : extension) value /= leftNorm;
    boundaryBasis_.push_back(std::move(boundaryChange));
    harmonicBasis_.push_back(std::move(extension));
}

namespace {
// A subspace step, or a correction kept for it, matters when it moves some node by more than
// this many displacement tolerances of its shortest edge (below, the displacement test and
// Newton finish more cheaply; at a reversal of the motion the predictor is the solution).
constexpr double significantCorrection = 10.0;
} // namespace

int ReducedNewtonSolver::subspaceStep(std::vector<Vector3>& u, std::vector<Matrix3>& rotations, double& energy,
                                      std::vector<double>& g, const TrialMove& moveAlong, std::vector<Vector3>& trial,
                                      std::vector<Matrix3>& trialRotations, bool monitor)
{
    // An orthonormal basis of the corrections; nearly dependent ones are left out.
    const std::vector<std::vector<double>> basis = orthonormalise(recentCorrections_).basis;
    const int k = static_cast<int>(basis.size());
    if (k == 0) return 0;
    // A = Wᵀ S W and b = −Wᵀ ∇Ẽ; A by Cholesky (k ≤ a few), given up unless positive definite.
    reducedEnergy_.prepareHessian(u, rotations);
    std::vector<double> product(g.size());
    std::vector<double> a(static_cast<std::size_t>(k) * k), b(static_cast<std::size_t>(k));
    for (int j = 0; j < k; ++j) {
        reducedEnergy_.applyHessian(basis[j], product);
        for (int i = 0; i < k; ++i) a[static_cast<std::size_t>(i) * k + j] = dotProduct(basis[i], product);
        b[j] = -dotProduct(basis[j], g);
    }
    for (int i = 0; i < k; ++i)
        for (int j = 0; j < i; ++j) a[static_cast<std::size_t>(i) * k + j] = a[static_cast<std::size_t>(j) * k + i] =
                                        0.5 * (a[static_cast<std::size_t>(i) * k + j] + a[static_cast<std::size_t>(j) * k + i]);
    for (int j = 0; j < k; ++j) {
        double pivot = a[static_cast<std::size_t>(j) * k + j];
        for (int l = 0; l < j; ++l) pivot -= a[static_cast<std::size_t>(j) * k + l] * a[static_cast<std::size_t>(j) * k + l];
        if (!(pivot > 0.0)) return 0;  // negative curvature in W: leave it to Newton's safeguards
        const double root = std::sqrt(pivot);
        a[static_cast<std::size_t>(j) * k + j] = root;
        for (int i = j + 1; i < k; ++i) {
            double value = a[static_cast<std::size_t>(i) * k + j];
            for (int l = 0; l < j; ++l) value -= a[static_cast<std::size_t>(i) * k + l] * a[static_cast<std::size_t>(j) * k + l];
            a[static_cast<std::size_t>(i) * k + j] = value / root;
        }
    }
    std::vector<double> c = b;  // L Lᵀ c = b
    for (int i = 0; i < k; ++i) {
        for (int l = 0; l < i; ++l) c[i] -= a[static_cast<std::size_t>(i) * k + l] * c[l];
        c[i] /= a[static_cast<std::size_t>(i) * k + i];
    }
    for (int i = k - 1; i >= 0; --i) {
        for (int l = i + 1; l < k; ++l) c[i] -= a[static_cast<std::size_t>(l) * k + i] * c[l];
        c[i] /= a[static_cast<std::size_t>(i) * k + i];
    }
    std::vector<double> step(g.size(), 0.0);
    for (int j = 0; j < k; ++j)
        for (std::size_t q = 0; q < step.size(); ++q) step[q] += c[j] * basis[j][q];
    const double slope = dotProduct(g, step);  // −bᵀA⁻¹b < 0
    // A decrease the energy's rounding cannot show (a start at the minimum already: a warm start
    // from the solution, or one solved to round-off): not taken.
    if (!(-0.5 * slope > 1e-13 * std::abs(energy))) {
        if (monitor) std::printf("  reduced Newton, subspace of %d correction(s): decrease at rounding level, not taken\n", k);
        return 0;
    }
    if (options_.displacementTolerance > 0.0 &&
        largestRelativeDisplacement(step) <= significantCorrection * options_.displacementTolerance) {
        if (monitor) std::printf("  reduced Newton, subspace of %d correction(s): step within 10 tolerances, not taken\n", k);
        return 0;
    }
    moveAlong(u, step, 1.0);
    const double trialEnergy = reducedEnergy_.fitAndEnergy(trial, trialRotations);
    const bool accepted = slope < 0.0 && std::isfinite(trialEnergy) && trialEnergy <= energy + 1e-4 * slope;
    if (monitor)
        std::printf("  reduced Newton, subspace of %d correction(s): energy %.12e -> %.12e%s\n", k, energy, trialEnergy,
                    accepted ? "" : ", not taken");
    if (!accepted) return 0;
    u.swap(trial);
    rotations.swap(trialRotations);
    energy = trialEnergy;
    reducedEnergy_.gradient(u, rotations, g);
    return k;
}

RbmResult ReducedNewtonSolver::solve(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess)
{
    problem_.checkNodeArray(prescribedDisplacement, "prescribed displacement");
    if (problem_.unknownNodeCount() == 0) return prescribedOnlyResult(problem_, prescribedDisplacement);
    const int n = problem_.nodeCount();
    const int m = problem_.unknownNodeCount();
    const int dim = problem_.dimension();
    const std::size_t size = static_cast<std::size_t>(m) * dim;
    const std::vector<int>& nodes = problem_.unknownNodes();
    const CellNeighbourGraph& graph = problem_.graph();
    const BlockPattern& pattern = problem_.blockPattern();
    RbmResult result;

    std::vector<double> offset(size);  // sliding offsets c n, compact
    problem_.slidingOffset(prescribedDisplacement, offset, dim);
    auto flat = [dim](Vector3 v) {
        if (dim == 2) v.z = 0.0;
        return v;
    };
    // b_k = Σ_{j prescribed} w ū_j − (K c)_k: the right-hand side of the harmonic interpolation.
    // Only unknown nodes next to a prescribed one have a boundary term, and K c only with
    // sliding nodes (c = 0 otherwise): a warm start evaluates this twice.
    if (boundaryNeighbours_.empty()) {
        for (int a = 0; a < m; ++a) {
            const int i = nodes[a];
            for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e)
                if (!problem_.isUnknown(graph.neighbours[e])) {
                    boundaryNeighbours_.push_back(a);
                    break;
                }
        }
        boundaryNeighbours_.push_back(-1);  // the list is made (a solve may have none)
    }
    auto boundaryRightHandSide = [&](std::span<const Vector3> values, std::span<const double> slidingOffset) {
        std::vector<double> b(size, 0.0);
        for (const int a : boundaryNeighbours_) {
            if (a < 0) break;
            const int i = nodes[a];
            Vector3 sum{};
            for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e)
                if (!problem_.isUnknown(graph.neighbours[e]))
                    sum += problem_.edgeWeights()[e] * flat(values[graph.neighbours[e]]);
            for (int q = 0; q < dim; ++q) b[static_cast<std::size_t>(a) * dim + q] = sum[q];
        }
        if (problem_.hasSlidingNodes()) {
            const std::vector<double>& laplacian = preconditioner_.laplacian();
            for (int a = 0; a < m; ++a)
                for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position)
                    for (int q = 0; q < dim; ++q)
                        b[static_cast<std::size_t>(a) * dim + q] -=
                            laplacian[position] * slidingOffset[static_cast<std::size_t>(pattern.columns[position]) * dim + q];
        }
        return b;
    };

    std::vector<Vector3> u(n);
    for (int node = 0; node < n; ++node)
        if (!problem_.isUnknown(node)) u[node] = flat(prescribedDisplacement[node]);
    // u_unknown ← c n + P (value − c n): onto the sliding planes.
    auto setUnknowns = [&](std::vector<Vector3>& target, std::span<const double> values) {
        std::vector<double> tangential(size);
        for (std::size_t k = 0; k < size; ++k) tangential[k] = values[k] - offset[k];
        problem_.projectSliding(tangential, dim);
        for (int a = 0; a < m; ++a) {
            Vector3 value{};
            for (int q = 0; q < dim; ++q)
                value[q] = offset[static_cast<std::size_t>(a) * dim + q] + tangential[static_cast<std::size_t>(a) * dim + q];
            target[nodes[a]] = value;
        }
    };

    std::vector<double> start(size), correction(size);
    std::vector<double> predictorStart;  // the predictor's start where the start is another
    std::string failure;
    bool chained = false;  // warm-started from this solver's own last result, with its history
    // The predictor meets the prescribed boundary to rounding (a turning point of the motion
    // back to a boundary met before, whose kept result it reproduces; a boundary back at rest):
    // the start is usually the minimum already (see the displacement test before the loop).
    bool boundaryReproduced = false;
    if (initialGuess) {
        // Warm start. When the guess is this solver's own last result and the one before is
        // known, a secant step along the boundary's path first: G = u_n + α (u_n − u_{n−1}),
        // α fitting the prescribed change best (on a pitching airfoil, the start is then off by
        // the second difference of the motion instead of the first). Then the boundary
        // mismatch moved in harmonically: start = G + K⁻¹ (b(new) − b(G)).
        problem_.checkNodeArray(initialGuess->displacement, "initial guess displacement");
        std::vector<Vector3> base(initialGuess->displacement.begin(), initialGuess->displacement.end());
        chained = solutionHistory_.size() >= 2 && solutionHistory_[0] == base;
        if (chained) {
            const std::vector<Vector3>& last = solutionHistory_[0];
            const std::vector<Vector3>& previous = solutionHistory_[1];
            double numerator = 0.0, denominator = 0.0;
            for (int node = 0; node < n; ++node) {
                if (problem_.isUnknown(node)) continue;
                const Vector3 step = flat(last[node] - previous[node]);
                numerator += dot(flat(prescribedDisplacement[node]) - flat(last[node]), step);
                denominator += normSquared(step);
            }
            const double secant = denominator > 0.0 ? numerator / denominator : 0.0;
            std::vector<double> coefficients{std::clamp(secant, -2.0, 2.0)};
            // |α| beyond 2: the boundary moves back past the last step (a turning point of the
            // motion between the steps), where the secant extrapolates the wrong way. Then the
            // candidate that fits the prescribed boundary best: the secant, the line through
            // the last result and each older one, or the fit over all (predictorCandidates);
            // on the benchmark's pitching airfoil the step after each reversal then starts at
            // the result of the step mirroring it (the same boundary) instead of at energy 2e-2.
            if (std::abs(secant) > 2.0 && solutionHistory_.size() >= 3)
                coefficients = bestPredictorOnBoundary(prescribedDisplacement, std::move(coefficients));
            for (std::size_t j = 0; j < coefficients.size(); ++j) {
                if (coefficients[j] == 0.0) continue;
                const std::vector<Vector3>& older = solutionHistory_[j + 1];
                for (int node = 0; node < n; ++node) base[node] += coefficients[j] * (last[node] - older[node]);
            }
        }
        // On the prescribed nodes: the predictor's miss, the sizes of the new boundary, the
        // predictor's and the guess's (the two tests to rounding below).
        double missSquared = 0.0, restSquared = 0.0, baseSquared = 0.0, lastSquared = 0.0;
        for (int node = 0; node < n; ++node) {
            if (problem_.isUnknown(node)) continue;
            missSquared += normSquared(flat(prescribedDisplacement[node]) - flat(base[node]));
            restSquared += normSquared(flat(prescribedDisplacement[node]));
            baseSquared += normSquared(flat(base[node]));
            lastSquared += normSquared(flat(initialGuess->displacement[node]));
        }
        boundaryReproduced = std::isfinite(restSquared + baseSquared) &&
                             std::sqrt(missSquared) <= roundingChangeShare * std::sqrt(restSquared + baseSquared);
        std::vector<double> baseOffset(size);
        problem_.slidingOffset(base, baseOffset, dim);
        // K⁻¹ of the change is linear in the boundary's change (without sliding nodes): taken
        // from the extensions of the changes met before where the new one is their combination
        // (harmonicChangeFromBasis), solved otherwise.
        std::vector<double> boundaryChange;
        if (!harmonicChangeFromBasis(prescribedDisplacement, base, boundaryChange, correction)) {
            std::vector<double> change = boundaryRightHandSide(prescribedDisplacement, offset);
            const std::vector<double> previous = boundaryRightHandSide(base, baseOffset);
            for (std::size_t k = 0; k < size; ++k) change[k] -= previous[k];
            if (!preconditioner_.apply(change, correction)) failure = "DIVERGED_LINEAR_SOLVE (harmonic predictor)";
            else rememberHarmonicChange(std::move(boundaryChange), correction);
        }
        for (int a = 0; a < m; ++a) {
            const Vector3 guess = flat(base[nodes[a]]);
            for (int q = 0; q < dim; ++q) {
                const std::size_t k = static_cast<std::size_t>(a) * dim + q;
                start[k] = guess[q] + correction[k] + (offset[k] - baseOffset[k]);
            }
        }
        // A boundary back at rest to rounding (a pitching motion about its rest position, every
        // half period): the reference mesh, no displacement, is its exact minimum, and the
        // start. The predictor's start is kept: the chain's correction is still its miss (the
        // subspace step of the next steps learns from it).
        if (failure.empty() && std::isfinite(lastSquared) &&
            std::sqrt(restSquared) <= roundingChangeShare * std::sqrt(lastSquared)) {
            predictorStart = start;
            start = offset;  // the sliding nodes' normal part (zero at rest, to rounding)
            boundaryReproduced = true;
        }
    } else {
        // Cold start: the harmonic interpolation of the boundary, c n + P K⁻¹ P b.
        if (!preconditioner_.apply(boundaryRightHandSide(prescribedDisplacement, offset), correction))
            failure = "DIVERGED_LINEAR_SOLVE (harmonic start)";
        for (std::size_t k = 0; k < size; ++k) start[k] = offset[k] + correction[k];
    }
    setUnknowns(u, start);
    std::vector<Matrix3> rotations, trialRotations;
    std::vector<Vector3> trial;
    // trial ← from + λ step (step compact), sliding nodes put back onto their planes exactly.
    auto moveAlong = [&](const std::vector<Vector3>& from, std::span<const double> direction, double lambda) {
        trial = from;
        for (int a = 0; a < m; ++a) {
            Vector3& value = trial[nodes[a]];
            for (int q = 0; q < dim; ++q) value[q] += lambda * direction[static_cast<std::size_t>(a) * dim + q];
            if (problem_.kind(nodes[a]) == NodeKind::sliding) {
                Vector3 c{};
                for (int q = 0; q < dim; ++q) c[q] = offset[static_cast<std::size_t>(a) * dim + q];
                value -= problem_.slidingNormalPart(nodes[a], value - c);
            }
        }
    };
    auto compactUnknowns = [&](const std::vector<Vector3>& displacement) {
        std::vector<double> values(size);
        for (int a = 0; a < m; ++a)
            for (int q = 0; q < dim; ++q) values[static_cast<std::size_t>(a) * dim + q] = displacement[nodes[a]][q];
        return values;
    };
    std::vector<double> g(size), trialGradient(size), step(size);
    std::vector<double> negativeGradient(size), estimatedCorrection(size);  // the displacement test
    double energy = reducedEnergy_.fitAndEnergy(u, rotations);
    const bool turnedCandidate = !initialGuess || !chained;
    if (turnedCandidate && failure.empty() && options_.turnedStart) {
        // Where the boundary is one rigid body moving in a fixed frame, also the harmonic
        // interpolation of its TURN: s = K⁻¹ b(1 on the body, 0 on the fixed nodes), and every
        // node moved by the body's motion scaled by s — turned by s θ about the body's centre
        // and shifted by s t — instead of interpolating the displacement vectors, which
        // shortens the cells between (a turned neighbourhood's chord, not its arc). The start
        // of lower energy is kept (with its fitted rotations). On the airfoil's 4° step: energy
        // 4.1 instead of 129 at the start, 3 Newton steps / 19 CG iterations instead of 4 / 24;
        // on the 10⁵-cell hexahedral cube twisted 30°: 9 723 instead of 33 365 (minimum
        // 8 376.5), 3 Newton steps / 20 CG instead of 4 / 30.
        // A warm start without the history for the secant (the first after a restart; a
        // series' second step continues a chain from the reference mesh, see the end of solve):
        // the same from the guess, the body's motion since the guess turned in. On the
        // benchmark's pitching airfoil the series' second step (when it had no chain): 3 Newton
        // steps / 15 CG iterations instead of 4 / 20.
        trial = u;
        const std::span<const Vector3> base =
            initialGuess ? std::span<const Vector3>(initialGuess->displacement) : std::span<const Vector3>{};
        if (turnedHarmonicStart(prescribedDisplacement, trial, base)) {
            const double turnedEnergy = reducedEnergy_.fitAndEnergy(trial, trialRotations);
            if (turnedEnergy < energy) {
                u.swap(trial);
                rotations.swap(trialRotations);
                energy = turnedEnergy;
            }
        }
    }
    // The start actually taken (after the turned one's choice), or the predictor's where the
    // reference mesh was taken instead: the step's Newton correction is the result minus it
    // (the subspace step of later steps).
    std::vector<double> predicted = compactUnknowns(u);
    if (!predictorStart.empty()) {
        trial = u;
        setUnknowns(trial, predictorStart);
        predicted = compactUnknowns(trial);
    }
    reducedEnergy_.gradient(u, rotations, g);
    double gradientNorm = euclideanNorm(g);
    const double tolerance = std::max(absoluteTolerance_, options_.relativeTolerance * gradientNorm);
    constexpr double roundoffFactor = 10.0;  // as CoupledNewtonSolver's convergence test
    // -rbm_reduced_max_it N (Newton steps) and -rbm_reduced_monitor, from PETSc's options.
    PetscInt maximumIterations = options_.maximumIterations;
    PetscBool given = PETSC_FALSE, monitor = PETSC_FALSE;
    RBM_CHECK_PETSC(PetscOptionsGetInt(nullptr, "rbm_reduced_", "-max_it", &maximumIterations, &given));
    RBM_CHECK_PETSC(PetscOptionsHasName(nullptr, "rbm_reduced_", "-monitor", &monitor));
    double forcing = 0.1;
    double previousGradientNorm = gradientNorm;
    int localGlobalSteps = 0;
    std::string reason = failure;
    result.converged = false;
    int firstNewtonIteration = 0;  // after the subspace step, Newton's forcing starts afresh
    // The subspace step: along a chain, in the span of the chain's own corrections (the
    // secant predictor's misses); a warm start outside a chain (the second after a restart,
    // whose first kept no history), in that of the last solve's (the miss of its turned start).
    const bool correctionsFit = chained == correctionsFromChain_;
    bool subspaceTried = !initialGuess || recentCorrections_.empty() || !correctionsFit;
    // Where the boundary is reproduced, the displacement test first: the subspace step's products
    // (three S products, the Hessian's data, a fit and a gradient) would end "not taken" there.
    // On the benchmark's pitching airfoil (steps 6, 7, 16, 17 and those at rest) such a step
    // took 0.011–0.012 instead of 0.021–0.029 s of CPU; on the twisted 10⁵-cell cube turned
    // ±10° (rbmMoveMesh, 20 steps) the four steps after a turning point 0.12–0.13 instead of
    // 0.20–0.21 s. Where the test fails, its K⁻¹ is one back-substitution (or V-cycle) more
    // before the usual order.
    bool convergedAtStart = false;
    if (boundaryReproduced && !subspaceTried && options_.displacementTolerance > 0.0 && failure.empty() &&
        std::isfinite(energy) && std::isfinite(gradientNorm) && gradientNorm > tolerance) {
        for (std::size_t k = 0; k < size; ++k) negativeGradient[k] = -g[k];
        if (preconditioner_.apply(negativeGradient, estimatedCorrection)) {
            const double estimatedDisplacement = largestRelativeDisplacement(estimatedCorrection);
            if (monitor)
                std::printf("  displacement test at the reproduced boundary: K^-1(-grad) moves a node by %.3g of its "
                            "shortest edge (tolerance %.3g)\n",
                            estimatedDisplacement, options_.displacementTolerance);
            if (estimatedDisplacement <= options_.displacementTolerance) {
                result.converged = true;
                reason = "CONVERGED_DISPLACEMENT";
                convergedAtStart = true;
            }
        }
    }
    for (int iteration = 0; failure.empty() && !convergedAtStart; ++iteration) {
        if (!std::isfinite(energy) || !std::isfinite(gradientNorm)) {
            reason = "DIVERGED_FNORM_NAN";
            break;
        }
        if (gradientNorm <= tolerance) {
            result.converged = true;
            reason = gradientNorm <= absoluteTolerance_ ? "CONVERGED_FNORM_ABS" : "CONVERGED_FNORM_RELATIVE";
            break;
        }
        const double roundingLevel = roundoffFactor * reducedEnergy_.gradientRoundoffNorm(u);
        if (gradientNorm <= roundingLevel) {
            result.converged = true;
            reason = "CONVERGED_FNORM_ABS (rounding level)";
            break;
        }
        if (iteration >= maximumIterations) {
            reason = "DIVERGED_MAX_IT";
            break;
        }
        // Eisenstat–Walker (choice 2): η = 0.9 (‖g‖/‖g_prev‖)^forcingExponent_, safeguarded, at
        // most 0.5, and no tighter than the final tolerance needs (finalForcingFactor_ of it).
        if (iteration > firstNewtonIteration) {
            const double ratio = gradientNorm / previousGradientNorm;
            const double safeguard = 0.9 * std::pow(forcing, forcingExponent_);
            forcing = 0.9 * std::pow(ratio, forcingExponent_);
            if (safeguard > 0.1) forcing = std::max(forcing, safeguard);
        }
        forcing = std::clamp(forcing, finalForcingFactor_ * std::max(tolerance, roundingLevel) / gradientNorm, 0.5);
        if (!subspaceTried) {
            subspaceTried = true;
            // The Galerkin step in the span W of the last Newton corrections, c = (WᵀSW)⁻¹ Wᵀ(−∇Ẽ),
            // first. Along a smooth time series the secant predictor misses by nearly the same
            // field each step (its error is the curvature of the path), which CG would rebuild
            // from K⁻¹ in about ten iterations; W costs one S product per vector and no
            // back-substitution. Before the displacement test (whose K⁻¹(−∇Ẽ) would be thrown
            // away): a step smaller than that test's tolerance is not taken (the predictor at a
            // reversal of the motion is the solution already). Then the tests and Newton from
            // the new point.
            if (subspaceStep(u, rotations, energy, g, moveAlong, trial, trialRotations, monitor == PETSC_TRUE) > 0) {
                ++result.iterations;
                gradientNorm = euclideanNorm(g);
                previousGradientNorm = gradientNorm;
                firstNewtonIteration = iteration + 1;
                continue;
            }
        }

        // The displacement test: K⁻¹(−∇Ẽ), the local/global estimate of the remaining
        // displacement (S ≤ K: it underestimates the Newton step, by 2.5–5× on the airfoil near
        // convergence), small against every node's shortest edge. It is CG's first
        // preconditioned residual too, so the test costs nothing when it fails.
        const std::vector<double>* firstPreconditioned = nullptr;
        if (options_.displacementTolerance > 0.0) {
            for (std::size_t k = 0; k < size; ++k) negativeGradient[k] = -g[k];
            if (!preconditioner_.apply(negativeGradient, estimatedCorrection)) {
                reason = "DIVERGED_LINEAR_SOLVE (Laplacian)";
                break;
            }
            const double estimatedDisplacement = largestRelativeDisplacement(estimatedCorrection);
            if (monitor)
                std::printf("  displacement test: K^-1(-grad) moves a node by %.3g of its shortest edge (tolerance %.3g)\n",
                            estimatedDisplacement, options_.displacementTolerance);
            if (estimatedDisplacement <= options_.displacementTolerance) {
                result.converged = true;
                reason = "CONVERGED_DISPLACEMENT";
                break;
            }
            firstPreconditioned = &estimatedCorrection;
            // Close to the minimum the step's own nonlinearity is of the order of the squared
            // displacement (relative to the edges): with D² ≤ 10 ε it is a fraction of ε (the
            // airfoil series' second step, before it was a chain's: from D = 1.2e-3 one step left
            // 3.0e-7 with ε = 1e-6).
            // The gradient after the step is then CG's residual, so the step takes CG to the
            // displacement target that makes the next test pass (newtonDirection) instead of
            // stopping at Eisenstat–Walker's forcing and leaving a Newton step more: on the
            // airfoil series the forcing of 0.1 after a subspace step stopped CG with 1–3
            // tolerances left in six of twenty steps (37 → 30 Newton and subspace steps, 71 →
            // 69 CG iterations). CloseToTheMinimumOneNewtonStepPassesTheDisplacementTest.
            if (estimatedDisplacement * estimatedDisplacement <= 10.0 * options_.displacementTolerance)
                forcing = std::min(forcing, finalForcingFactor_ * std::max(tolerance, roundingLevel) / gradientNorm);
        }
        reducedEnergy_.prepareHessian(u, rotations);
        const int linearIterationsBefore = result.linearIterations;
        bool negativeCurvature = false;
        if (!newtonDirection(g, forcing, firstPreconditioned, step, result.linearIterations, negativeCurvature)) {
            reason = "DIVERGED_LINEAR_SOLVE (Laplacian)";
            break;
        }
        double slope = dotProduct(g, step);
        if (!(slope < 0.0)) {
            // Not a descent direction (rounding near a negative curvature): a local/global step.
            if (!preconditioner_.apply(g, step)) {
                reason = "DIVERGED_LINEAR_SOLVE (Laplacian)";
                break;
            }
            for (double& value : step) value = -value;
            slope = dotProduct(g, step);
            negativeCurvature = true;
        }
        if (negativeCurvature) ++localGlobalSteps;

        // Backtracking (Armijo) on Ẽ; where Ẽ no longer resolves the decrease, a step that
        // lowers ‖P∇Ẽ‖ is taken (CoupledNewtonSolver's line search).
        bool gradientKnown = false;  // trialGradient is the last trial point's
        double trialGradientNorm = gradientNorm;
        const LineSearchResult search = backtrackingLineSearch(
            energy, slope,
            [&](double lambda) {
                moveAlong(u, step, lambda);
                gradientKnown = false;
                return reducedEnergy_.fitAndEnergy(trial, trialRotations);
            },
            [&] {
                reducedEnergy_.gradient(trial, trialRotations, trialGradient);
                trialGradientNorm = euclideanNorm(trialGradient);
                gradientKnown = true;
                return trialGradientNorm < gradientNorm;
            });
        if (search.accepted && !gradientKnown) {
            reducedEnergy_.gradient(trial, trialRotations, trialGradient);
            trialGradientNorm = euclideanNorm(trialGradient);
        }
        const double lambda = search.lambda, trialEnergy = search.energy;
        if (!search.accepted) {
            reason = "DIVERGED_LINE_SEARCH";
            break;
        }
        ++result.iterations;
        if (monitor)
            std::printf("  reduced Newton %d: |P grad| %.6e -> %.6e, CG %d (forcing %.2e), step %.3g, energy %.12e%s\n",
                        iteration, gradientNorm, trialGradientNorm, result.linearIterations - linearIterationsBefore,
                        forcing, lambda, trialEnergy, negativeCurvature ? ", negative curvature" : "");
        u.swap(trial);
        rotations.swap(trialRotations);
        g.swap(trialGradient);
        energy = trialEnergy;
        previousGradientNorm = gradientNorm;
        gradientNorm = trialGradientNorm;
    }

    // History of the predictor: only along a chain of warm starts from own results.
    if (!initialGuess) solutionHistory_.clear();
    // The corrections of converged steps, newest first (a reversal's zero one adds nothing); a
    // solve that does not continue a chain, or the first of a chain, starts the list afresh.
    if (!chained || !correctionsFit) recentCorrections_.clear();
    correctionsFromChain_ = chained;
    if (!result.converged || options_.correctionMemory <= 0) {
        recentCorrections_.clear();
    } else {
        std::vector<double> newCorrection = compactUnknowns(u);
        for (std::size_t k = 0; k < size; ++k) newCorrection[k] -= predicted[k];
        // Only corrections of the predictor's error, not of a few tolerances (a reversal of
        // the motion, whose predictor was the solution already): noise would take a place.
        const bool significant =
            options_.displacementTolerance > 0.0
                ? largestRelativeDisplacement(newCorrection) > significantCorrection * options_.displacementTolerance
                : euclideanNorm(newCorrection) > 0.0;
        if (significant) {
            recentCorrections_.insert(recentCorrections_.begin(), std::move(newCorrection));
            if (recentCorrections_.size() > static_cast<std::size_t>(options_.correctionMemory))
                recentCorrections_.resize(static_cast<std::size_t>(options_.correctionMemory));
        }
    }
    solutionHistory_.insert(solutionHistory_.begin(), u);
    // After a cold solve, the reference mesh is the result before it: no displacement is the
    // exact minimum (Ẽ = 0) for a boundary that does not move. So the next warm start from this
    // result continues a chain of two results, and takes the secant predictor at once
    // (u₁ + α u₁, its boundary mismatch moved in harmonically) instead of the turned start from
    // the guess; its Newton correction then is a chain's, and the third step takes the subspace
    // step along it. On the benchmark's pitching airfoil over 20 steps: 69 → 61 CG iterations,
    // the third step 10 → 8 and the fourth 7 → 2 CG iterations; a further step's solve 0.043 →
    // 0.038 s (mean of four alternating runs each, one thread).
    if (!initialGuess && result.converged) solutionHistory_.emplace_back(static_cast<std::size_t>(n), Vector3{});
    if (solutionHistory_.size() > keptResults) solutionHistory_.resize(keptResults);
    result.displacement = std::move(u);
    result.rotation.assign(n, Vector3{});
    if (rotations.size() == static_cast<std::size_t>(n))
        for (int node : nodes) result.rotation[node] = rotationParameters(dim, rotations[node]);
    // E(u, R*(u)) = Ẽ(u), and ‖P∇E‖ = ‖P∇Ẽ‖ since ∇_R E = 0 at the best fit (file comment):
    // the values of the last iterate, without a second evaluation.
    result.energy = energy;
    result.residualNorm = gradientNorm;
    std::ostringstream text;
    text << reason;
    if (localGlobalSteps > 0) text << " (" << localGlobalSteps << " local/global steps at negative curvature)";
    result.reason = text.str();
    return result;
}

} // namespace rbm::motion

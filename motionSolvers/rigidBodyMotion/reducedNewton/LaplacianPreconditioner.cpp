#include "LaplacianPreconditioner.hpp"

#include "BlockRowLayout.hpp"
#include "PartLaplacian.hpp"
#include "ConjugateGradients.hpp"
#include "ReducedLinearizedOperator.hpp"
#include "SparseCholesky.hpp"
#include "ThreadCount.hpp"
#include "ThreeVectorMultigrid.hpp"

#include <array>
#include <stdexcept>
#include <string>

namespace rbm::motion {

namespace {

// Whether the user chose K's solver or package through PETSc's options (-rbm_reduced_…, -rbm_…
// or global); another living solver's copies and defaults under -rbm_reduced_ are not a choice.
bool userChoseLaplacianSolver()
{
    bool chosen = false;
    for (const char* prefix : {"rbm_reduced_", "rbm_", static_cast<const char*>(nullptr)})
        for (const char* name : {"-ksp_type", "-pc_type", "-pc_factor_mat_solver_type"}) {
            PetscBool given = PETSC_FALSE;
            RBM_CHECK_PETSC(PetscOptionsHasName(nullptr, prefix, name, &given));
            const std::string fullName = "-" + std::string(prefix ? prefix : "") + std::string(name + 1);
            chosen = chosen || (given == PETSC_TRUE && !InheritedOptions::isHeldCopy(fullName));
        }
    return chosen;
}

} // namespace

LaplacianPreconditioner::LaplacianPreconditioner(const RbmProblem& problem, LinearSolverKind linearSolver,
                                                 double relativeTolerance)
    : problem_(problem), relativeTolerance_(relativeTolerance)
{
    if (problem.totalUnknownNodeCount() == 0) return;
    const int dim = problem.dimension();
    // -rbm_reduced_inner_solve: K⁻¹ by CG + GAMG to the relative tolerance instead of one cycle.
    PetscBool innerSolve = PETSC_FALSE;
    RBM_CHECK_PETSC(PetscOptionsHasName(nullptr, "rbm_reduced_", "-inner_solve", &innerSolve));
    laplacian_ = coupledDisplacementLaplacian(problem_);
    if (problem_.isPart()) {  // one rank's part of a distributed problem: PartLaplacian.hpp
        if (problem_.hasCoupledPairs())
            throw std::invalid_argument("cyclic patches are not supported in a distributed solve yet");
        vectorSystem_ = true;
        partLaplacian_ = std::make_unique<PartLaplacian>(problem_, laplacian_, relativeTolerance_, innerSolve);
        // A decision every rank takes alike (the turned start's, hasScalarSolve).
        anyRankHasSlidingNodes_ = problem_.maximumOverRanks(problem_.hasSlidingNodes() ? 1.0 : 0.0) > 0.0;
        // PETSc holds its own copy of K: the array goes, as for the serial 3D cycle, unless the
        // warm start reads it (sliding nodes), and before GAMG's set-up, the part's memory peak
        // (with the reduced energy built after K⁻¹, ReducedNewtonSolver.hpp: 347 → 335 MiB per
        // rank on the 2·10⁵-cell cube on 2 ranks).
        if (!problem_.hasSlidingNodes()) {
            const BlockPattern& pattern = problem_.blockPattern();
            diagonal_.resize(problem_.unknownNodeCount());
            for (int a = 0; a < problem_.unknownNodeCount(); ++a) diagonal_[a] = laplacian_[pattern.diagonal[a]];
            std::vector<double>().swap(laplacian_);
        }
        partLaplacian_->setUp();
        return;
    }
    vectorSystem_ = problem_.hasSlidingNodes();
    PetscMPIInt ranks = 1;
    RBM_CHECK_PETSC(MPI_Comm_size(solverCommunicator(), &ranks));
    const bool factorised = linearSolver == LinearSolverKind::direct ||
                            (linearSolver == LinearSolverKind::automatic &&
                             (dim == 2 || problem_.unknownNodeCount() <= directSolverRowLimit));
    // rbm's own factorisation and back-substitution wherever K would be factorised on one rank,
    // unless the user chose K's solver through PETSc's options: then PETSc's KSP, as configured.
    if (ranks == 1 && factorised && !userChoseLaplacianSolver() && SparseCholesky::available()) {
        const BlockPattern& pattern = problem_.blockPattern();
        if (!vectorSystem_) {
            // Supernodal rows with single-precision entries (SparseCholesky.hpp) halve the
            // memory traffic of the back-substitutions, most of this solver's work; K⁻¹ is only
            // CG's preconditioner, so the single precision costs no accuracy of the minimum.
            cholesky_ = std::make_unique<SparseCholesky>(problem_.unknownNodeCount(), pattern.rowOffsets,
                                                         pattern.columns, laplacian_, FactorPrecision::single);
        } else {
            // Sliding nodes: P (K ⊗ I) P in the sliding frames, factorised once
            // (ProjectedLaplacianFactor.hpp) in double precision: its solve is the start's exact
            // harmonic extension, as the multifrontal solve of the vector system it replaces was.
            projectedCholesky_ =
                std::make_unique<ProjectedLaplacianFactor>(problem_, laplacian_, FactorPrecision::double_);
        }
        return;
    }
    choosePetscDefaults(ranks, factorised);
    // 3D on one rank with K solved iteratively: ONE multigrid hierarchy of K, set up here on
    // laplacian_ itself (PETSc keeps no copy of K) and applied as one V-cycle to the three
    // components at once (ThreeVectorMultigrid.hpp, apply). Another preconditioner chosen
    // by options: the BlockSystemSolver below.
    // With sliding nodes the same cycle of the scalar K, between projections onto the sliding
    // planes, preconditions CG on the projected K ⊗ I, solved to laplacianRelativeTolerance
    // (projectedCycleSolve): far fewer iterations than PETSc's CG + GAMG on the projected
    // K ⊗ I itself (docs/motionSolver.md, "Reduced Newton"). One cycle alone (no inner CG) is too
    // rough an estimate of K⁻¹ there for the start and the displacement test, which then stops
    // short of the minimum.
    // In 2D (K iterative: `linearSolver iterative` or `matrixFree`, which rbmMoveMesh suggests
    // when K's factorisation does not fit in memory) K ⊗ I is solved the same way, by CG + the
    // cycle to the relative tolerance: one cycle alone is no K⁻¹ on a boundary-layer mesh (the
    // start's energy explodes and Newton stalls).
    const bool laplacianIterative =
        linearSolver == LinearSolverKind::iterative || linearSolver == LinearSolverKind::matrixFree ||
        (linearSolver == LinearSolverKind::automatic && problem_.unknownNodeCount() > directSolverRowLimit);
    if (laplacianIterative && !innerSolve) {
        const BlockPattern& pattern = problem_.blockPattern();
        threeVectorCycle_ = ThreeVectorMultigrid::build(pattern.rowOffsets, pattern.columns, laplacian_, "reduced");
        if (threeVectorCycle_) {
            laplacianByCycle_ = true;
            // 3D without sliding nodes (one cycle is K⁻¹, applyInverse) only solveScalar's
            // products read K in double precision, and the edge weights give them
            // (laplacianTimes): K's values go, its diagonal stays. Elsewhere projectedCycleSolve's
            // CG multiplies by K.
            if (problem_.dimension() == 3 && !vectorSystem_ && !threeVectorCycle_->readsFinestValues()) {
                diagonal_.resize(static_cast<std::size_t>(problem_.unknownNodeCount()));
                for (int a = 0; a < problem_.unknownNodeCount(); ++a) diagonal_[a] = laplacian_[pattern.diagonal[a]];
                std::vector<double>().swap(laplacian_);
            }
            return;
        }
    }
    buildPetscSystem(linearSolver, ranks, innerSolve);
}

void LaplacianPreconditioner::choosePetscDefaults([[maybe_unused]] int ranks, [[maybe_unused]] bool factorised)
{
#if defined(PETSC_HAVE_SUITESPARSE)
    // One rank, scalar K: CHOLMOD's supernodal Cholesky, whose back-substitution does far fewer
    // flops than MUMPS's on these graph Laplacians (the back-substitutions are most of this
    // solver's work).
    if (!vectorSystem_ && ranks == 1) {
        laplacianOptions_ = std::make_unique<InheritedOptions>("reduced");
        laplacianOptions_->addDefault("pc_factor_mat_solver_type", "cholmod");
    }
#endif
#if defined(PETSC_HAVE_HYPRE)
    // 2D, K solved iteratively on several ranks (rbm's own cycle is one rank's): PETSc's CG with
    // hypre's BoomerAMG by default instead of GAMG. K is a weighted graph Laplacian, an
    // M-matrix, the case classical AMG is made for, and on a boundary-layer mesh its weights
    // span many orders (1/|d|², wall cells of very high aspect ratio), where GAMG's smoothed
    // aggregation does not converge (DIVERGED_LINEAR_SOLVE, also with a drop threshold). In 3D
    // (one cycle as K⁻¹) GAMG stays: there it was as fast or faster (docs/motionSolver.md,
    // "Reduced Newton"). -rbm_reduced_pc_type gamg brings GAMG back.
    if (ranks > 1 && !factorised && problem_.dimension() == 2) {
        if (!laplacianOptions_) laplacianOptions_ = std::make_unique<InheritedOptions>("reduced");
        laplacianOptions_->addDefault("pc_type", "hypre");
    }
#endif
}

void LaplacianPreconditioner::buildPetscSystem(LinearSolverKind linearSolver, int ranks, bool innerSolve)
{
    const int dim = problem_.dimension();
    const BlockPattern& pattern = problem_.blockPattern();
    system_ = std::make_unique<BlockSystemSolver>(pattern.rowOffsets, pattern.columns, vectorSystem_ ? dim : 1,
                                                  MatrixSymmetry::symmetricPositiveDefinite, linearSolver, dim,
                                                  relativeTolerance_, "reduced");
    if (!vectorSystem_) {
        system_->setMatrix(laplacian_);
    } else {
        std::vector<double> blocks(static_cast<std::size_t>(pattern.blockCount()) * dim * dim, 0.0);
        for (int position = 0; position < pattern.blockCount(); ++position)
            for (int q = 0; q < dim; ++q)
                blocks[(static_cast<std::size_t>(position) * dim + q) * dim + q] = laplacian_[position];
        problem_.projectSlidingBlocks(blocks, dim);
        system_->setMatrix(blocks);
    }
    // One rank and a factorisation (not the user's choice of an iterative method): all components at once.
    multipleRightHandSides_ = !vectorSystem_ && system_->isDirect() && ranks == 1;
    if (!system_->isDirect()) {
        // One PETSc cycle as K⁻¹ only in 3D: in 2D (here with -parallel, or with the options'
        // own preconditioner) one PCGAMG cycle was no K⁻¹ on a boundary-layer mesh (see above),
        // so K ⊗ I is solved to the relative tolerance.
        laplacianByCycle_ = !innerSolve && dim == 3;
    }
    componentIn_.resize(problem_.unknownNodeCount());
    componentOut_.resize(problem_.unknownNodeCount());
}

LaplacianPreconditioner::~LaplacianPreconditioner() = default;

bool LaplacianPreconditioner::apply(std::span<const double> r, std::span<double> z)
{
    if (!problem_.hasCoupledPairs()) return applyInverse(r, z);
    // Cyclic pairs: Π K⁻¹ Π with Π the projection onto the pairs (and the sliding planes). K
    // does not know the pairs (each side of an interface is a free boundary of K), but Π K⁻¹ Π
    // is symmetric positive definite on the subspace the Newton iteration stays in, which is
    // all that CG needs of a preconditioner.
    const int dim = problem_.dimension();
    pairProjected_.assign(r.begin(), r.end());
    problem_.projectSliding(pairProjected_, dim);
    if (!applyInverse(pairProjected_, z)) return false;
    problem_.projectSliding(z, dim);
    return true;
}

bool LaplacianPreconditioner::applyInverse(std::span<const double> r, std::span<double> z)
{
    const int m = problem_.unknownNodeCount();
    const int dim = problem_.dimension();
    if (partLaplacian_) return partLaplacian_->apply(r, z);
    if (cholesky_) {
        cholesky_->solve(r, z, dim);  // compact vectors are interleaved by node already
        return true;
    }
    if (projectedCholesky_) {
        projectedCholesky_->solve(r, z);
        return true;
    }
    if (!vectorSystem_ && multipleRightHandSides_) {
        // Every component in one back-substitution (MatMatSolve): the factor is read once.
        if (!factor_) {
            KSP ksp = system_->ksp();
            PC pc = nullptr;
            RBM_CHECK_PETSC(KSPSetUp(ksp));
            RBM_CHECK_PETSC(KSPGetPC(ksp, &pc));
            RBM_CHECK_PETSC(PCFactorGetMatrix(pc, &factor_));
            RBM_CHECK_PETSC(MatCreateSeqDense(PETSC_COMM_SELF, m, dim, nullptr, components_.out()));
            RBM_CHECK_PETSC(MatCreateSeqDense(PETSC_COMM_SELF, m, dim, nullptr, solutions_.out()));
        }
        PetscScalar* in = nullptr;
        RBM_CHECK_PETSC(MatDenseGetArrayWrite(components_, &in));
        for (int a = 0; a < m; ++a)
            for (int q = 0; q < dim; ++q) in[static_cast<std::size_t>(q) * m + a] = r[static_cast<std::size_t>(a) * dim + q];
        RBM_CHECK_PETSC(MatDenseRestoreArrayWrite(components_, &in));
        RBM_CHECK_PETSC(MatMatSolve(factor_, components_, solutions_));
        const PetscScalar* out = nullptr;
        RBM_CHECK_PETSC(MatDenseGetArrayRead(solutions_, &out));
        for (int a = 0; a < m; ++a)
            for (int q = 0; q < dim; ++q) z[static_cast<std::size_t>(a) * dim + q] = out[static_cast<std::size_t>(q) * m + a];
        RBM_CHECK_PETSC(MatDenseRestoreArrayRead(solutions_, &out));
        return true;
    }
    if (threeVectorCycle_) {
        // One V-cycle on the three components at once (ThreeVectorMultigrid.hpp); with sliding
        // nodes, CG on the projected K ⊗ I preconditioned by it.
        if (!vectorSystem_ && dim == 3) {
            threeVectorCycle_->apply(r, z);
            return true;
        }
        return projectedCycleSolve(r, z, relativeTolerance_);
    }
    if (!vectorSystem_) {
        // The same K for every component.
        for (int q = 0; q < dim; ++q) {
            for (int a = 0; a < m; ++a) componentIn_[a] = r[static_cast<std::size_t>(a) * dim + q];
            if (laplacianByCycle_) {
                system_->applyPreconditioner(componentIn_, componentOut_);
            } else {
                const BlockSystemSolver::Report report = system_->solve(componentIn_, componentOut_, false);
                if (!report.converged) return false;
            }
            for (int a = 0; a < m; ++a) z[static_cast<std::size_t>(a) * dim + q] = componentOut_[a];
        }
        return true;
    }
    std::vector<double> projected(r.begin(), r.end());
    problem_.projectSliding(projected, dim);
    const BlockSystemSolver::Report report = system_->solve(projected, z, false);
    problem_.projectSliding(z, dim);
    return report.converged;
}

bool LaplacianPreconditioner::projectedCycleSolve(std::span<const double> r, std::span<double> z, double relativeTolerance)
{
    constexpr int maximumIterations = 1000;
    const int m = problem_.unknownNodeCount();
    const int dim = problem_.dimension();
    const BlockPattern& pattern = problem_.blockPattern();
    // Every vector of the iteration stays on the sliding planes: b = P r, q = P (K ⊗ I) p,
    // z = P C r.
    projected_.assign(r.begin(), r.end());
    problem_.projectSliding(projected_, dim);
    auto multiply = [&](std::span<const double> p, std::span<double> q) {
#pragma omp parallel for schedule(static) if (worthThreading(pattern.columns.size()))
        for (int a = 0; a < m; ++a) {
            double sum[3] = {0.0, 0.0, 0.0};
            for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position)
                for (int c = 0; c < dim; ++c)
                    sum[c] += laplacian_[position] * p[static_cast<std::size_t>(pattern.columns[position]) * dim + c];
            for (int c = 0; c < dim; ++c) q[static_cast<std::size_t>(a) * dim + c] = sum[c];
        }
        problem_.projectSliding(q, dim);
    };
    auto cycle = [&](std::span<const double> residual, std::span<double> result) {
        if (dim == 3) {
            threeVectorCycle_->apply(residual, result);
        } else {  // the cycle takes three components: the third zero
            planarIn_.resize(3 * static_cast<std::size_t>(m), 0.0);
            planarOut_.resize(3 * static_cast<std::size_t>(m));
            for (int a = 0; a < m; ++a)
                for (int c = 0; c < 2; ++c) planarIn_[3 * static_cast<std::size_t>(a) + c] = residual[2 * static_cast<std::size_t>(a) + c];
            threeVectorCycle_->apply(planarIn_, planarOut_);
            for (int a = 0; a < m; ++a)
                for (int c = 0; c < 2; ++c) result[2 * static_cast<std::size_t>(a) + c] = planarOut_[3 * static_cast<std::size_t>(a) + c];
        }
        problem_.projectSliding(result, dim);
    };
    return conjugateGradients(multiply, cycle, projected_, z, relativeTolerance, maximumIterations, cycleWork_);
}

bool LaplacianPreconditioner::hasScalarSolve() const
{
    if (partLaplacian_) return !anyRankHasSlidingNodes_ && partLaplacian_->hasScalarSolve();
    return !vectorSystem_ && (cholesky_ || threeVectorCycle_);
}

bool LaplacianPreconditioner::solveScalar(std::span<const double> b, std::span<double> s)
{
    if (cholesky_) {
        cholesky_->solve(b, s, 1);
        return true;
    }
    // 3D, K by one multigrid cycle: conjugate gradients on the scalar K, the cycle as the
    // preconditioner (one component of the three it treats at once). The start needs s only
    // roughly (Newton corrects it): to a relative residual of 1e-2, where a tighter tolerance
    // costs more cycles than it saves Newton work and a looser one costs CG iterations.
    constexpr double harmonicShareTolerance = 1e-2;
    constexpr int maximumIterations = 50;
    if (partLaplacian_) return partLaplacian_->solveScalar(b, s, harmonicShareTolerance, maximumIterations);
    const std::size_t size = static_cast<std::size_t>(problem_.unknownNodeCount());
    std::vector<double> in(3 * size, 0.0), out(3 * size);
    auto cycle = [&](std::span<const double> residual, std::span<double> result) {
        for (std::size_t a = 0; a < size; ++a) in[3 * a] = residual[a];
        threeVectorCycle_->apply(in, out);
        for (std::size_t a = 0; a < size; ++a) result[a] = out[3 * a];
    };
    auto multiply = [&](std::span<const double> p, std::span<double> q) { laplacianTimes(p, q); };
    std::array<std::vector<double>, 4> work;
    return conjugateGradients(multiply, cycle, b, s, harmonicShareTolerance, maximumIterations, work);
}

void LaplacianPreconditioner::laplacianTimes(std::span<const double> p, std::span<double> q) const
{
    const BlockPattern& pattern = problem_.blockPattern();
    const int m = problem_.unknownNodeCount();
    if (!laplacian_.empty()) {
#pragma omp parallel for schedule(static) if (worthThreading(pattern.columns.size()))
        for (int a = 0; a < m; ++a) {
            double sum = 0.0;
            for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position)
                sum += laplacian_[position] * p[pattern.columns[position]];
            q[a] = sum;
        }
        return;
    }
    // The same row sums from the graph: the unknown neighbours in graph order are the row's
    // columns in order, K_ab = −2 w_e exactly as coupledDisplacementLaplacian stores it, and the
    // diagonal term comes where its column would (before the first neighbour b > a).
    const CellNeighbourGraph& graph = problem_.graph();
    const std::vector<double>& weights = problem_.edgeWeights();
    const std::vector<int>& unknownIndex = problem_.unknownIndex();
    const std::vector<int>& nodes = problem_.unknownNodes();
#pragma omp parallel for schedule(static) if (worthThreading(graph.neighbours.size()))
    for (int a = 0; a < m; ++a) {
        const int i = nodes[a];
        double sum = 0.0;
        bool diagonalAdded = false;
        for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
            const int b = unknownIndex[graph.neighbours[e]];
            if (b < 0) continue;
            if (!diagonalAdded && b > a) {
                sum += diagonal_[a] * p[a];
                diagonalAdded = true;
            }
            sum += -2.0 * weights[e] * p[b];
        }
        if (!diagonalAdded) sum += diagonal_[a] * p[a];
        q[a] = sum;
    }
}

} // namespace rbm::motion

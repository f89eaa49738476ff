#include "MatrixFreeLinearizedSystem.hpp"

#include "BlockRowLayout.hpp"
#include "ThreeVectorMultigrid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rbm::motion {

namespace {

PetscErrorCode shellMultiply(Mat shell, Vec x, Vec y)
{
    try {
        void* context = nullptr;
        RBM_CHECK_PETSC(MatShellGetContext(shell, &context));
        const auto* system = static_cast<const MatrixFreeLinearizedSystem*>(context);
        PetscInt size = 0;
        RBM_CHECK_PETSC(VecGetLocalSize(x, &size));
        const PetscScalar* in = nullptr;
        PetscScalar* out = nullptr;
        RBM_CHECK_PETSC(VecGetArrayRead(x, &in));
        RBM_CHECK_PETSC(VecGetArray(y, &out));
        system->multiply({in, static_cast<std::size_t>(size)}, {out, static_cast<std::size_t>(size)});
        RBM_CHECK_PETSC(VecRestoreArray(y, &out));
        RBM_CHECK_PETSC(VecRestoreArrayRead(x, &in));
    } catch (const std::exception& error) {
        return petscErrorFromException("MatrixFreeLinearizedSystem::multiply", error);
    }
    return 0;
}

PetscErrorCode shellPrecondition(PC pc, Vec x, Vec y)
{
    try {
        void* context = nullptr;
        RBM_CHECK_PETSC(PCShellGetContext(pc, &context));
        static_cast<MatrixFreeLinearizedSystem*>(context)->precondition(x, y);
    } catch (const std::exception& error) {
        return petscErrorFromException("MatrixFreeLinearizedSystem::precondition", error);
    }
    return 0;
}

void copyToVec(std::span<const double> values, Vec vector)
{
    PetscScalar* out = nullptr;
    RBM_CHECK_PETSC(VecGetArray(vector, &out));
    std::copy(values.begin(), values.end(), out);
    RBM_CHECK_PETSC(VecRestoreArray(vector, &out));
}

void copyFromVec(Vec vector, std::span<double> values)
{
    const PetscScalar* in = nullptr;
    RBM_CHECK_PETSC(VecGetArrayRead(vector, &in));
    std::copy(in, in + values.size(), values.begin());
    RBM_CHECK_PETSC(VecRestoreArrayRead(vector, &in));
}

} // namespace

bool matrixFreeChosen(LinearSolverKind kind, int dimension, int unknownCount)
{
    if (kind == LinearSolverKind::matrixFree) return true;
    if (kind != LinearSolverKind::automatic || dimension != 3 || unknownCount <= 0) return false;
    PetscMPIInt ranks = 1;
    RBM_CHECK_PETSC(MPI_Comm_size(solverCommunicator(), &ranks));
    return ranks == 1;
}

MatrixFreeLinearizedSystem::MatrixFreeLinearizedSystem(const RbmProblem& problem, double relativeTolerance)
    : problem_(problem), operator_(problem), options_("linearized")
{
    PetscMPIInt ranks = 1;
    RBM_CHECK_PETSC(MPI_Comm_size(solverCommunicator(), &ranks));
    if (ranks > 1)
        throw std::invalid_argument("linearSolver matrixFree runs on one MPI rank; with -parallel use "
                                    "'linearSolver iterative;' or 'automatic'");
    const int dimension = problem.dimension();
    const PetscInt nodes = problem.unknownNodeCount();
    const PetscInt size = nodes * dimension;

    // The displacement Laplacian H_uu (scalar, CSR over the block pattern) and its multigrid.
    const BlockPattern& pattern = problem.blockPattern();
    const std::vector<PetscInt> rowOffsets(pattern.rowOffsets.begin(), pattern.rowOffsets.end());
    const std::vector<PetscInt> columns(pattern.columns.begin(), pattern.columns.end());
    laplacianValues_ = operator_.displacementLaplacianValues();
    // rbm's cycle (ThreeVectorMultigrid: its smoothed-aggregation hierarchy, symmetric Chebyshev
    // smoothing, so a symmetric positive definite preconditioner), unless the options choose
    // another preconditioner under rbm_linearized_mf_ (then PETSc's, one PCApply per
    // component). PCGAMG's cycle is not positive definite on the boundary-layer airfoil with
    // the default stiffening: CG stops with DIVERGED_INDEFINITE_PC and the step ends with
    // inverted cells after every sub-step split (docs/motionSolver.md, "Linear solvers").
    cycle_ = ThreeVectorMultigrid::build(pattern.rowOffsets, pattern.columns, laplacianValues_, "linearized_mf");
    if (!cycle_) {
        RBM_CHECK_PETSC(MatCreate(PETSC_COMM_SELF, laplacian_.out()));
        RBM_CHECK_PETSC(MatSetSizes(laplacian_, nodes, nodes, nodes, nodes));
        RBM_CHECK_PETSC(MatSetType(laplacian_, MATSEQAIJ));
        RBM_CHECK_PETSC(
            MatSeqAIJSetPreallocationCSR(laplacian_, rowOffsets.data(), columns.data(), laplacianValues_.data()));
        RBM_CHECK_PETSC(MatSetOption(laplacian_, MAT_SPD, PETSC_TRUE));
        RBM_CHECK_PETSC(PCCreate(PETSC_COMM_SELF, laplacianPreconditioner_.out()));
        RBM_CHECK_PETSC(PCSetOperators(laplacianPreconditioner_, laplacian_, laplacian_));
        RBM_CHECK_PETSC(PCSetType(laplacianPreconditioner_, PCGAMG));
        RBM_CHECK_PETSC(PCSetOptionsPrefix(laplacianPreconditioner_, "rbm_linearized_mf_"));
        RBM_CHECK_PETSC(PCSetFromOptions(laplacianPreconditioner_));
        RBM_CHECK_PETSC(PCSetUp(laplacianPreconditioner_));
    }

    // S as a shell, CG preconditioned by the Laplacian per component.
    RBM_CHECK_PETSC(MatCreateShell(PETSC_COMM_SELF, size, size, size, size, this, shell_.out()));
    RBM_CHECK_PETSC(MatShellSetOperation(shell_, MATOP_MULT, reinterpret_cast<void (*)(void)>(&shellMultiply)));
    RBM_CHECK_PETSC(MatSetOption(shell_, MAT_SYMMETRIC, PETSC_TRUE));
    RBM_CHECK_PETSC(KSPCreate(PETSC_COMM_SELF, ksp_.out()));
    RBM_CHECK_PETSC(KSPSetType(ksp_, KSPCG));
    // Converged on the PRECONDITIONED residual M⁻¹r, a displacement (M⁻¹ a cycle of the
    // displacement Laplacian), not on the true residual r, a force in units of the 1/|d|²
    // weights. On a boundary-layer mesh the true residual is dominated by the nodes at the wall
    // (weights up to ~5e10), so its relative reduction says little about the far field: a
    // solve stopped on it at relativeTolerance 1e-10 can leave far-field nodes hundredths of a
    // chord from the converged solution. The preconditioned residual is a displacement, so
    // its reduction follows what every node still has to move, at the same cost on the
    // twisted cube (docs/motionSolver.md, "Matrix-free linearized solve" and "Linear
    // solvers, measured": the boundary-layer airfoil solved in 3D between two symmetry planes,
    // RigidBodyMotionSolverSubSteps.DISABLED_MeasureMatrixFreeOnTheBoundaryLayerAirfoil).
    RBM_CHECK_PETSC(KSPSetNormType(ksp_, KSP_NORM_PRECONDITIONED));
    RBM_CHECK_PETSC(KSPSetTolerances(ksp_, relativeTolerance, PETSC_DEFAULT, PETSC_DEFAULT, 10000));
    PC pc = nullptr;
    RBM_CHECK_PETSC(KSPGetPC(ksp_, &pc));
    RBM_CHECK_PETSC(PCSetType(pc, PCSHELL));
    RBM_CHECK_PETSC(PCShellSetContext(pc, this));
    RBM_CHECK_PETSC(PCShellSetApply(pc, shellPrecondition));
    RBM_CHECK_PETSC(PCShellSetName(pc, "displacement Laplacian, one multigrid cycle per component"));
    RBM_CHECK_PETSC(KSPSetOperators(ksp_, shell_, shell_));
    configureFromOptions(ksp_.get(), options_);

    for (PetscVec* vector : {&rightHandSide_, &solution_, &projected_}) {
        RBM_CHECK_PETSC(VecCreateSeq(PETSC_COMM_SELF, size, vector->out()));
        RBM_CHECK_PETSC(VecSetBlockSize(*vector, dimension));
    }
    RBM_CHECK_PETSC(VecCreateSeq(PETSC_COMM_SELF, nodes, componentIn_.out()));
    RBM_CHECK_PETSC(VecCreateSeq(PETSC_COMM_SELF, nodes, componentOut_.out()));
}

void MatrixFreeLinearizedSystem::multiply(std::span<const double> x, std::span<double> y) const
{
    const int dimension = problem_.dimension();
    if (problem_.hasSlidingNodes()) {
        projectedInput_.assign(x.begin(), x.end());
        problem_.projectSliding(projectedInput_, dimension);
        operator_.apply(projectedInput_, y);
        problem_.projectSliding(y, dimension);
    } else {
        operator_.apply(x, y);
    }
}

void MatrixFreeLinearizedSystem::precondition(Vec x, Vec y)
{
    const int dimension = problem_.dimension();
    Vec input = x;
    if (problem_.hasSlidingNodes()) {
        RBM_CHECK_PETSC(VecCopy(x, projected_));
        projectSliding(projected_);
        input = projected_;
    }
    if (cycle_) {
        // All components in one cycle (a 2D vector padded with a zero third component).
        const std::size_t nodes = static_cast<std::size_t>(problem_.unknownNodeCount());
        cycleIn_.resize(3 * nodes, 0.0);
        cycleOut_.resize(3 * nodes);
        const PetscScalar* in = nullptr;
        RBM_CHECK_PETSC(VecGetArrayRead(input, &in));
        for (std::size_t a = 0; a < nodes; ++a)
            for (int c = 0; c < dimension; ++c) cycleIn_[3 * a + c] = in[a * dimension + c];
        RBM_CHECK_PETSC(VecRestoreArrayRead(input, &in));
        cycle_->apply(cycleIn_, cycleOut_);
        PetscScalar* out = nullptr;
        RBM_CHECK_PETSC(VecGetArrayWrite(y, &out));
        for (std::size_t a = 0; a < nodes; ++a)
            for (int c = 0; c < dimension; ++c) out[a * dimension + c] = cycleOut_[3 * a + c];
        RBM_CHECK_PETSC(VecRestoreArrayWrite(y, &out));
    } else {
        for (int component = 0; component < dimension; ++component) {
            RBM_CHECK_PETSC(VecStrideGather(input, component, componentIn_, INSERT_VALUES));
            RBM_CHECK_PETSC(PCApply(laplacianPreconditioner_, componentIn_, componentOut_));
            RBM_CHECK_PETSC(VecStrideScatter(componentOut_, component, y, INSERT_VALUES));
        }
    }
    if (problem_.hasSlidingNodes()) projectSliding(y);
}

void MatrixFreeLinearizedSystem::projectSliding(Vec vector) const
{
    PetscScalar* values = nullptr;
    PetscInt size = 0;
    RBM_CHECK_PETSC(VecGetLocalSize(vector, &size));
    RBM_CHECK_PETSC(VecGetArray(vector, &values));
    problem_.projectSliding({values, static_cast<std::size_t>(size)}, problem_.dimension());
    RBM_CHECK_PETSC(VecRestoreArray(vector, &values));
}

std::vector<double> MatrixFreeLinearizedSystem::solveUnknowns(std::span<const Vector3> prescribedDisplacement,
                                                              const RbmState* initialGuess,
                                                              BlockSystemSolver::Report& report)
{
    problem_.checkNodeArray(prescribedDisplacement, "prescribed displacement");
    const int dimension = problem_.dimension();
    const int nodes = problem_.unknownNodeCount();
    const std::vector<int>& unknownNodes = problem_.unknownNodes();

    // Start: prescribed nodes as given, unknown nodes at the sliding offset c n (zero for
    // free nodes). E_reduced is quadratic: the minimiser over start + range(P) is start + δ
    // with (P S P) δ = −P ∇E_reduced(start).
    std::vector<Vector3> displacement(problem_.nodeCount());
    for (int node = 0; node < problem_.nodeCount(); ++node) {
        if (problem_.isUnknown(node)) continue;
        displacement[node] = prescribedDisplacement[node];
        if (dimension == 2) displacement[node].z = 0.0;
    }
    std::vector<double> compact(static_cast<std::size_t>(nodes) * dimension);
    problem_.slidingOffset(prescribedDisplacement, compact, dimension);
    for (int a = 0; a < nodes; ++a)
        for (int q = 0; q < dimension; ++q) displacement[unknownNodes[a]][q] = compact[static_cast<std::size_t>(a) * dimension + q];

    std::vector<double> gradient(compact.size());
    operator_.gradient(displacement, gradient);
    problem_.projectSliding(gradient, dimension);
    for (double& value : gradient) value = -value;
    copyToVec(gradient, rightHandSide_);

    const bool useGuess = initialGuess != nullptr;
    if (useGuess) {
        problem_.checkNodeArray(initialGuess->displacement, "initial guess");
        std::vector<double> step(compact.size());
        for (int a = 0; a < nodes; ++a)
            for (int q = 0; q < dimension; ++q)
                step[static_cast<std::size_t>(a) * dimension + q] =
                    initialGuess->displacement[unknownNodes[a]][q] - compact[static_cast<std::size_t>(a) * dimension + q];
        problem_.projectSliding(step, dimension);
        copyToVec(step, solution_);
    }
    RBM_CHECK_PETSC(KSPSetInitialGuessNonzero(ksp_, useGuess ? PETSC_TRUE : PETSC_FALSE));
    RBM_CHECK_PETSC(KSPSolve(ksp_, rightHandSide_, solution_));
    PetscInt iterations = 0;
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    RBM_CHECK_PETSC(KSPGetIterationNumber(ksp_, &iterations));
    RBM_CHECK_PETSC(KSPGetConvergedReason(ksp_, &reason));
    report.iterations = static_cast<int>(iterations);
    report.converged = reason > 0;
    report.reason = convergedReasonText(reason);

    std::vector<double> step(compact.size());
    copyFromVec(solution_, step);
    problem_.projectSliding(step, dimension);  // exact constraint despite the solver's rounding
    for (int a = 0; a < nodes; ++a)
        for (int q = 0; q < dimension; ++q)
            displacement[unknownNodes[a]][q] += step[static_cast<std::size_t>(a) * dimension + q];

    // The residual P∇E_lin at the result: its rotation part vanishes (best rotations), its
    // displacement part is the reduced gradient.
    operator_.gradient(displacement, gradient);
    problem_.projectSliding(gradient, dimension);
    double sum = 0.0;
    for (double value : gradient) sum += value * value;
    report.residualNorm = std::sqrt(sum);

    std::vector<Vector3> rotation(problem_.nodeCount());
    operator_.bestRotations(displacement, rotation);
    RbmState state;
    state.displacement = std::move(displacement);
    state.rotation = std::move(rotation);
    std::vector<double> unknowns(problem_.unknownCount());
    packUnknowns(problem_, state, unknowns);
    return unknowns;
}

} // namespace rbm::motion

#include "PartLaplacian.hpp"

#include "NodeExchange.hpp"
#include "PartThreeVectorCycle.hpp"

#include <cstdio>
#include <stdexcept>

namespace rbm::motion {

namespace {

// Removes a sliding node's normal part(s) from its 3 displacement entries: P = I − n nᵀ (− m̂ m̂ᵀ on a line).
void projectNode(const RbmProblem& problem, int node, double* v)
{
    for (const Vector3* normal : {&problem.slidingNormal(node), &problem.secondSlidingNormal(node)}) {
        const Vector3& n = *normal;
        const double normalPart = n.x * v[0] + n.y * v[1] + n.z * v[2];
        v[0] -= normalPart * n.x;
        v[1] -= normalPart * n.y;
        v[2] -= normalPart * n.z;
    }
}

bool isSliding(const RbmProblem& problem, int node) { return problem.constraints()[node].kind == NodeKind::sliding; }

} // namespace

PartLaplacian::PartLaplacian(const RbmProblem& problem, std::span<const double> laplacian, double relativeTolerance,
                             bool solveToTolerance)
    : problem_(problem), ownedUnknowns_(problem.ownedUnknownCount())
{
    if (!problem.isPart() || problem.dimension() != 3)
        throw std::invalid_argument("PartLaplacian: one rank's part of a 3D problem is needed");
    if (laplacian.size() != static_cast<std::size_t>(problem.blockPattern().blockCount()))
        throw std::invalid_argument("PartLaplacian: one Laplacian entry per block of the pattern expected");
    // A preconditioner named for the cycle (-rbm_reduced_cycle_pc_type cholesky, ...) is PETSc's,
    // on PETSc's K: the "gamg" path, whose PC the options then replace.
    PetscBool pcNamed = PETSC_FALSE;
    RBM_CHECK_PETSC(PetscOptionsHasName(nullptr, "rbm_reduced_cycle_", "-pc_type", &pcNamed));
    char cycle[16] = "aggregation";
    if (pcNamed) std::snprintf(cycle, sizeof(cycle), "gamg");
    RBM_CHECK_PETSC(PetscOptionsGetString(nullptr, "rbm_reduced_", "-part_cycle", cycle, sizeof(cycle), nullptr));
    const std::string cycleName = cycle;
    if (cycleName != "local" && cycleName != "gamg" && cycleName != "aggregation")
        throw std::invalid_argument("-rbm_reduced_part_cycle " + cycleName + ": expected aggregation, gamg or local");
    useLocalCycle_ = cycleName == "local";
    useAggregationCycle_ = cycleName == "aggregation";
    relativeTolerance_ = relativeTolerance;
    innerSolve_ = solveToTolerance;
    // The matrix over the ranks only where something multiplies by it or cycles on it.
    if (!useLocalCycle_ || solveToTolerance) assemble(laplacian);
    else slidingScales(laplacian);
    if (useLocalCycle_) setUpLocalCycle(laplacian);
}

void PartLaplacian::setUp()
{
    if (setUp_) return;
    if (!useLocalCycle_) setUpCycle();
    setUpSolver();
    setUp_ = true;
}

PartLaplacian::~PartLaplacian() = default;

std::vector<PetscInt> PartLaplacian::unknownRows() const
{
    const NodeExchange& exchange = *problem_.nodeExchange();
    const int owned = problem_.ownedUnknownCount();
    PetscInt first = 0;
    const PetscInt count = owned;
    RBM_CHECK_PETSC(MPI_Exscan(&count, &first, 1, MPIU_INT, MPI_SUM, exchange.communicator()));
    int rank = 0;
    RBM_CHECK_PETSC(MPI_Comm_rank(exchange.communicator(), &rank));
    if (rank == 0) first = 0;  // MPI_Exscan leaves rank 0's result undefined
    // Through the node exchange as doubles (exact below 2⁵³): −1 at prescribed nodes.
    std::vector<double> nodeRows(static_cast<std::size_t>(problem_.nodeCount()), -1.0);
    for (int a = 0; a < owned; ++a) nodeRows[problem_.unknownNodes()[a]] = static_cast<double>(first + a);
    exchange.updateGhosts(nodeRows, 1);
    std::vector<PetscInt> rows(static_cast<std::size_t>(problem_.unknownNodeCount()));
    for (int a = 0; a < problem_.unknownNodeCount(); ++a) {
        rows[a] = static_cast<PetscInt>(nodeRows[problem_.unknownNodes()[a]]);
        if (rows[a] < 0)
            throw std::logic_error("PartLaplacian: a ghost unknown node is prescribed on its owner");
    }
    return rows;
}

void PartLaplacian::assemble(std::span<const double> laplacian)
{
    const BlockPattern& pattern = problem_.blockPattern();
    const std::vector<PetscInt> rows = unknownRows();
    const int owned = ownedUnknowns_;
    // Preallocation by row: columns on this rank (its owned range) and elsewhere.
    const PetscInt firstOwnedRow = owned > 0 ? rows[0] : 0;
    std::vector<PetscInt> diagonalEntries(owned, 0), offDiagonalEntries(owned, 0);
    for (int a = 0; a < owned; ++a)
        for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position) {
            const PetscInt column = rows[pattern.columns[position]];
            const bool local = column >= firstOwnedRow && column < firstOwnedRow + owned;
            (local ? diagonalEntries : offDiagonalEntries)[a] += 1;
        }
    const MPI_Comm communicator = problem_.nodeExchange()->communicator();
    RBM_CHECK_PETSC(MatCreateAIJ(communicator, owned, owned, PETSC_DETERMINE, PETSC_DETERMINE, 0,
                                 diagonalEntries.data(), 0, offDiagonalEntries.data(), stiffness_.out()));
    std::vector<PetscInt> columns;
    for (int a = 0; a < owned; ++a) {
        columns.clear();
        for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position)
            columns.push_back(rows[pattern.columns[position]]);
        const int first = pattern.rowOffsets[a];
        RBM_CHECK_PETSC(MatSetValues(stiffness_, 1, &rows[a], static_cast<PetscInt>(columns.size()), columns.data(),
                                     laplacian.data() + first, INSERT_VALUES));
    }
    RBM_CHECK_PETSC(MatAssemblyBegin(stiffness_, MAT_FINAL_ASSEMBLY));
    RBM_CHECK_PETSC(MatAssemblyEnd(stiffness_, MAT_FINAL_ASSEMBLY));
    RBM_CHECK_PETSC(MatSetOption(stiffness_, MAT_SPD, PETSC_TRUE));
    RBM_CHECK_PETSC(MatCreateVecs(stiffness_, componentIn_.out(), componentOut_.out()));
    slidingScales(laplacian);
}

void PartLaplacian::slidingScales(std::span<const double> laplacian)
{
    // s of projectSlidingBlocks: the mean displacement diagonal of the node's block, K_aa.
    const BlockPattern& pattern = problem_.blockPattern();
    slidingScale_.resize(ownedUnknowns_);
    for (int a = 0; a < ownedUnknowns_; ++a) slidingScale_[a] = laplacian[pattern.diagonal[a]];
}

void PartLaplacian::setUpLocalCycle(std::span<const double> laplacian)
{
    // Owned unknowns come first in the part's unknown numbering: a column below their count is
    // one of them.
    const BlockPattern& pattern = problem_.blockPattern();
    localOffsets_.assign(1, 0);
    for (int a = 0; a < ownedUnknowns_; ++a) {
        for (int position = pattern.rowOffsets[a]; position < pattern.rowOffsets[a + 1]; ++position) {
            if (pattern.columns[position] >= ownedUnknowns_) continue;
            localColumns_.push_back(pattern.columns[position]);
            localValues_.push_back(laplacian[position]);
        }
        localOffsets_.push_back(static_cast<int>(localColumns_.size()));
    }
    localCycle_ = ThreeVectorMultigrid::buildAggregation(localOffsets_, localColumns_, localValues_);
    if (ownedUnknowns_ > 0 && !localCycle_)
        throw std::runtime_error("PartLaplacian: the multigrid hierarchy of the rank's block of K could not be built");
    // The cycle keeps K's finest values in single precision where it has coarser levels.
    if (localCycle_ && !localCycle_->readsFinestValues()) std::vector<double>().swap(localValues_);
}

void PartLaplacian::setUpCycle()
{
    if (useAggregationCycle_) {
        threeVectorCycle_ = std::make_unique<PartThreeVectorCycle>(problem_, stiffness_, unknownRows());
        // PETSc's K only where the CG on A multiplies by it (the cycle reads its own copy).
        if (!innerSolve_) stiffness_.reset();
        return;
    }
    cycleOptions_ = std::make_unique<InheritedOptions>("reduced_cycle");
    cycle_ = createGamgCycle(stiffness_, *cycleOptions_);
}

void PartLaplacian::setUpSolver()
{
    const MPI_Comm communicator = problem_.nodeExchange()->communicator();
    const PetscInt ownedRows = 3 * static_cast<PetscInt>(ownedUnknowns_);
    RBM_CHECK_PETSC(VecCreateMPIWithArray(communicator, 3, ownedRows, PETSC_DECIDE, nullptr, rightHandSide_.out()));
    RBM_CHECK_PETSC(VecCreateMPIWithArray(communicator, 3, ownedRows, PETSC_DECIDE, nullptr, solution_.out()));
    RBM_CHECK_PETSC(VecDuplicate(rightHandSide_, projected_.out()));
    RBM_CHECK_PETSC(MatCreateShell(communicator, ownedRows, ownedRows, PETSC_DETERMINE, PETSC_DETERMINE, this,
                                   operator_.out()));
    RBM_CHECK_PETSC(MatShellSetOperation(operator_, MATOP_MULT, reinterpret_cast<void (*)(void)>(&shellMultiply)));
    RBM_CHECK_PETSC(KSPCreate(communicator, solver_.out()));
    RBM_CHECK_PETSC(KSPSetOperators(solver_, operator_, operator_));
    RBM_CHECK_PETSC(KSPSetType(solver_, innerSolve_ ? KSPCG : KSPPREONLY));
    RBM_CHECK_PETSC(KSPSetTolerances(solver_, relativeTolerance_, 0.0, PETSC_DEFAULT, 1000));
    options_ = std::make_unique<InheritedOptions>("reduced");
    configureFromOptions(solver_, *options_);
    // The preconditioner is this class's own, whatever -rbm_reduced_pc_type says (the serial
    // path's option).
    PC preconditioner = nullptr;
    RBM_CHECK_PETSC(KSPGetPC(solver_, &preconditioner));
    RBM_CHECK_PETSC(PCSetType(preconditioner, PCSHELL));
    RBM_CHECK_PETSC(PCShellSetContext(preconditioner, this));
    RBM_CHECK_PETSC(PCShellSetApply(preconditioner, &shellPrecondition));
    RBM_CHECK_PETSC(KSPSetUp(solver_));
}

void PartLaplacian::project(double* values) const
{
    if (!problem_.hasSlidingNodes()) return;
    for (int a = 0; a < ownedUnknowns_; ++a) {
        const int node = problem_.unknownNodes()[a];
        if (isSliding(problem_, node)) projectNode(problem_, node, values + 3 * static_cast<std::size_t>(a));
    }
}

void PartLaplacian::componentwise(Vec in, Vec out, bool cycle) const
{
    // By hand rather than VecStrideGather: Krylov work vectors made from the shell have no
    // block size.
    for (int q = 0; q < 3; ++q) {
        const double* from = nullptr;
        double* component = nullptr;
        RBM_CHECK_PETSC(VecGetArrayRead(in, &from));
        RBM_CHECK_PETSC(VecGetArray(componentIn_, &component));
        for (int a = 0; a < ownedUnknowns_; ++a) component[a] = from[3 * a + q];
        RBM_CHECK_PETSC(VecRestoreArray(componentIn_, &component));
        RBM_CHECK_PETSC(VecRestoreArrayRead(in, &from));
        if (cycle) RBM_CHECK_PETSC(KSPSolve(cycle_, componentIn_, componentOut_));
        else RBM_CHECK_PETSC(MatMult(stiffness_, componentIn_, componentOut_));
        const double* result = nullptr;
        double* to = nullptr;
        RBM_CHECK_PETSC(VecGetArrayRead(componentOut_, &result));
        RBM_CHECK_PETSC(VecGetArray(out, &to));
        for (int a = 0; a < ownedUnknowns_; ++a) to[3 * a + q] = result[a];
        RBM_CHECK_PETSC(VecRestoreArray(out, &to));
        RBM_CHECK_PETSC(VecRestoreArrayRead(componentOut_, &result));
    }
}

// out = P (B ⊗ I) P in + (I − P) in × f at the sliding nodes: the operator A (B = K, f = s) or
// the preconditioner M (B = the cycle C, f = 1/s).
void PartLaplacian::betweenProjections(Vec in, Vec out, bool cycle) const
{
    RBM_CHECK_PETSC(VecCopy(in, projected_));
    double* projected = nullptr;
    RBM_CHECK_PETSC(VecGetArray(projected_, &projected));
    project(projected);
    RBM_CHECK_PETSC(VecRestoreArray(projected_, &projected));
    if (cycle && (useLocalCycle_ || threeVectorCycle_)) {
        const double* from = nullptr;
        double* to = nullptr;
        RBM_CHECK_PETSC(VecGetArrayRead(projected_, &from));
        RBM_CHECK_PETSC(VecGetArray(out, &to));
        const std::size_t entries = 3 * static_cast<std::size_t>(ownedUnknowns_);
        if (threeVectorCycle_) threeVectorCycle_->apply({from, entries}, {to, entries});
        else if (localCycle_) localCycle_->apply({from, entries}, {to, entries});
        RBM_CHECK_PETSC(VecRestoreArray(out, &to));
        RBM_CHECK_PETSC(VecRestoreArrayRead(projected_, &from));
    } else {
        componentwise(projected_, out, cycle);
    }
    if (!problem_.hasSlidingNodes()) return;
    const double* ins = nullptr;
    const double* projecteds = nullptr;
    double* outs = nullptr;
    RBM_CHECK_PETSC(VecGetArrayRead(in, &ins));
    RBM_CHECK_PETSC(VecGetArrayRead(projected_, &projecteds));
    RBM_CHECK_PETSC(VecGetArray(out, &outs));
    for (int a = 0; a < ownedUnknowns_; ++a) {
        const int node = problem_.unknownNodes()[a];
        if (!isSliding(problem_, node)) continue;
        double* outA = outs + 3 * static_cast<std::size_t>(a);
        projectNode(problem_, node, outA);
        const double factor = cycle ? 1.0 / slidingScale_[a] : slidingScale_[a];
        for (int k = 0; k < 3; ++k) outA[k] += factor * (ins[3 * a + k] - projecteds[3 * a + k]);
    }
    RBM_CHECK_PETSC(VecRestoreArray(out, &outs));
    RBM_CHECK_PETSC(VecRestoreArrayRead(projected_, &projecteds));
    RBM_CHECK_PETSC(VecRestoreArrayRead(in, &ins));
}

PetscErrorCode PartLaplacian::shellMultiply(Mat matrix, Vec x, Vec y)
{
    try {
        void* context = nullptr;
        RBM_CHECK_PETSC(MatShellGetContext(matrix, &context));
        static_cast<const PartLaplacian*>(context)->betweenProjections(x, y, false);
        return 0;
    } catch (const std::exception&) {
        return PETSC_ERR_LIB;
    }
}

PetscErrorCode PartLaplacian::shellScalarCycle(PC preconditioner, Vec r, Vec z)
{
    try {
        void* context = nullptr;
        RBM_CHECK_PETSC(PCShellGetContext(preconditioner, &context));
        auto* self = static_cast<PartLaplacian*>(context);
        const std::size_t rows = static_cast<std::size_t>(self->ownedUnknowns_);
        std::vector<double> in(3 * rows, 0.0), out(3 * rows);
        const double* from = nullptr;
        RBM_CHECK_PETSC(VecGetArrayRead(r, &from));
        for (std::size_t a = 0; a < rows; ++a) in[3 * a] = from[a];
        RBM_CHECK_PETSC(VecRestoreArrayRead(r, &from));
        self->threeVectorCycle_->apply(in, out);
        double* to = nullptr;
        RBM_CHECK_PETSC(VecGetArray(z, &to));
        for (std::size_t a = 0; a < rows; ++a) to[a] = out[3 * a];
        RBM_CHECK_PETSC(VecRestoreArray(z, &to));
        return 0;
    } catch (const std::exception&) {
        return PETSC_ERR_LIB;
    }
}

PetscErrorCode PartLaplacian::shellPrecondition(PC preconditioner, Vec r, Vec z)
{
    try {
        void* context = nullptr;
        RBM_CHECK_PETSC(PCShellGetContext(preconditioner, &context));
        static_cast<const PartLaplacian*>(context)->betweenProjections(r, z, true);
        return 0;
    } catch (const std::exception&) {
        return PETSC_ERR_LIB;
    }
}

bool PartLaplacian::apply(std::span<const double> r, std::span<double> z)
{
    if (!setUp_) throw std::logic_error("PartLaplacian::apply before setUp");
    const std::size_t ownedEntries = 3 * static_cast<std::size_t>(ownedUnknowns_);
    if (r.size() != 3 * static_cast<std::size_t>(problem_.unknownNodeCount()) || z.size() != r.size())
        throw std::invalid_argument("PartLaplacian::apply: 3 entries per unknown node expected");
    projectedRightHandSide_.assign(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(ownedEntries));
    project(projectedRightHandSide_.data());
    std::fill(z.begin(), z.end(), 0.0);
    RBM_CHECK_PETSC(VecPlaceArray(rightHandSide_, projectedRightHandSide_.data()));
    RBM_CHECK_PETSC(VecPlaceArray(solution_, z.data()));
    RBM_CHECK_PETSC(KSPSolve(solver_, rightHandSide_, solution_));
    RBM_CHECK_PETSC(VecResetArray(rightHandSide_));
    RBM_CHECK_PETSC(VecResetArray(solution_));
    std::fill(z.begin() + static_cast<std::ptrdiff_t>(ownedEntries), z.end(), 0.0);
    PetscInt iterations = 0;
    RBM_CHECK_PETSC(KSPGetIterationNumber(solver_, &iterations));
    lastIterations_ = innerSolve_ ? static_cast<int>(iterations) : 0;
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    RBM_CHECK_PETSC(KSPGetConvergedReason(solver_, &reason));
    return reason > 0;
}

bool PartLaplacian::solveScalar(std::span<const double> b, std::span<double> s, double relativeTolerance,
                                int maximumIterations)
{
    if (!setUp_) throw std::logic_error("PartLaplacian::solveScalar before setUp");
    const std::size_t unknowns = static_cast<std::size_t>(problem_.unknownNodeCount());
    if (b.size() != unknowns || s.size() != unknowns)
        throw std::invalid_argument("PartLaplacian::solveScalar: one entry per unknown node expected");
    if (useLocalCycle_) throw std::logic_error("PartLaplacian::solveScalar: not with -rbm_reduced_part_cycle local");
    const MPI_Comm communicator = problem_.nodeExchange()->communicator();
    if (!scalarSolver_) {
        RBM_CHECK_PETSC(KSPCreate(communicator, scalarSolver_.out()));
        RBM_CHECK_PETSC(KSPSetType(scalarSolver_, KSPCG));
        if (threeVectorCycle_) {
            // K as the cycle reads it, the cycle on the first of its three vectors.
            const Mat laplacian = threeVectorCycle_->fineLevel().matrix();
            RBM_CHECK_PETSC(KSPSetOperators(scalarSolver_, laplacian, laplacian));
            PC preconditioner = nullptr;
            RBM_CHECK_PETSC(KSPGetPC(scalarSolver_, &preconditioner));
            RBM_CHECK_PETSC(PCSetType(preconditioner, PCSHELL));
            RBM_CHECK_PETSC(PCShellSetContext(preconditioner, this));
            RBM_CHECK_PETSC(PCShellSetApply(preconditioner, &shellScalarCycle));
        } else {
            // PETSc's cycle: its operator and preconditioner shared, nothing set up again.
            Mat laplacian = nullptr;
            RBM_CHECK_PETSC(KSPGetOperators(cycle_, &laplacian, nullptr));
            PC cycle = nullptr;
            RBM_CHECK_PETSC(KSPGetPC(cycle_, &cycle));
            RBM_CHECK_PETSC(KSPSetPC(scalarSolver_, cycle));
            RBM_CHECK_PETSC(KSPSetOperators(scalarSolver_, laplacian, laplacian));
        }
    }
    RBM_CHECK_PETSC(KSPSetTolerances(scalarSolver_, relativeTolerance, 0.0, PETSC_DEFAULT, maximumIterations));
    std::vector<double> owned(b.begin(), b.begin() + ownedUnknowns_);
    std::fill(s.begin(), s.end(), 0.0);
    PetscVec right, solution;
    RBM_CHECK_PETSC(VecCreateMPIWithArray(communicator, 1, ownedUnknowns_, PETSC_DECIDE, owned.data(), right.out()));
    RBM_CHECK_PETSC(VecCreateMPIWithArray(communicator, 1, ownedUnknowns_, PETSC_DECIDE, s.data(), solution.out()));
    RBM_CHECK_PETSC(KSPSolve(scalarSolver_, right, solution));
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    RBM_CHECK_PETSC(KSPGetConvergedReason(scalarSolver_, &reason));
    // The ghosts' values from their owners, through a node array.
    std::vector<double> nodeValues(static_cast<std::size_t>(problem_.nodeCount()), 0.0);
    const std::vector<int>& nodes = problem_.unknownNodes();
    for (int a = 0; a < ownedUnknowns_; ++a) nodeValues[nodes[a]] = s[a];
    problem_.nodeExchange()->updateGhosts(nodeValues, 1);
    for (std::size_t a = static_cast<std::size_t>(ownedUnknowns_); a < unknowns; ++a) s[a] = nodeValues[nodes[a]];
    return reason > 0;
}

} // namespace rbm::motion

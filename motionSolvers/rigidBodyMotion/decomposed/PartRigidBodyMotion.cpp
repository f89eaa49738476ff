#include "PartRigidBodyMotion.hpp"

#include "BoundaryPath.hpp"
#include "CurvedPatchProjection.hpp"
#include "CellNeighbourGraph.hpp"
#include "EdgeStiffening.hpp"
#include "InputError.hpp"
#include "NodeClasses.hpp"
#include "NodeExchange.hpp"
#include "PartBoundary.hpp"
#include "PartStiffening.hpp"
#include "PetscSupport.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "RbmSolverSelection.hpp"
#include "ReturnFreedMemory.hpp"
#include "ScopedPetscOptions.hpp"
#include "Stiffening.hpp"
#include "UnconstrainedPatches.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace rbm::motion {

namespace {

// The checks a part can make before any collective step: what the distributed solve does not
// take. Every rank reads the same options and the same patch list, so all refuse alike.
void refuseWhatPartsDoNotSolve(const RigidBodyMotionOptions& options, const PolyMesh& localMesh,
                               const BoundaryDescription& boundary)
{
    if (!options.automaticSubSteps() && options.subSteps > 1)
        throw InputError(options.file, 0,
                         "rigidBodyMotionSolver: subSteps " + std::to_string(options.subSteps) +
                             " is not applied on a decomposed case (rbmMoveMesh -parallel solves each step whole); "
                             "remove it (the default solver needs no sub-steps) or run the reconstructed case "
                             "without -parallel");
    if (!partsSolve(options))
        throw InputError(options.file, 0,
                         "rigidBodyMotionSolver: a decomposed case (rbmMoveMesh -parallel) is solved by the default "
                         "variant only (coupling coupled, formulation nonlinear, algorithm reducedNewton), not coupling " +
                             std::string(couplingName(options.coupling)) + ", formulation " +
                             std::string(formulationName(options.formulation)) + ", algorithm " +
                             std::string(algorithmName(options.algorithm)) +
                             "; run the reconstructed case without -parallel for the other variants");
    if (detectPseudoTwoD(localMesh) != PseudoTwoDKind::None)
        throw InputError(options.file, 0,
                         "rigidBodyMotionSolver: this decomposed case is pseudo-2D (one layer of cells between empty or "
                         "wedge patches); the distributed solve is 3D only. Move the undecomposed case (2D solves are "
                         "small) and decompose its result");
    for (std::size_t p = 0; p < boundary.size(); ++p)
        if (boundary[p].nodeClass == BoundaryNodeClass::coupled)
            throw InputError(options.file, 0,
                             "rigidBodyMotionSolver: patch '" + localMesh.patches[p].name +
                                 "' is cyclic; a decomposed case with cyclic patches is not solved in parallel yet. Move "
                                 "the undecomposed case");
}

// Per patch of the local mesh: its faces over all ranks (the processor patches: their own).
std::vector<Label> wholeMeshFaceCounts(const PolyMesh& localMesh, MPI_Comm communicator)
{
    std::vector<Label> counts;
    for (const Patch& patch : localMesh.patches) counts.push_back(patch.faceCount);
    RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, counts.data(), static_cast<int>(sharedPatchCount(localMesh)),
                                  MPI_INT, MPI_SUM, communicator));
    return counts;
}

bool anyRank(bool mine, MPI_Comm communicator)
{
    int value = mine ? 1 : 0;
    RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_INT, MPI_LOR, communicator));
    return value != 0;
}

} // namespace

bool partsSolve(const RigidBodyMotionOptions& options)
{
    return options.coupling == RbmCoupling::coupled && options.formulation == RbmFormulation::nonlinear &&
           options.algorithm == RbmAlgorithm::reducedNewton && (options.automaticSubSteps() || options.subSteps <= 1);
}

void checkPartIsSolvable(const io::Dictionary& coefficients, const PolyMesh& localMesh,
                         const BoundaryDescription& boundary)
{
    const RigidBodyMotionOptions options = RigidBodyMotionOptions::read(coefficients);
    refuseWhatPartsDoNotSolve(options, localMesh, boundary);
    const UnconstrainedPatches namesChecked(localMesh, localMesh.points, options);
    const EdgeStiffening stiffeningNamesChecked(options, localMesh, 3,
                                                [](std::span<const Label>, double) { return std::vector<double>{}; });
}

struct PartRigidBodyMotion::Impl {
    RigidBodyMotionOptions options;
    const PolyMesh& localMesh;
    const BoundaryDescription& localBoundary;
    MeshPart part;
    std::shared_ptr<const NodeExchange> exchange;
    std::shared_ptr<const CellNeighbourGraph> graph;
    UnconstrainedPatches unconstrained;
    NodeClasses classes;
    PrescribedGroups groups;
    EdgeStiffening stiffening;
    std::vector<bool> movedPatches;
    std::unique_ptr<RbmProblem> problem;
    std::unique_ptr<RbmSolver> solver;
    RbmState state;
    bool hasState = false;
    std::vector<std::string> warnings;

    Impl(MPI_Comm communicator, const PolyMesh& mesh, std::span<const Label> globalIds,
         const BoundaryDescription& boundary, RigidBodyMotionOptions solverOptions)
        : options(std::move(solverOptions)),
          localMesh(mesh),
          localBoundary(boundary),
          part(communicator, localCellsOf(mesh, globalIds)),
          exchange(std::make_shared<const NodeExchange>(part)),
          graph(std::make_shared<const CellNeighbourGraph>(
              buildCellNeighbourGraph(part.nodeCount(), part.cellOffsets(), part.cellNodes()))),
          unconstrained(mesh, mesh.points, options),
          stiffening(options, mesh, 3, partStiffeningFactors(mesh, part, *graph),
                     wholeMeshFaceCounts(mesh, communicator))
    {
        part.releaseCells();  // the graph above is all that reads them (305 → 301 MiB, as above)
        const BoundaryDescription merged = partBoundaryDescription(mesh, boundary, part, *exchange, unconstrained);
        classes = classifyNodes(merged, nullptr, *graph, unconstrained);
        groups = groupPrescribedNodes(classes.prescribingPatch, static_cast<int>(merged.size()));
        warnAboutCurvedUnconstrainedPatches();
        rebuildProblem();
    }

    // UnconstrainedPatches::planeWarnings over the ranks: a floating patch that was planar (on
    // each rank that has faces of it) and whose points now leave its plane, by the farthest of
    // any rank's, beyond the smallest tolerance. The same words on every rank.
    void warnAboutFloatingPlanes(const std::vector<Vector3>& displacement, std::vector<std::string>& warnings) const
    {
        const std::size_t shared = sharedPatchCount(localMesh);
        std::vector<double> farthest(shared, 0.0), negativeTolerance(shared, -std::numeric_limits<double>::infinity());
        if (unconstrained.watchesPlanes()) {
            std::vector<Vector3> moved = localMesh.points;
            for (std::size_t p = 0; p < moved.size(); ++p) moved[p] += displacement[p];
            for (const UnconstrainedPatches::PlaneDeparture& departure : unconstrained.planeDepartures(moved)) {
                farthest[departure.patch] = departure.farthest;
                negativeTolerance[departure.patch] = -departure.tolerance;
            }
        }
        RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, farthest.data(), static_cast<int>(shared), MPI_DOUBLE, MPI_MAX,
                                      part.communicator()));
        RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, negativeTolerance.data(), static_cast<int>(shared), MPI_DOUBLE,
                                      MPI_MAX, part.communicator()));
        for (std::size_t p = 0; p < shared; ++p)
            if (std::isfinite(negativeTolerance[p]) && farthest[p] > -negativeTolerance[p])
                warnings.push_back(unconstrained.planeWarning(static_cast<Label>(p), farthest[p]));
    }

    // The serial solver puts the points of curved unconstrained patches back onto their surface
    // after each solve (CurvedPatchProjection.hpp); a part does not yet: say so, naming them.
    void warnAboutCurvedUnconstrainedPatches()
    {
        const std::size_t shared = sharedPatchCount(localMesh);
        double shortest = shortestGraphEdge(*graph, part.nodePoints(), 3);
        RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, &shortest, 1, MPI_DOUBLE, MPI_MIN, part.communicator()));
        std::vector<int> curved(shared, 0);
        for (std::size_t p = 0; p < shared; ++p) {
            if (localBoundary[p].nodeClass != BoundaryNodeClass::free || unconstrained.floats(static_cast<Label>(p)))
                continue;
            std::vector<Vector3> positions;
            for (Label point : localBoundary[p].meshPoints) positions.push_back(localMesh.points[point]);
            curved[p] = !pointsAreFlat(positions, 3, shortest);
        }
        RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, curved.data(), static_cast<int>(shared), MPI_INT, MPI_LOR,
                                      part.communicator()));
        for (std::size_t p = 0; p < shared; ++p)
            if (curved[p])
                warnings.push_back("patch " + localMesh.patches[p].name +
                                   " is curved and unconstrained (zeroGradient-like): in a decomposed run its points "
                                   "slide on their tangent planes and are not put back onto its surface as in a serial "
                                   "run (they leave it by about s²/2R after a slide s on a radius R); give it a slip "
                                   "condition, list it in floatingPatches, or move the undecomposed case");
    }

    void rebuildProblem()
    {
        solver.reset();
        problem.reset();
        problem = std::make_unique<RbmProblem>(3, part.nodePoints(), graph, classes.constraints, options.weighting,
                                               ProblemPart{static_cast<int>(part.ownedNodeCount()), exchange});
        if (stiffening.factors()) problem->setEdgeWeightFactors(stiffening.factors());
        // The weights hold the factors now, and a part has no sub-steps to rebuild problems
        // from them: both copies go (followMotion computes them again if it applies them
        // again). 8 bytes per directed edge that GAMG's set-up, a rank's memory peak, would
        // otherwise see alive: with PartQuality's evaluator let go between evaluations, the
        // 2·10⁵-cell cube on 2 ranks went from 335 to 305 MiB per rank.
        problem->releaseEdgeWeightFactors();
        stiffening.releaseFactors();
    }

    // `stiffening auto`'s rule (EdgeStiffening::followMotion) on decisions all ranks share.
    void followMotion(std::span<const Vector3> target)
    {
        if (!stiffening.automatic()) return;
        const bool moves = std::any_of(target.begin(), target.end(), [](const Vector3& u) { return !(u == Vector3{}); });
        if (!anyRank(moves, part.communicator())) return;
        const std::vector<Vector3> zero(target.size());
        const bool locallyRigid =
            BoundaryPath(3, part.nodePoints(), groups.offsets, groups.nodes, zero, target).allRigid();
        const bool rigid = !anyRank(!locallyRigid, part.communicator());
        // The processor patches prescribe nothing and differ between ranks: not reduced.
        movedPatches.resize(sharedPatchCount(localMesh), false);
        std::vector<int> moved(movedPatches.size(), 0);
        for (std::size_t p = 0; p < moved.size(); ++p)
            for (int k = groups.offsets[p]; !moved[p] && k < groups.offsets[p + 1]; ++k)
                moved[p] = !(target[groups.nodes[k]] == Vector3{});
        RBM_CHECK_PETSC(MPI_Allreduce(MPI_IN_PLACE, moved.data(), static_cast<int>(moved.size()), MPI_INT, MPI_LOR,
                                      part.communicator()));
        for (std::size_t p = 0; p < moved.size(); ++p) movedPatches[p] = movedPatches[p] || moved[p];
        if (stiffening.followMotion(rigid, movedPatches)) rebuildProblem();
    }
};

PartRigidBodyMotion::PartRigidBodyMotion(MPI_Comm communicator, const PolyMesh& localMesh,
                                         std::span<const Label> globalIds, const BoundaryDescription& boundary,
                                         const io::Dictionary& coefficients)
{
    RigidBodyMotionOptions options = RigidBodyMotionOptions::read(coefficients);
    refuseWhatPartsDoNotSolve(options, localMesh, boundary);
    const ScopedPetscOptions petscOptions(options.petscOptionList);
    impl_ = std::make_unique<Impl>(communicator, localMesh, globalIds, boundary, std::move(options));
}

PartRigidBodyMotion::~PartRigidBodyMotion()
{
    if (impl_) {
        impl_->solver.reset();  // before the problem it refers to
        impl_->problem.reset();
    }
}

const MeshPart& PartRigidBodyMotion::part() const { return impl_->part; }
const std::vector<std::string>& PartRigidBodyMotion::warnings() const { return impl_->warnings; }
const RigidBodyMotionOptions& PartRigidBodyMotion::options() const { return impl_->options; }

std::string PartRigidBodyMotion::describe() const
{
    const RigidBodyMotionOptions& o = impl_->options;
    return o.describe() + impl_->stiffening.describeAutomatic(o, impl_->localMesh) + describeAutomaticScaling(o, 3);
}

MotionSolveReport PartRigidBodyMotion::solve(std::vector<Vector3>& displacement)
{
    const auto started = std::chrono::steady_clock::now();
    Impl& impl = *impl_;
    const ScopedPetscOptions petscOptions(impl.options.petscOptionList);
    const std::vector<int>& prescriber = impl.classes.prescribingPatch;
    const std::vector<Vector3> target =
        partPrescribedValues(impl.localBoundary, impl.part, *impl.exchange, prescriber, displacement);
    impl.followMotion(target);

    MotionSolveReport report;
    report.subStepCount = 1;
    const bool moves = std::any_of(target.begin(), target.end(), [](const Vector3& u) { return !(u == Vector3{}); });
    if (!anyRank(moves, impl.part.communicator())) {
        // E = 0 at zero displacement: the initial mesh itself, and no warm start from it
        // (the serial solver's rule, RigidBodyMotionSolver::solve).
        impl.state.displacement.assign(target.size(), Vector3{});
        impl.state.rotation.assign(target.size(), Vector3{});
        impl.hasState = false;
        report.converged = true;
        report.reason = "no boundary displacement";
    } else {
        if (!impl.solver) impl.solver = makeRbmSolver(*impl.problem, impl.options);
        RbmResult result = impl.solver->solve(target, impl.hasState ? &impl.state : nullptr);
        report.iterations = result.iterations;
        report.residual = result.residualNorm;
        report.energy = result.energy;
        report.converged = result.converged;
        report.reason = result.reason;
        impl.state = std::move(static_cast<RbmState&>(result));
        impl.hasState = true;
        returnFreedMemory();  // the solve's work arrays, before the quality check and the output
    }
    const std::vector<Label>& nodeOf = impl.part.pointNodes();
    for (std::size_t point = 0; point < displacement.size(); ++point) {
        const Label node = nodeOf[point];
        displacement[point] = prescriber[node] == heldNode ? Vector3{} : impl.state.displacement[node];
    }
    impl.warnAboutFloatingPlanes(displacement, report.warnings);
    report.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return report;
}

} // namespace rbm::motion

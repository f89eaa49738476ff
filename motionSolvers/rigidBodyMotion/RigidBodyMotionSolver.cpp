#include "RigidBodyMotionSolver.hpp"

#include "CellNeighbourGraph.hpp"
#include "CellSizeRatio.hpp"
#include "CurvedPatchProjection.hpp"
#include "CyclicCoupling.hpp"
#include "CyclicPatchEntries.hpp"
#include "EdgeStiffening.hpp"
#include "InputError.hpp"
#include "InvertedCellCounter.hpp"
#include "InvertedStepAdvice.hpp"
#include "LocalGlobalSolver.hpp"  // rotationParameters
#include "MemoryFit.hpp"
#include "NodeClasses.hpp"
#include "PetscSupport.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "RbmEnergy.hpp"
#include "RbmSolverSelection.hpp"
#include "RbmUntangling.hpp"
#include "ReturnFreedMemory.hpp"
#include "ScopedPetscOptions.hpp"
#include "SubStepSplitting.hpp"
#include "SubStepping.hpp"
#include "BoundaryPath.hpp"
#include "TransverseGradientPenalty.hpp"
#include "UnconstrainedPatches.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <stdexcept>

// The solver is a driver over named parts, each in its own file:
//   node classes       NodeClasses (which nodes are prescribed, slide or float; their groups),
//                      CyclicCoupling (the node pairs of cyclic patches, their classes agreeing)
//   unconstrained      UnconstrainedPatches (zeroGradient-like patches slide or float),
//                      CurvedPatchProjection (and stay on their surface where it is curved)
//   stiffening         EdgeStiffening (the edge factors in effect, `stiffening auto`'s rule)
//   the solver object  RbmSolverSelection (options → the variant's solver)
//   sub-stepping       subStepping/ (the boundary's path, the count, halving on inversion)
//   checks             InvertedCellCounter (src/InvertedCell.hpp's predicate on the solve's mesh)
//   untangling         RbmUntangling (src/Untangling.hpp on the problem's node classes)
//   advice             InvertedStepAdvice (what to change when a step inverted cells)
// What is left here is the order in which they run, and the state kept between solves.

namespace rbm::motion {

namespace {

bool allZero(std::span<const Vector3> values)
{
    return std::all_of(values.begin(), values.end(), [](const Vector3& v) { return v == Vector3{}; });
}

std::unique_ptr<PseudoTwoDMesh> pseudoTwoDMeshOf(const PolyMesh& mesh)
{
    if (detectPseudoTwoD(mesh) == PseudoTwoDKind::None) return nullptr;
    return std::make_unique<PseudoTwoDMesh>(extractPseudoTwoD(mesh));
}

// The node pairs of the mesh's plain cyclic patches (CyclicCoupling.hpp), checked against the
// boundary conditions and the chosen variant: only the reduced Newton solver keeps its iterates
// in the subspace u_b = q u_a.
CyclicCoupling cyclicCouplingOf(const MotionSolver& solver, const std::filesystem::path& caseDirectory,
                                const PseudoTwoDMesh* twoD, const RigidBodyMotionOptions& options)
{
    const PolyMesh& mesh = solver.mesh();
    const std::string file = (caseDirectory / "constant" / "polyMesh" / "boundary").string();
    const std::vector<CyclicPatchSpec> specs = io::readCyclicPatchSpecs(mesh, file);
    for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
        const bool cyclicPatch = mesh.patches[p].type == "cyclic";
        if (cyclicPatch != (solver.boundary()[p].nodeClass == BoundaryNodeClass::coupled))
            throw InputError(file, 0,
                             "patch '" + mesh.patches[p].name + "' is of type " + mesh.patches[p].type +
                                 (cyclicPatch ? " but its boundary condition does not couple it (expected type cyclic)"
                                              : " but its boundary condition is cyclic"));
    }
    if (specs.empty()) return {};
    const bool reducedNewton = options.coupling == RbmCoupling::coupled &&
                               options.formulation == RbmFormulation::nonlinear &&
                               options.algorithm == RbmAlgorithm::reducedNewton;
    if (!reducedNewton)
        throw InputError(options.file, 0,
                         "rigidBodyMotionSolver: cyclic patch '" + mesh.patches[specs.front().patch].name +
                             "': the variant coupling " + std::string(couplingName(options.coupling)) + ", formulation " +
                             std::string(formulationName(options.formulation)) + ", algorithm " +
                             std::string(algorithmName(options.algorithm)) +
                             " does not support cyclic patches; only the default (coupling coupled, formulation "
                             "nonlinear, algorithm reducedNewton) ties their points together");
    return coupleCyclicNodes(mesh, pairCyclicPatches(mesh, solver.points0(), specs, file), twoD, file);
}

} // namespace

// ---------------------------------------------------------------------------------------

struct RigidBodyMotionSolver::Impl {
    RigidBodyMotionSolver& owner;
    RigidBodyMotionOptions options;
    UnconstrainedPatches unconstrained;   // zeroGradient-like patches: slide on their surface or float
    std::unique_ptr<PseudoTwoDMesh> twoD; // a pseudo-3D mesh is solved on its front plane
    int dimension;
    // Per node (2D: frame coordinates of the front plane): the owner's points0 or twoD's planar
    // points themselves, neither of which changes (a copy was 24 bytes a node).
    const std::vector<Vector3>& referencePoints;
    std::shared_ptr<const CellNeighbourGraph> graph;
    CyclicCoupling cyclic;                  // node pairs of the cyclic patches
    std::vector<double> interfaceFactors;   // interfaceEdgeFactors(cyclic); empty without pairs
    std::string boundaryFile;               // constant/polyMesh/boundary, for messages
    EdgeStiffening stiffening;
    std::vector<bool> movedPatches;         // per mesh patch: prescribed non-zero in some solve so far
    InvertedCellCounter inverted;
    RbmUntangler untangler;
    Label initialInverted = 0;             // the reference mesh's own inverted cells

    // Node classes of the current problem (their constraints are the problem's own: not kept
    // twice, 66 bytes per node in 3D).
    std::vector<int> prescribingPatch;     // per node: patch that prescribes it, heldNode, or -1
    PrescribedGroups groups;               // prescribed nodes by prescribing patch
    std::vector<CoupledPair> coupledPairs;  // the cyclic pairs of unknown nodes, for every problem
    std::vector<std::uint8_t> pointIsPrescribed;  // per mesh point: written by a condition, not by the solver
    std::unique_ptr<RbmProblem> problem;
    std::unique_ptr<RbmSolver> baseSolver;  // for `problem`, kept between solve() calls
    CurvedPatchProjection curvedPatches;    // of the current node classes
    std::uint64_t problemBoundaryRevision = 0;  // owner.boundaryRevision() the node classes were derived from

    RbmState state;
    bool hasState = false;
    std::vector<Vector3> statePrescribed;  // the prescribed displacement `state` belongs to
    // What is written: the state, its points on curved unconstrained patches put back onto
    // their surface (projected: else the state itself). The state stays the solver's, the warm
    // start of the next solve.
    std::vector<Vector3> projected;
    bool useProjected = false;
    const std::vector<Vector3>& written() const { return useProjected ? projected : state.displacement; }

    Impl(RigidBodyMotionSolver& solver, RigidBodyMotionOptions solverOptions);

    int nodeCount() const { return static_cast<int>(referencePoints.size()); }
    Label pointOfNode(int node) const { return twoD ? twoD->frontPointOfNode[node] : node; }

    // `stiffening auto`: stiffen while every prescribed patch moves rigidly to `target`, not
    // otherwise (the problem is rebuilt when that changes); a zero target changes nothing.
    void chooseAutomaticStiffening(std::span<const Vector3> target);
    // Recomputes the node classes from the patch conditions; rebuilds the problem when they changed.
    void updateProblem();
    std::vector<Vector3> prescribedTarget() const;
    // A problem on `points` with the node classes `nodeConstraints` (by default the current
    // problem's), the weighting and the stiffening.
    std::unique_ptr<RbmProblem> problemAround(std::vector<Vector3> points,
                                              std::vector<NodeConstraint> nodeConstraints = {}) const;
    // The current problem around `points` (a sub-step's mesh): its node classes, pairs and
    // weight factors (RbmProblem::withReferencePoints).
    std::unique_ptr<RbmProblem> problemAt(std::vector<Vector3> points) const;
    InputError notAProblem(const std::invalid_argument& error) const;
    // Once `problem`'s weights hold the stiffening, its factors go (210 MB at 10⁶ hexahedra).
    void releaseStiffeningFactors();

    // The untangling stage: when state leaves inverted cells that the initial mesh did not
    // have, moves the points around them until none is; the reason tells.
    void untangleState(MotionSolveReport& report);
    // `written` from the state: projected onto the curved unconstrained patches, unless that
    // inverts cells the state does not (then the state, with a warning).
    void prepareWritten(MotionSolveReport& report);
    void writeBack();

    // smallestCellSizeRatio (src/CellSizeRatio.hpp) of the current state.
    double smallestCellSizeRatio() const;

    void solveOnInitialMesh(std::span<const Vector3> target, MotionSolveReport& report);
    void solveInIncrements(std::span<const Vector3> target, MotionSolveReport& report);
};

RigidBodyMotionSolver::Impl::Impl(RigidBodyMotionSolver& solver, RigidBodyMotionOptions solverOptions)
    : owner(solver),
      options(std::move(solverOptions)),
      unconstrained(owner.mesh(), owner.points0(), options),
      twoD(pseudoTwoDMeshOf(owner.mesh())),
      dimension(twoD ? 2 : 3),
      referencePoints(twoD ? twoD->planar.points : owner.points0()),
      graph(std::make_shared<const CellNeighbourGraph>(twoD ? buildCellNeighbourGraph(twoD->planar)
                                                            : buildCellNeighbourGraph(owner.mesh()))),
      cyclic(cyclicCouplingOf(owner, owner.caseDirectory_, twoD.get(), options)),
      interfaceFactors(interfaceEdgeFactors(cyclic, *graph)),
      boundaryFile((owner.caseDirectory_ / "constant" / "polyMesh" / "boundary").string()),
      stiffening(options, owner.mesh(), owner.points0(), twoD.get(), *graph, referencePoints, dimension),
      inverted(owner.mesh(), owner.points0(), twoD.get()),
      untangler(owner.mesh(), twoD.get())
{
    const std::vector<Vector3> zero(referencePoints.size());
    initialInverted = inverted.count(zero);
    inverted.forgetLastCheck();  // the reference mesh's is not asked again: no copy through the first solve
    updateProblem();
}

void RigidBodyMotionSolver::Impl::chooseAutomaticStiffening(std::span<const Vector3> target)
{
    if (!stiffening.automatic() || allZero(target)) return;
    const std::vector<Vector3> zero(target.size());
    const bool rigid = BoundaryPath(dimension, referencePoints, groups.offsets, groups.nodes, zero, target).allRigid();
    // A patch moves from the first solve that prescribes a non-zero displacement on it.
    movedPatches.resize(groups.offsets.size() - 1, false);
    for (std::size_t p = 0; p + 1 < groups.offsets.size(); ++p)
        for (int k = groups.offsets[p]; !movedPatches[p] && k < groups.offsets[p + 1]; ++k)
            movedPatches[p] = !(target[groups.nodes[k]] == Vector3{});
    // A translation (every moving prescribed point by one vector, towards fixed walls that face
    // it) with the transverse penalty in effect: the translation factors (EdgeStiffening.hpp)
    // instead of the stiffening.
    const bool translation = effectiveTransverseStiffness(options, dimension) > 0.0 &&
                             !(TransverseGradientPenalty::translationTowardsFixedWalls(*problem, target) == Vector3{});
    if (!stiffening.followMotion(rigid, movedPatches, translation)) return;
    // The old problem goes before the new one is built: the default's factors are first applied
    // here, at every run's first solve, and two problems at once would raise a large run's peak.
    std::vector<NodeConstraint> constraints = problem->constraints();
    baseSolver.reset();
    problem.reset();
    problem = problemAround(referencePoints, std::move(constraints));
    releaseStiffeningFactors();
}

void RigidBodyMotionSolver::Impl::releaseStiffeningFactors()
{
    // The weights hold the factors; sub-steps take them back out of the weights
    // (RbmProblem::withReferencePoints), a rebuild computes them again (restoreFactors).
    problem->releaseEdgeWeightFactors();
    stiffening.releaseFactors();
}

void RigidBodyMotionSolver::Impl::updateProblem()
{
    // The node classes depend on the boundary description (and the fixed graph) only.
    if (problem && owner.boundaryRevision() == problemBoundaryRevision) return;
    problemBoundaryRevision = owner.boundaryRevision();
    const int n = nodeCount();
    NodeClasses nodeClasses = classifyNodes(owner.boundary(), twoD.get(), *graph, unconstrained);
    std::vector<NodeConstraint>& classes = nodeClasses.constraints;
    std::vector<int>& prescriber = nodeClasses.prescribingPatch;
    const BoundaryDescription& conditions = owner.boundary();
    std::vector<CoupledPair> pairs =
        unifyCoupledClasses(cyclic, nodeClasses, dimension == 2, owner.mesh(), boundaryFile);

    bool changed = !problem;
    const std::vector<NodeConstraint>& constraints = problem ? problem->constraints() : classes;
    for (int node = 0; !changed && node < n; ++node)
        changed = classes[node].kind != constraints[node].kind || !(classes[node].normal == constraints[node].normal) ||
                  !(classes[node].secondNormal == constraints[node].secondNormal) ||
                  classes[node].mirror != constraints[node].mirror ||
                  prescriber[node] != prescribingPatch[node];
    if (!changed) return;

    prescribingPatch = std::move(prescriber);
    coupledPairs = std::move(pairs);
    groups = groupPrescribedNodes(prescribingPatch, static_cast<int>(conditions.size()));
    pointIsPrescribed.assign(owner.mesh().points.size(), 0);
    for (const BoundaryPatchDescription& condition : conditions)
        if (condition.nodeClass == BoundaryNodeClass::prescribed)
            for (Label point : condition.meshPoints) pointIsPrescribed[point] = 1;

    baseSolver.reset();
    problem.reset();
    stiffening.restoreFactors();
    problem = problemAround(referencePoints, std::move(classes));
    releaseStiffeningFactors();
    curvedPatches = CurvedPatchProjection(owner.mesh(), owner.points0(), twoD.get(), conditions, unconstrained, *problem);
}

std::unique_ptr<RbmProblem> RigidBodyMotionSolver::Impl::problemAround(std::vector<Vector3> points,
                                                                      std::vector<NodeConstraint> nodeConstraints) const
{
    if (nodeConstraints.empty() && problem) nodeConstraints = problem->constraints();
    std::unique_ptr<RbmProblem> result;
    try {
        result = std::make_unique<RbmProblem>(dimension, std::move(points), graph, std::move(nodeConstraints),
                                              options.weighting);
        if (!coupledPairs.empty()) result->setCoupledPairs(coupledPairs);
    } catch (const std::invalid_argument& error) {
        throw notAProblem(error);
    }
    if (!interfaceFactors.empty()) {
        // The interface's edges count once (CyclicCoupling.hpp), times any stiffening.
        std::vector<double> factors = interfaceFactors;
        if (stiffening.factors())
            for (std::size_t e = 0; e < factors.size(); ++e) factors[e] *= (*stiffening.factors())[e];
        result->setEdgeWeightFactors(factors);
    } else if (stiffening.factors()) {
        result->setEdgeWeightFactors(stiffening.factors());
    }
    return result;
}

std::unique_ptr<RbmProblem> RigidBodyMotionSolver::Impl::problemAt(std::vector<Vector3> points) const
{
    try {
        return std::make_unique<RbmProblem>(problem->withReferencePoints(std::move(points)));
    } catch (const std::invalid_argument& error) {
        throw notAProblem(error);
    }
}

InputError RigidBodyMotionSolver::Impl::notAProblem(const std::invalid_argument& error) const
{
    return InputError(options.file, 0,
                      std::string("rigidBodyMotionSolver: the mesh and its boundary conditions do not define an RBM "
                                  "problem: ") +
                          error.what() +
                          " (every group of moving points needs a prescribed patch, e.g. fixedValue, holding it)");
}

std::vector<Vector3> RigidBodyMotionSolver::Impl::prescribedTarget() const
{
    const int n = nodeCount();
    std::vector<Vector3> target(n);
    const std::vector<Vector3>& displacement = owner.pointDisplacement();
    for (int node = 0; node < n; ++node) {
        if (prescribingPatch[node] < 0) continue;  // free, sliding (offset 0: u·n = 0) or held
        Vector3 u = displacement[pointOfNode(node)];
        if (twoD) {
            u = twoD->frame.toLocal(u);
            u.z = 0.0;
        }
        target[node] = u;
    }
    return target;
}

void RigidBodyMotionSolver::Impl::untangleState(MotionSolveReport& report)
{
    // Only cells the solve inverted: an initial mesh that is already inverted is the user's.
    if (!options.untangle || initialInverted > 0 || inverted.count(state.displacement) == 0) return;
    const RbmUntangler::Outcome outcome = untangler.untangle(*problem, referencePoints, state.displacement, inverted);
    report.untangledCellCount = outcome.untangledCellCount;
    report.reason += outcome.reason;
}

void RigidBodyMotionSolver::Impl::prepareWritten(MotionSolveReport& report)
{
    useProjected = false;
    if (curvedPatches.empty() || !hasState) return;
    projected = state.displacement;
    curvedPatches.project(referencePoints, projected);
    problem->enforceCoupledPairs(projected);  // a cyclic point on a curved patch: its partner follows
    const Label before = inverted.count(state.displacement);
    useProjected = inverted.count(projected) <= before;
    if (useProjected) return;
    std::string names;
    for (const std::string& name : curvedPatches.patchNames(owner.mesh())) names += (names.empty() ? "" : " ") + name;
    report.warnings.push_back("the points of the curved patches (" + names +
                              ") were left on their tangent planes: put back onto the patches' surfaces they "
                              "inverted cells");
}

void RigidBodyMotionSolver::Impl::writeBack()
{
    std::vector<Vector3>& displacement = owner.pointDisplacement();
    if (twoD) {
        const std::vector<Vector3> lifted = twoD->liftDisplacements(written());
        for (std::size_t p = 0; p < lifted.size(); ++p) {
            const Label node = twoD->nodeOfPoint[p];
            if (node < 0 || pointIsPrescribed[p]) continue;
            displacement[p] = prescribingPatch[node] == heldNode ? Vector3{} : lifted[p];
        }
    } else {
        for (int node = 0; node < nodeCount(); ++node) {
            if (pointIsPrescribed[node]) continue;
            displacement[node] = prescribingPatch[node] == heldNode ? Vector3{} : written()[node];
        }
    }
}

double RigidBodyMotionSolver::Impl::smallestCellSizeRatio() const
{
    if (!twoD) return rbm::smallestCellSizeRatio(owner.mesh(), owner.points0(), owner.curPoints());
    std::vector<Vector3> moved(referencePoints.size());
    for (std::size_t node = 0; node < moved.size(); ++node)
        moved[node] = referencePoints[node] + (hasState ? written()[node] : Vector3{});
    return rbm::smallestCellSizeRatio(twoD->planar, moved);
}

// Nonlinear variants: the energy on the initial mesh for the total prescribed displacement,
// continued from the previous solve (or from the linearized solution at the first).
void RigidBodyMotionSolver::Impl::solveOnInitialMesh(std::span<const Vector3> target, MotionSolveReport& report)
{
    if (!baseSolver) baseSolver = makeRbmSolver(*problem, options);
    // From the last step's boundary, or (empty) from the reference mesh.
    const BoundaryPath path(dimension, referencePoints, groups.offsets, groups.nodes,
                            hasState ? std::span<const Vector3>(statePrescribed) : std::span<const Vector3>{}, target);
    const bool automatic = options.automaticSubSteps();
    const int count = automatic ? 1 : options.subSteps;

    // The warm start: the last step's state itself, then each accepted segment's result, moved
    // and not copied (a time step of the 40k-node airfoil copied 2 MB twice).
    RbmState current;
    const RbmState* guess = hasState ? &state : nullptr;
    report.converged = true;
    SubStepSplitting splitting(automatic ? options.maxSubStepSplits : 0);
    RbmResult last;
    // Segment [from, to] of the path at depth `depth` of halving.
    auto solveSegment = [&](auto&& self, double from, double to, int depth) -> void {
        // The path's end is the target itself, not a copy (at(1) would copy it).
        const std::vector<Vector3> between = to < 1.0 ? path.at(to) : std::vector<Vector3>{};
        const std::span<const Vector3> boundary = to < 1.0 ? std::span<const Vector3>(between) : target;
        RbmResult result = baseSolver->solve(boundary, guess);
        report.iterations += result.iterations;
        if (splitting.allows(depth) && !splitting.accept(depth, inverted.count(result.displacement) > initialInverted)) {
            const double middle = 0.5 * (from + to);
            self(self, from, middle, depth + 1);
            self(self, middle, to, depth + 1);
            return;
        }
        ++report.subStepCount;
        report.converged = report.converged && result.converged;
        current = std::move(static_cast<RbmState&>(result));  // last keeps the figures only
        guess = &current;
        last = std::move(result);
    };
    for (int step = 1; step <= count; ++step)
        solveSegment(solveSegment, static_cast<double>(step - 1) / count, static_cast<double>(step) / count, 0);
    state = std::move(current);
    report.residual = last.residualNorm;
    report.energy = last.energy;
    report.reason = last.reason + splitting.describe();
}

// Linearized variants: the thesis' sub-step method (§2.6), each increment solved around the
// mesh of the previous one, always starting from the initial mesh.
void RigidBodyMotionSolver::Impl::solveInIncrements(std::span<const Vector3> target, MotionSolveReport& report)
{
    if (!baseSolver) baseSolver = makeRbmSolver(*problem, options);
    const int n = nodeCount();
    const std::vector<Vector3> zero(n);
    const BoundaryPath path(dimension, referencePoints, groups.offsets, groups.nodes, zero, target);
    const bool automatic = options.automaticSubSteps();
    int count = options.subSteps;
    bool capped = false;
    if (automatic) {
        count = rotationAwareSubStepCount(*problem, target, groups.offsets, groups.nodes,
                                          defaultMaxSubStepAngleDegrees * std::numbers::pi / 180.0);
        if (count > options.maxSubSteps) {
            count = options.maxSubSteps;
            capped = true;
        }
    }

    std::vector<Vector3> displacement(n);
    std::vector<Matrix3> rotation(dimension == 3 ? n : 0, Matrix3::identity());
    std::vector<double> planarAngle(dimension == 2 ? n : 0, 0.0);
    std::vector<Vector3> reached(n);
    report.converged = true;
    SubStepSplitting splitting(automatic ? options.maxSubStepSplits : 0);
    RbmResult last;
    auto solveSegment = [&](auto&& self, double from, double to, int depth) -> void {
        const std::vector<Vector3> boundary = path.at(to);
        std::vector<Vector3> increment(n);
        for (int node = 0; node < n; ++node) increment[node] = boundary[node] - reached[node];
        RbmResult result;
        if (from == 0.0) {
            result = baseSolver->solve(increment);
        } else {
            std::vector<Vector3> points(referencePoints);
            for (int node = 0; node < n; ++node) {
                points[node].x += displacement[node].x;
                points[node].y += displacement[node].y;
                if (dimension == 3) points[node].z += displacement[node].z;
            }
            const std::unique_ptr<RbmProblem> stepProblem = problemAt(std::move(points));
            result = makeRbmSolver(*stepProblem, options)->solve(increment);
        }
        report.iterations += result.iterations;
        std::vector<Vector3> candidate(displacement);
        for (int node = 0; node < n; ++node) candidate[node] += result.displacement[node];
        if (splitting.allows(depth) && !splitting.accept(depth, inverted.count(candidate) > initialInverted)) {
            const double middle = 0.5 * (from + to);
            self(self, from, middle, depth + 1);
            self(self, middle, to, depth + 1);
            return;
        }
        ++report.subStepCount;
        report.converged = report.converged && result.converged;
        displacement = std::move(candidate);
        for (int node = 0; node < n; ++node) {
            if (!problem->isUnknown(node)) continue;
            if (dimension == 2) planarAngle[node] += result.rotation[node].z;
            else rotation[node] = rotationFromVector(result.rotation[node]) * rotation[node];
        }
        reached = boundary;
        last = std::move(result);
    };
    for (int step = 1; step <= count; ++step)
        solveSegment(solveSegment, static_cast<double>(step - 1) / count, static_cast<double>(step) / count, 0);

    state.displacement = std::move(displacement);
    state.rotation.assign(n, Vector3{});
    for (int node : problem->unknownNodes())
        state.rotation[node] = dimension == 2 ? Vector3{0.0, 0.0, planarAngle[node]} : rotationParameters(3, rotation[node]);
    std::vector<double> unknowns(problem->unknownCount());
    packUnknowns(*problem, state, unknowns);
    // One sub-step: the solver's result is this state (rotations through a matrix and back, equal
    // to rounding), and its exact energy is known; a time series saves an evaluation per step.
    report.energy = report.subStepCount == 1 && count == 1
                        ? last.energy
                        : RbmEnergy(*problem, RotationModel::exact, target).value(unknowns);
    report.residual = last.residualNorm;
    report.reason = last.reason;
    if (capped) report.reason += " (automatic sub-steps capped at maxSubSteps " + std::to_string(options.maxSubSteps) + ")";
    report.reason += splitting.describe();
}

// ---------------------------------------------------------------------------------------

RigidBodyMotionSolver::RigidBodyMotionSolver(const PolyMesh& mesh, const io::Dictionary& coefficients,
                                             std::unique_ptr<BoundaryConditions> conditions,
                                             std::filesystem::path caseDirectory)
    : MotionSolver(mesh, coefficients, std::move(conditions), std::move(caseDirectory))
{
    initialise();
}

RigidBodyMotionSolver::RigidBodyMotionSolver(const PolyMesh& mesh, const io::Dictionary& coefficients,
                                             BoundaryDescription boundary, std::filesystem::path caseDirectory)
    : MotionSolver(mesh, coefficients, std::move(boundary), std::move(caseDirectory))
{
    initialise();
}

void RigidBodyMotionSolver::initialise()
{
    // Parse the options first so that the PETSc options apply while the core builds its objects.
    RigidBodyMotionOptions options = RigidBodyMotionOptions::read(coefficients());
    if (!PetscSession::isInitialized())
        throw std::logic_error("rigidBodyMotionSolver: PETSc is not initialised (create a PetscSession first)");
    const ScopedPetscOptions petscOptions(options.petscOptionList);
    impl_ = std::make_unique<Impl>(*this, std::move(options));
}

RigidBodyMotionSolver::~RigidBodyMotionSolver()
{
    if (impl_) {
        // Solvers before the problem they refer to.
        impl_->baseSolver.reset();
        impl_->problem.reset();
    }
}

const RigidBodyMotionOptions& RigidBodyMotionSolver::options() const { return impl_->options; }
int RigidBodyMotionSolver::dimension() const { return impl_->dimension; }
const PseudoTwoDMesh* RigidBodyMotionSolver::twoDMesh() const { return impl_->twoD.get(); }
const RbmProblem* RigidBodyMotionSolver::problem() const { return impl_->problem.get(); }
const RbmState& RigidBodyMotionSolver::state() const { return impl_->state; }
std::vector<double> RigidBodyMotionSolver::stiffeningFactors() const { return impl_->stiffening.factorsInEffect(); }
const std::vector<Label>& RigidBodyMotionSolver::stiffeningPatches() const { return impl_->stiffening.patches(); }
const std::vector<Label>& RigidBodyMotionSolver::stiffeningMovingPatches() const
{
    return impl_->stiffening.movingPatches();
}
Label RigidBodyMotionSolver::initialInvertedCellCount() const { return impl_->initialInverted; }

std::string RigidBodyMotionSolver::describe() const
{
    const RigidBodyMotionOptions& o = impl_->options;
    return o.describe() + impl_->stiffening.describeAutomatic(o, mesh()) + describeAutomaticScaling(o, impl_->dimension);
}

std::string RigidBodyMotionSolver::invertedStepAdvice() const
{
    const Impl& impl = *impl_;
    double angleDegrees = 0.0;
    double squeeze = 1.0;
    // Measured only when the advice is about the motion (the robust options are in effect).
    if (robustOptionChanges(impl.options, impl.dimension).empty()) {
        const std::vector<Vector3> target = impl.prescribedTarget();
        const std::vector<Vector3> zero(target.size());
        angleDegrees = BoundaryPath(impl.dimension, impl.referencePoints, impl.groups.offsets, impl.groups.nodes, zero,
                                    target)
                           .largestRigidAngle() *
                       180.0 / std::numbers::pi;
        squeeze = impl.smallestCellSizeRatio();
    }
    return motion::invertedStepAdvice(impl.options, impl.dimension, angleDegrees, squeeze);
}

std::string RigidBodyMotionSolver::fitIntoMemory(const AvailableMemory& available)
{
    Impl& impl = *impl_;
    const MemoryFit fit = fitSolveIntoMemory(impl.options, solveSizeOf(*impl.problem), available);
    if (fit.linearSolver) {
        impl.options.linearSolver = *fit.linearSolver;
        impl.baseSolver.reset();
    }
    return fit.note;
}

MotionSolveReport RigidBodyMotionSolver::solve()
{
    const auto started = std::chrono::steady_clock::now();
    Impl& impl = *impl_;
    const ScopedPetscOptions petscOptions(impl.options.petscOptionList);
    impl.updateProblem();
    const std::vector<Vector3> target = impl.prescribedTarget();
    impl.chooseAutomaticStiffening(target);

    MotionSolveReport report;
    if (allZero(target)) {
        // E ≥ 0 and E = 0 at zero displacement: the initial mesh itself, exactly.
        impl.state.displacement.assign(target.size(), Vector3{});
        impl.state.rotation.assign(target.size(), Vector3{});
        report.converged = true;
        report.reason = "no boundary displacement";
        // Not a warm start: the next solve starts from the linearized solution, as Newton
        // from zero can stop where node frames flip (docs/method.md §2).
        impl.hasState = false;
    } else {
        if (impl.options.formulation == RbmFormulation::nonlinear) impl.solveOnInitialMesh(target, report);
        else impl.solveInIncrements(target, report);
        returnFreedMemory();  // the solve's work arrays, before the checks and the caller's output
        impl.hasState = true;
        impl.statePrescribed = target;
        impl.untangleState(report);
        // Untangling moves points one by one, without their cyclic partners: the partners
        // follow (counted with the rest by the check below).
        impl.problem->enforceCoupledPairs(impl.state.displacement);
    }
    impl.prepareWritten(report);
    impl.writeBack();
    if (impl.unconstrained.watchesPlanes())
        for (std::string& warning : impl.unconstrained.planeWarnings(curPoints())) report.warnings.push_back(std::move(warning));
    report.invertedCellCount = impl.inverted.count(impl.written(), &report.worstQuality);
    report.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return report;
}

} // namespace rbm::motion

#include "RigidBodyMotionSolver.hpp"

#include "CellNeighbourGraph.hpp"
#include "CoupledLinearizedSolver.hpp"
#include "CoupledNewtonSolver.hpp"
#include "DecoupledSolver.hpp"
#include "InputError.hpp"
#include "InvertedCell.hpp"
#include "LocalGlobalSolver.hpp"
#include "NodeClasses.hpp"
#include "MeshGeometry.hpp"
#include "PetscSupport.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "RbmEnergy.hpp"
#include "RbmUntangling.hpp"
#include "ReducedNewtonSolver.hpp"
#include "Stiffening.hpp"
#include "UnconstrainedPatches.hpp"
#include "SubStepping.hpp"
#include "ThesisQuality.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace rbm::motion {

namespace {

// ---------------------------------------------------------------------------------------
// PETSc options of the coefficient dictionary (`petscOptions "..."`), present in PETSc's
// options database only while this solver builds or runs its PETSc objects, so that two
// solvers in one program do not see each other's options. Options already in the database
// (the program's command line, PETSC_OPTIONS) are left alone: the command line wins.
class ScopedPetscOptions {
public:
    explicit ScopedPetscOptions(const std::vector<std::pair<std::string, std::string>>& options)
    {
        for (const auto& [name, value] : options) {
            PetscBool set = PETSC_FALSE;
            RBM_CHECK_PETSC(PetscOptionsHasName(nullptr, nullptr, name.c_str(), &set));
            if (set) continue;
            RBM_CHECK_PETSC(PetscOptionsSetValue(nullptr, name.c_str(), value.empty() ? nullptr : value.c_str()));
            inserted_.push_back(name);
        }
    }
    ~ScopedPetscOptions()
    {
        for (const std::string& name : inserted_) (void)PetscOptionsClearValue(nullptr, name.c_str());
    }
    ScopedPetscOptions(const ScopedPetscOptions&) = delete;
    ScopedPetscOptions& operator=(const ScopedPetscOptions&) = delete;

private:
    std::vector<std::string> inserted_;
};

// ---------------------------------------------------------------------------------------
// Coupled nonlinear by local/global iterations; where they stall (maxIterations without
// convergence: a loosely held boundary, thesis §3.1.3), Newton finishes from where they stopped.
class LocalGlobalThenNewton final : public RbmSolver {
public:
    LocalGlobalThenNewton(const RbmProblem& problem, LocalGlobalOptions localGlobal, CoupledNewtonOptions newton)
        : problem_(problem), localGlobal_(problem, localGlobal), newtonOptions_(newton)
    {}
    const RbmProblem& problem() const override { return problem_; }
    RbmResult solve(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess) override
    {
        RbmResult first = localGlobal_.solve(prescribedDisplacement, initialGuess);
        if (first.converged) return first;
        if (!newton_) newton_ = std::make_unique<CoupledNewtonSolver>(problem_, newtonOptions_);
        RbmResult second = newton_->solve(prescribedDisplacement, &first);
        second.iterations += first.iterations;
        second.linearIterations += first.linearIterations;
        second.reason = "local/global stalled (" + first.reason + "), then Newton: " + second.reason;
        return second;
    }

private:
    const RbmProblem& problem_;
    LocalGlobalSolver localGlobal_;
    CoupledNewtonOptions newtonOptions_;
    std::unique_ptr<CoupledNewtonSolver> newton_;
};

// ---------------------------------------------------------------------------------------
// The prescribed displacement along a sub-step path, from `from` (fraction 0) to `to`
// (fraction 1). Prescribed nodes are grouped by the patch that prescribes them; a group whose
// motion from -> to is rigid moves along the rigid motion (a rotation is split into rotations,
// not chords: docs/method.md §4), others along straight lines.
class BoundaryPath {
public:
    BoundaryPath(int dimension, const std::vector<Vector3>& reference, const std::vector<int>& groupOffsets,
                 const std::vector<int>& groupNodes, std::span<const Vector3> from, std::span<const Vector3> to)
        : dimension_(dimension), reference_(reference), groupOffsets_(groupOffsets), groupNodes_(groupNodes),
          from_(from.begin(), from.end()), to_(to.begin(), to.end())
    {
        const int groupCount = static_cast<int>(groupOffsets.size()) - 1;
        motions_.resize(groupCount);
        for (int group = 0; group < groupCount; ++group) fit(group);
    }

    std::vector<Vector3> at(double fraction) const
    {
        if (fraction >= 1.0) return to_;
        std::vector<Vector3> values(to_.size());
        for (std::size_t node = 0; node < values.size(); ++node)
            values[node] = from_[node] + fraction * (to_[node] - from_[node]);
        for (std::size_t group = 0; group < motions_.size(); ++group) {
            const GroupMotion& motion = motions_[group];
            if (!motion.rigid) continue;
            const Matrix3 rotation = dimension_ == 2 ? planarRotation(fraction * motion.rotation.z)
                                                    : rotationFromVector(fraction * motion.rotation);
            for (int k = groupOffsets_[group]; k < groupOffsets_[group + 1]; ++k) {
                const int node = groupNodes_[k];
                const Vector3 start = position(node, from_);
                Vector3 value = motion.centre + fraction * motion.translation + rotation * (start - motion.centre) -
                                flat(reference_[node]);
                if (dimension_ == 2) value.z = 0.0;
                values[node] = value;
            }
        }
        return values;
    }

    // Whether every group's motion from -> to is rigid (to rounding; an empty group counts as rigid).
    bool allRigid() const
    {
        return std::all_of(motions_.begin(), motions_.end(), [](const GroupMotion& m) { return m.rigid; });
    }

    // The largest rotation angle (radians) of the groups that move rigidly.
    double largestRigidAngle() const
    {
        double largest = 0.0;
        for (const GroupMotion& motion : motions_)
            if (motion.rigid) largest = std::max(largest, norm(motion.rotation));
        return largest;
    }

private:
    struct GroupMotion {
        bool rigid = false;
        Vector3 centre;       // of the group at `from`
        Vector3 translation;  // of the centre
        Vector3 rotation;     // 2D: (0, 0, θ) counter-clockwise; 3D: rotation vector
    };

    Vector3 flat(Vector3 v) const
    {
        if (dimension_ == 2) v.z = 0.0;
        return v;
    }
    Vector3 position(int node, const std::vector<Vector3>& displacement) const
    {
        return flat(reference_[node] + displacement[node]);
    }

    void fit(int group)
    {
        const int begin = groupOffsets_[group];
        const int end = groupOffsets_[group + 1];
        if (end == begin) {
            motions_[group].rigid = true;
            return;
        }
        Vector3 centreFrom;
        Vector3 centreTo;
        for (int k = begin; k < end; ++k) {
            centreFrom += position(groupNodes_[k], from_);
            centreTo += position(groupNodes_[k], to_);
        }
        centreFrom /= static_cast<double>(end - begin);
        centreTo /= static_cast<double>(end - begin);
        Matrix3 rotation = Matrix3::identity();
        Vector3 parameters;
        double radius = 0.0;
        double largestMove = 0.0;
        if (dimension_ == 2) {
            double crossSum = 0.0;
            double dotSum = 0.0;
            for (int k = begin; k < end; ++k) {
                const Vector3 a = position(groupNodes_[k], from_) - centreFrom;
                const Vector3 b = position(groupNodes_[k], to_) - centreTo;
                crossSum += a.x * b.y - a.y * b.x;
                dotSum += a.x * b.x + a.y * b.y;
            }
            parameters.z = bestPlanarAngle(crossSum, dotSum);
            rotation = planarRotation(parameters.z);
        } else {
            Matrix3 covariance;
            for (int k = begin; k < end; ++k) {
                const Vector3 a = position(groupNodes_[k], from_) - centreFrom;
                const Vector3 b = position(groupNodes_[k], to_) - centreTo;
                for (int r = 0; r < 3; ++r)
                    for (int c = 0; c < 3; ++c) covariance.m[r][c] += b[r] * a[c];
            }
            rotation = bestRotation(covariance);
            parameters = rotationVectorFromMatrix(rotation);
            rotation = rotationFromVector(parameters);
        }
        double misfit = 0.0;
        for (int k = begin; k < end; ++k) {
            const int node = groupNodes_[k];
            const Vector3 a = position(node, from_) - centreFrom;
            const Vector3 b = position(node, to_);
            radius = std::max(radius, norm(a));
            largestMove = std::max(largestMove, norm(to_[node] - from_[node]));
            misfit = std::max(misfit, norm(centreTo + rotation * a - b));
        }
        GroupMotion& motion = motions_[group];
        motion.rigid = misfit <= 1e-9 * (radius + largestMove) && std::isfinite(misfit);
        motion.centre = centreFrom;
        motion.translation = centreTo - centreFrom;
        motion.rotation = parameters;
    }

    int dimension_;
    const std::vector<Vector3>& reference_;
    const std::vector<int>& groupOffsets_;
    const std::vector<int>& groupNodes_;
    std::vector<Vector3> from_;
    std::vector<Vector3> to_;
    std::vector<GroupMotion> motions_;
};

// Halving of sub-steps that invert cells (automatic sub-steps): a sub-step is split in two
// while its depth of halving is below maxSubStepSplits. Once a sub-step at the deepest level
// still inverts cells, splitting is given up for the rest of the solve: smaller steps did not
// help there, and going on would cost up to 2^depth solves per remaining sub-step.
class SplitBudget {
public:
    explicit SplitBudget(int maximumDepth) : maximumDepth_(maximumDepth) {}
    bool allows(int depth) const { return !exhausted_ && maximumDepth_ > 0 && depth <= maximumDepth_; }
    // Whether to keep a sub-step at `depth` whose mesh is (not) valid; false: split it.
    bool accept(int depth, bool inverted)
    {
        if (!inverted) return true;
        if (depth < maximumDepth_) {
            ++splits_;
            return false;
        }
        exhausted_ = true;
        return true;
    }
    std::string describe() const
    {
        std::string text;
        if (splits_ > 0) text += " (" + std::to_string(splits_) + " sub-step splits)";
        if (exhausted_) text += " (a sub-step still inverted cells after " + std::to_string(maximumDepth_) + " splits)";
        return text;
    }

private:
    int maximumDepth_;
    int splits_ = 0;
    bool exhausted_ = false;
};

bool allZero(std::span<const Vector3> values)
{
    return std::all_of(values.begin(), values.end(), [](const Vector3& v) { return v == Vector3{}; });
}


} // namespace

// ---------------------------------------------------------------------------------------

struct RigidBodyMotionSolver::Impl {
    RigidBodyMotionSolver& owner;
    RigidBodyMotionOptions options;
    UnconstrainedPatches unconstrained;   // zeroGradient-like patches: slide on their surface or float
    int dimension = 3;
    std::unique_ptr<PseudoTwoDMesh> twoD;
    std::shared_ptr<const CellNeighbourGraph> graph;
    std::vector<Vector3> referencePoints;  // per node (2D: frame coordinates of the front plane)
    // Stiffening, per graph edge; null: none. Shared with the problems built from it (one
    // array of 210 MB at 10⁶ hexahedra instead of three).
    std::shared_ptr<const std::vector<double>> edgeFactors;
    std::vector<Label> stiffenedPatches;   // the patches of the stiffening distance
    std::shared_ptr<const std::vector<double>> automaticFactors;  // `stiffening auto`: the factors, applied while the motion is rigid

    // Node classes of the current problem (their constraints are the problem's own: not kept
    // twice, 66 MB at 10⁶ hexahedra).
    std::vector<int> prescribingPatch;     // per node: patch that prescribes it, heldNode, or -1
    std::vector<int> groupOffsets{0};      // prescribed nodes grouped by prescribing patch (CSR)
    std::vector<int> groupNodes;
    std::vector<std::uint8_t> pointIsPrescribed;  // per mesh point: written by a condition, not by the solver
    std::unique_ptr<RbmProblem> problem;
    std::unique_ptr<RbmSolver> baseSolver;  // for `problem`, kept between solve() calls
    std::uint64_t problemBoundaryRevision = 0;  // owner.boundaryRevision() the node classes were derived from

    RbmState state;
    bool hasState = false;
    std::vector<Vector3> statePrescribed;  // the prescribed displacement `state` belongs to

    // Inverted-cell checks.
    MeshGeometry geometry;
    std::vector<Vector3> positions;
    std::vector<double> smallestPyramid;
    std::vector<int> faceCounts;
    Label initialInverted = 0;
    // The last check without a cell list: its displacement and figures. A solve checks its
    // last sub-step's result, then (unchanged unless untangled) the state it keeps.
    std::vector<Vector3> checkedDisplacement;
    Label checkedInverted = -1;   // -1: none yet
    double checkedWorst = 0.0;

    Impl(RigidBodyMotionSolver& solver, RigidBodyMotionOptions solverOptions);

    int nodeCount() const { return static_cast<int>(referencePoints.size()); }
    Label pointOfNode(int node) const { return twoD ? twoD->frontPointOfNode[node] : node; }

    void buildStiffening();
    // `stiffening auto`: stiffen while every prescribed patch moves rigidly to `target`, not
    // otherwise (the problem is rebuilt when that changes); a zero target changes nothing.
    void chooseAutomaticStiffening(std::span<const Vector3> target);
    // Recomputes the node classes from the patch conditions; rebuilds the problem when they changed.
    void updateProblem();
    std::vector<Vector3> prescribedTarget() const;
    std::unique_ptr<RbmSolver> makeSolver(const RbmProblem& forProblem) const;
    // A problem on `points` with the node classes `nodeConstraints` (by default the current
    // problem's), the weighting and the stiffening.
    std::unique_ptr<RbmProblem> problemAround(std::vector<Vector3> points,
                                              std::vector<NodeConstraint> nodeConstraints = {}) const;

    // invertedCells (optional) receives the labels of the inverted cells (2D: planar cells).
    Label countInverted(std::span<const Vector3> nodeDisplacement, double* worstQuality = nullptr,
                        std::vector<Label>* invertedCells = nullptr);
    // The untangling stage (src/Untangling.hpp): when state leaves inverted cells that the
    // initial mesh did not have, moves the points around them until none is; the reason tells.
    void untangleState(MotionSolveReport& report);
    std::unique_ptr<SimplexDecomposition> simplices;  // built at the first untangling
    void writeBack();

    // How far the motion squeezes the cells: the ratio of a valid cell's size (2D: area, 3D:
    // volume) in the current state to its size in the reference mesh, at the 1st percentile.
    double smallestCellSizeRatio() const;

    void solveOnInitialMesh(std::span<const Vector3> target, MotionSolveReport& report);
    void solveInIncrements(std::span<const Vector3> target, MotionSolveReport& report);
};

RigidBodyMotionSolver::Impl::Impl(RigidBodyMotionSolver& solver, RigidBodyMotionOptions solverOptions)
    : owner(solver), options(std::move(solverOptions)), unconstrained(owner.mesh(), owner.points0(), options)
{
    const PolyMesh& mesh = owner.mesh();
    if (detectPseudoTwoD(mesh) != PseudoTwoDKind::None) {
        twoD = std::make_unique<PseudoTwoDMesh>(extractPseudoTwoD(mesh));
        dimension = 2;
        referencePoints = twoD->planar.points;
        graph = std::make_shared<const CellNeighbourGraph>(buildCellNeighbourGraph(twoD->planar));
    } else {
        dimension = 3;
        referencePoints = owner.points0();
        graph = std::make_shared<const CellNeighbourGraph>(buildCellNeighbourGraph(mesh));
    }
    buildStiffening();
    const std::vector<Vector3> zero(referencePoints.size());
    initialInverted = countInverted(zero);
    updateProblem();
}

void RigidBodyMotionSolver::Impl::buildStiffening()
{
    const StiffeningOptions& stiffening = options.stiffening;
    if (!stiffening.enabled()) return;
    const PolyMesh& mesh = owner.mesh();
    std::vector<Label> patches;
    if (stiffening.automaticPatches) patches = automaticStiffeningPatches(mesh);
    for (const std::string& name : stiffening.patches) {
        bool found = false;
        for (Label p = 0; p < static_cast<Label>(mesh.patches.size()); ++p) {
            const Patch& patch = mesh.patches[p];
            const bool inGroup = std::find(patch.inGroups.begin(), patch.inGroups.end(), name) != patch.inGroups.end();
            if (patch.name == name || inGroup) {
                if (std::find(patches.begin(), patches.end(), p) == patches.end()) patches.push_back(p);
                found = true;
            }
        }
        if (!found)
            throw InputError(options.file, stiffening.line,
                             "stiffening: unknown patch " + name + ". Valid patches are: " + patchNameList(mesh));
    }
    NearestSurface surface;
    if (twoD) {
        std::vector<Label> planarPatches;
        for (Label p = 0; p < static_cast<Label>(twoD->planar.patches.size()); ++p)
            if (std::find(patches.begin(), patches.end(), twoD->planar.patches[p].polyMeshPatch) != patches.end())
                planarPatches.push_back(p);
        surface = patchSurface(twoD->planar, planarPatches);
    } else {
        surface = patchSurface(mesh, owner.points0(), patches);
    }
    edgeFactors = std::make_shared<const std::vector<double>>(
        motion::stiffeningFactors(*graph, referencePoints, dimension, surface, stiffening.exponent));
    stiffenedPatches = std::move(patches);
    if (stiffening.automaticPatches) automaticFactors = edgeFactors;
}

void RigidBodyMotionSolver::Impl::chooseAutomaticStiffening(std::span<const Vector3> target)
{
    if (!automaticFactors || allZero(target)) return;
    const std::vector<Vector3> zero(target.size());
    const bool rigid = BoundaryPath(dimension, referencePoints, groupOffsets, groupNodes, zero, target).allRigid();
    if (rigid == (edgeFactors != nullptr)) return;
    edgeFactors = rigid ? automaticFactors : nullptr;
    baseSolver.reset();
    problem = problemAround(referencePoints);
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

    bool changed = !problem;
    const std::vector<NodeConstraint>& constraints = problem ? problem->constraints() : classes;
    for (int node = 0; !changed && node < n; ++node)
        changed = classes[node].kind != constraints[node].kind || !(classes[node].normal == constraints[node].normal) ||
                  !(classes[node].secondNormal == constraints[node].secondNormal) ||
                  classes[node].mirror != constraints[node].mirror ||
                  prescriber[node] != prescribingPatch[node];
    if (!changed) return;

    prescribingPatch = std::move(prescriber);
    const int patchCount = static_cast<int>(conditions.size());
    groupOffsets.assign(patchCount + 1, 0);
    for (int node = 0; node < n; ++node)
        if (prescribingPatch[node] >= 0) ++groupOffsets[prescribingPatch[node] + 1];
    for (int p = 0; p < patchCount; ++p) groupOffsets[p + 1] += groupOffsets[p];
    groupNodes.assign(groupOffsets.back(), 0);
    {
        std::vector<int> next(groupOffsets.begin(), groupOffsets.end() - 1);
        for (int node = 0; node < n; ++node)
            if (prescribingPatch[node] >= 0) groupNodes[next[prescribingPatch[node]]++] = node;
    }
    pointIsPrescribed.assign(owner.mesh().points.size(), 0);
    for (const BoundaryPatchDescription& condition : conditions)
        if (condition.nodeClass == BoundaryNodeClass::prescribed)
            for (Label point : condition.meshPoints) pointIsPrescribed[point] = 1;

    baseSolver.reset();
    problem.reset();
    problem = problemAround(referencePoints, std::move(classes));
}

std::unique_ptr<RbmProblem> RigidBodyMotionSolver::Impl::problemAround(std::vector<Vector3> points,
                                                                      std::vector<NodeConstraint> nodeConstraints) const
{
    if (nodeConstraints.empty() && problem) nodeConstraints = problem->constraints();
    std::unique_ptr<RbmProblem> result;
    try {
        result = std::make_unique<RbmProblem>(dimension, std::move(points), graph, std::move(nodeConstraints),
                                              options.weighting);
    } catch (const std::invalid_argument& error) {
        throw InputError(options.file, 0,
                         std::string("rigidBodyMotionSolver: the mesh and its boundary conditions do not define an RBM "
                                     "problem: ") +
                             error.what() +
                             " (every group of moving points needs a prescribed patch, e.g. fixedValue, holding it)");
    }
    if (edgeFactors) result->setEdgeWeightFactors(edgeFactors);
    return result;
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

std::unique_ptr<RbmSolver> RigidBodyMotionSolver::Impl::makeSolver(const RbmProblem& forProblem) const
{
    const bool linearized = options.formulation == RbmFormulation::linearized;
    if (options.coupling == RbmCoupling::decoupled) {
        DecoupledOptions decoupled;
        decoupled.model = linearized ? DecoupledModel::linearized : DecoupledModel::nonlinear;
        decoupled.linearSolver = options.linearSolver;
        if (options.relativeTolerance) decoupled.linearRelativeTolerance = *options.relativeTolerance;
        if (options.maxIterations) decoupled.maximumIterations = *options.maxIterations;
        decoupled.displacementTolerance = options.tolerance;
        return std::make_unique<DecoupledSolver>(forProblem, decoupled);
    }
    if (linearized) {
        CoupledLinearizedOptions coupled;
        coupled.linearSolver = options.linearSolver;
        if (options.relativeTolerance) coupled.relativeTolerance = *options.relativeTolerance;
        return std::make_unique<CoupledLinearizedSolver>(forProblem, coupled);
    }
    CoupledNewtonOptions newton;
    newton.linearSolver = options.linearSolver;
    if (options.relativeTolerance) {
        newton.relativeTolerance = *options.relativeTolerance;
        newton.linearRelativeTolerance = std::min(*options.relativeTolerance, newton.linearRelativeTolerance);
    }
    if (options.tolerance != RigidBodyMotionOptions{}.tolerance) {
        // The same scale as the core's default: tolerance × (mean w|d|) × √(unknown nodes).
        const CellNeighbourGraph& g = forProblem.graph();
        const auto& points = forProblem.referencePoints();
        double sum = 0.0;
        for (int i = 0; i < forProblem.nodeCount(); ++i)
            for (int e = g.offsets[i]; e < g.offsets[i + 1]; ++e) {
                Vector3 d = points[g.neighbours[e]] - points[i];
                if (dimension == 2) d.z = 0.0;
                sum += forProblem.edgeWeights()[e] * norm(d);
            }
        const double mean = g.neighbours.empty() ? 1.0 : sum / static_cast<double>(g.neighbours.size());
        newton.absoluteTolerance = options.tolerance * mean * std::sqrt(static_cast<double>(forProblem.unknownNodeCount()));
    }
    if (options.algorithm == RbmAlgorithm::localGlobal) {
        LocalGlobalOptions localGlobal;
        localGlobal.linearSolver = options.linearSolver;
        if (options.relativeTolerance) localGlobal.linearRelativeTolerance = *options.relativeTolerance;
        localGlobal.maximumIterations = options.maxIterations.value_or(200);
        localGlobal.displacementTolerance = options.tolerance;
        return std::make_unique<LocalGlobalThenNewton>(forProblem, localGlobal, newton);
    }
    if (options.algorithm == RbmAlgorithm::reducedNewton) {
        ReducedNewtonOptions reduced;
        reduced.linearSolver = options.linearSolver;
        reduced.relativeTolerance = newton.relativeTolerance;
        reduced.absoluteTolerance = newton.absoluteTolerance;
        reduced.displacementTolerance = options.displacementTolerance;
        if (options.maxIterations) reduced.maximumIterations = *options.maxIterations;
        return std::make_unique<ReducedNewtonSolver>(forProblem, reduced);
    }
    if (options.maxIterations) newton.maximumIterations = *options.maxIterations;
    return std::make_unique<CoupledNewtonSolver>(forProblem, newton);
}

Label RigidBodyMotionSolver::Impl::countInverted(std::span<const Vector3> nodeDisplacement, double* worstQuality,
                                                std::vector<Label>* invertedCells)
{
    if (invertedCells) invertedCells->clear();
    const bool remember = invertedCells == nullptr;
    static_assert(sizeof(Vector3) == 3 * sizeof(double));
    if (remember && checkedInverted >= 0 && checkedDisplacement.size() == nodeDisplacement.size() &&
        std::memcmp(nodeDisplacement.data(), checkedDisplacement.data(), nodeDisplacement.size() * sizeof(Vector3)) == 0) {
        // The same bits: the same figures.
        if (worstQuality) *worstQuality = checkedWorst;
        return checkedInverted;
    }
    double worst = std::numeric_limits<double>::infinity();
    Label inverted = 0;
    if (twoD) {
        const PlanarMesh& planar = twoD->planar;
        positions.resize(planar.points.size());
        for (std::size_t node = 0; node < positions.size(); ++node) {
            positions[node] = planar.points[node];
            positions[node].x += nodeDisplacement[node].x;
            positions[node].y += nodeDisplacement[node].y;
        }
        for (Label c = 0; c < planar.cellCount(); ++c) {
            if (isInvertedPolygon(planar.signedArea(c, positions))) {
                ++inverted;
                if (invertedCells) invertedCells->push_back(c);
            }
            if (!worstQuality && !remember) continue;
            const auto cell = planar.cell(c);
            if (cell.size() == 3)
                worst = std::min(worst, triangleMeanRatio(positions[cell[0]], positions[cell[1]], positions[cell[2]]));
            else if (cell.size() == 4)
                worst = std::min(worst, quadrilateralShape(positions[cell[0]], positions[cell[1]], positions[cell[2]],
                                                           positions[cell[3]]));
        }
    } else {
        const PolyMesh& mesh = owner.mesh();
        const std::vector<Vector3>& points0 = owner.points0();
        positions.resize(points0.size());
        for (std::size_t p = 0; p < positions.size(); ++p) positions[p] = points0[p] + nodeDisplacement[p];
        updateMeshGeometry(mesh, positions, geometry);
        const std::size_t cellCount = geometry.cellVolumes.size();
        smallestPyramid.assign(cellCount, std::numeric_limits<double>::infinity());
        faceCounts.assign(cellCount, 0);
        const auto& centres = geometry.cellCentres;
        const Label internalFaces = mesh.internalFaceCount();
        // Face pyramids with apex at the cell centre (ThesisQuality's inverted-cell test).
        for (Label f = 0; f < mesh.faceCount(); ++f) {
            const Vector3& area = geometry.faceAreas[f];
            const Vector3& centre = geometry.faceCentres[f];
            const Label own = mesh.owner[f];
            smallestPyramid[own] = std::min(smallestPyramid[own], tripleFacePyramid(area, centre, centres[own], true) / 3.0);
            ++faceCounts[own];
            if (f < internalFaces) {
                const Label nei = mesh.neighbour[f];
                smallestPyramid[nei] =
                    std::min(smallestPyramid[nei], tripleFacePyramid(area, centre, centres[nei], false) / 3.0);
                ++faceCounts[nei];
            }
        }
        for (std::size_t c = 0; c < cellCount; ++c) {
            const double volume = geometry.cellVolumes[c];
            if (isInvertedCell(volume, smallestPyramid[c])) {
                ++inverted;
                if (invertedCells) invertedCells->push_back(static_cast<Label>(c));
            }
            // Smallest pyramid relative to the mean pyramid V / faces: 1 for a cube, ≤ 0 when inverted.
            if ((worstQuality || remember) && std::abs(volume) > 0.0)
                worst = std::min(worst, smallestPyramid[c] * faceCounts[c] / std::abs(volume));
        }
        // Not kept between checks: the 3D workspace (face centres and areas, cell centres and
        // volumes, positions) is 215 MB at 10⁶ hexahedra, and the first check, of the initial
        // mesh, comes before the solve, whose peak it would raise (twist3D at 10⁶ cells,
        // rbmMoveMesh with the defaults: 3.54 → 3.3 GB). Allocating it again costs a step
        // about 1 % of its time there.
        geometry = MeshGeometry{};
        positions = std::vector<Vector3>{};
        smallestPyramid = std::vector<double>{};
        faceCounts = std::vector<int>{};
    }
    worst = std::isfinite(worst) ? worst : 1.0;
    if (worstQuality) *worstQuality = worst;
    if (remember) {
        checkedDisplacement.assign(nodeDisplacement.begin(), nodeDisplacement.end());
        checkedInverted = inverted;
        checkedWorst = worst;
    }
    return inverted;
}

void RigidBodyMotionSolver::Impl::untangleState(MotionSolveReport& report)
{
    // Only cells the solve inverted: an initial mesh that is already inverted is the user's.
    if (!options.untangle || initialInverted > 0 || countInverted(state.displacement) == 0) return;
    if (!simplices)
        simplices = std::make_unique<SimplexDecomposition>(twoD ? decomposeCells(twoD->planar)
                                                                : decomposeCells(owner.mesh()));
    const int n = nodeCount();
    std::vector<Vector3> moved(n);
    for (int node = 0; node < n; ++node) moved[node] = referencePoints[node] + state.displacement[node];
    std::vector<Vector3> displacement(n);
    std::vector<Label> cells;
    const InvertedCellTest test = [&](std::span<const Vector3> at) {
        for (int node = 0; node < n; ++node) displacement[node] = at[node] - referencePoints[node];
        countInverted(displacement, nullptr, &cells);
        return cells;
    };
    const UntangleResult result = untangle(*simplices, referencePoints, untangleConstraints(*problem), moved, test);
    // Only the free and sliding nodes moved: prescribed displacements stay bit-for-bit.
    for (int node = 0; node < n; ++node)
        if (problem->isUnknown(node)) state.displacement[node] = moved[node] - referencePoints[node];
    report.untangledCellCount = result.initialInverted - static_cast<Label>(result.remainingCells.size());
    if (result.untangled()) {
        report.reason += "; untangled " + std::to_string(result.initialInverted) + " inverted cell" +
                         (result.initialInverted == 1 ? "" : "s");
        return;
    }
    std::string where = result.describe(moved, *simplices);
    if (!result.remainingCells.empty()) {
        const Label first = result.remainingCells.front();
        const std::string patches = twoD ? cellPatchNames(twoD->planar, first) : cellPatchNames(owner.mesh(), first);
        if (!patches.empty()) where += " (cell " + std::to_string(first) + ": " + patches + ")";
    }
    report.reason += "; untangling: " + where;
}

void RigidBodyMotionSolver::Impl::writeBack()
{
    std::vector<Vector3>& displacement = owner.pointDisplacement();
    if (twoD) {
        const std::vector<Vector3> lifted = twoD->liftDisplacements(state.displacement);
        for (std::size_t p = 0; p < lifted.size(); ++p) {
            const Label node = twoD->nodeOfPoint[p];
            if (node < 0 || pointIsPrescribed[p]) continue;
            displacement[p] = prescribingPatch[node] == heldNode ? Vector3{} : lifted[p];
        }
    } else {
        for (int node = 0; node < nodeCount(); ++node) {
            if (pointIsPrescribed[node]) continue;
            displacement[node] = prescribingPatch[node] == heldNode ? Vector3{} : state.displacement[node];
        }
    }
}

// Nonlinear variants: the energy on the initial mesh for the total prescribed displacement,
// continued from the previous solve (or from the linearized solution at the first).
void RigidBodyMotionSolver::Impl::solveOnInitialMesh(std::span<const Vector3> target, MotionSolveReport& report)
{
    if (!baseSolver) baseSolver = makeSolver(*problem);
    const int n = nodeCount();
    const std::vector<Vector3> rest(hasState ? 0 : n);
    const BoundaryPath path(dimension, referencePoints, groupOffsets, groupNodes,
                            hasState ? std::span<const Vector3>(statePrescribed) : std::span<const Vector3>(rest), target);
    const bool automatic = options.automaticSubSteps();
    const int count = automatic ? 1 : options.subSteps;

    // The warm start: the last step's state itself, then each accepted segment's result, moved
    // and not copied (a time step of the 40k-node airfoil copied 2 MB twice).
    RbmState current;
    const RbmState* guess = hasState ? &state : nullptr;
    report.converged = true;
    SplitBudget splitting(automatic ? options.maxSubStepSplits : 0);
    RbmResult last;
    // Segment [from, to] of the path at depth `depth` of halving.
    auto solveSegment = [&](auto&& self, double from, double to, int depth) -> void {
        const std::vector<Vector3> boundary = path.at(to);
        RbmResult result = baseSolver->solve(boundary, guess);
        report.iterations += result.iterations;
        if (splitting.allows(depth) && !splitting.accept(depth, countInverted(result.displacement) > initialInverted)) {
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
    if (!baseSolver) baseSolver = makeSolver(*problem);
    const int n = nodeCount();
    const std::vector<Vector3> zero(n);
    const BoundaryPath path(dimension, referencePoints, groupOffsets, groupNodes, zero, target);
    const bool automatic = options.automaticSubSteps();
    int count = options.subSteps;
    bool capped = false;
    if (automatic) {
        count = rotationAwareSubStepCount(*problem, target, groupOffsets, groupNodes,
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
    SplitBudget splitting(automatic ? options.maxSubStepSplits : 0);
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
            const std::unique_ptr<RbmProblem> stepProblem = problemAround(std::move(points));
            result = makeSolver(*stepProblem)->solve(increment);
        }
        report.iterations += result.iterations;
        std::vector<Vector3> candidate(displacement);
        for (int node = 0; node < n; ++node) candidate[node] += result.displacement[node];
        if (splitting.allows(depth) && !splitting.accept(depth, countInverted(candidate) > initialInverted)) {
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
const std::vector<double>& RigidBodyMotionSolver::stiffeningFactors() const
{
    static const std::vector<double> none;
    return impl_->edgeFactors ? *impl_->edgeFactors : none;
}
const std::vector<Label>& RigidBodyMotionSolver::stiffeningPatches() const { return impl_->stiffenedPatches; }
Label RigidBodyMotionSolver::initialInvertedCellCount() const { return impl_->initialInverted; }

double RigidBodyMotionSolver::Impl::smallestCellSizeRatio() const
{
    // Per valid cell, its size now over its size in the reference mesh; the percentile, not
    // the minimum, so that the few cells the failed step itself degenerated next to the
    // inverted ones do not stand for the motion.
    std::vector<double> ratios;
    if (twoD) {
        const PlanarMesh& planar = twoD->planar;
        std::vector<Vector3> moved(referencePoints.size());
        for (std::size_t node = 0; node < moved.size(); ++node)
            moved[node] = referencePoints[node] + (hasState ? state.displacement[node] : Vector3{});
        for (Label c = 0; c < planar.cellCount(); ++c) {
            const double before = planar.signedArea(c), after = planar.signedArea(c, moved);
            if (before > 0.0 && after > 0.0) ratios.push_back(after / before);
        }
    } else {
        const PolyMesh& mesh = owner.mesh();
        const MeshGeometry before = computeMeshGeometry(mesh, owner.points0());
        const MeshGeometry after = computeMeshGeometry(mesh, owner.curPoints());
        for (std::size_t c = 0; c < before.cellVolumes.size(); ++c)
            if (before.cellVolumes[c] > 0.0 && after.cellVolumes[c] > 0.0)
                ratios.push_back(after.cellVolumes[c] / before.cellVolumes[c]);
    }
    if (ratios.empty()) return 0.0;
    const auto percentile = ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 100);
    std::nth_element(ratios.begin(), percentile, ratios.end());
    return *percentile;
}

std::string RigidBodyMotionSolver::describe() const
{
    const RigidBodyMotionOptions& o = impl_->options;
    std::string text = o.describe();
    if (o.stiffening.automaticPatches && !impl_->stiffenedPatches.empty()) {
        std::ostringstream stiffening;
        stiffening << " = power " << o.stiffening.exponent << " inverseDistance (";
        for (std::size_t k = 0; k < impl_->stiffenedPatches.size(); ++k)
            stiffening << (k ? " " : "") << mesh().patches[impl_->stiffenedPatches[k]].name;
        stiffening << ") while every prescribed patch moves rigidly";
        text += stiffening.str();
    }
    return text;
}

std::string RigidBodyMotionSolver::invertedStepAdvice() const
{
    const Impl& impl = *impl_;
    const RigidBodyMotionOptions& o = impl.options;
    // The robust choices the user's options leave out, each of which can change the result.
    std::vector<std::string> changes;
    if (o.formulation == RbmFormulation::linearized)
        changes.push_back("formulation nonlinear (exact rotations: the linearized form shears cells under large turns)");
    if (o.weighting != EdgeWeighting::inverseDistanceSquared)
        changes.push_back("weighting inverseDistanceSquared (keeps small and stretched cells rigid)");
    if (!o.automaticSubSteps())
        changes.push_back("subSteps auto (halves a sub-step that inverts cells, up to maxSubStepSplits times)");
    else if (o.maxSubStepSplits < RigidBodyMotionOptions{}.maxSubStepSplits)
        changes.push_back("a larger maxSubStepSplits");
    if (!o.stiffening.enabled()) changes.push_back("stiffening auto (the cells next to a moving body turn with it)");
    if (!o.untangle) changes.push_back("untangle on (moves the points around inverted cells until they are valid)");
    std::ostringstream text;
    if (!changes.empty()) {
        text << "In rigidBodyMotionSolverCoeffs, what can help this motion: ";
        for (std::size_t k = 0; k < changes.size(); ++k) text << (k ? "; " : "") << changes[k];
        text << ".";
        return text.str();
    }
    // The robust choices are in effect: say what the motion asks of the mesh.
    const std::vector<Vector3> target = impl.prescribedTarget();
    const std::vector<Vector3> zero(target.size());
    const double angle = BoundaryPath(impl.dimension, impl.referencePoints, impl.groupOffsets, impl.groupNodes, zero,
                                      target)
                             .largestRigidAngle() *
                         180.0 / std::numbers::pi;
    const double squeeze = impl.smallestCellSizeRatio();
    text << std::setprecision(2);
    if (squeeze < 0.35) {
        text << "None of rbm's options will help: the motion squeezes cells to " << squeeze
             << " of their size and less (a body closing a gap; 1 % of the cells), and rbm moves every node's neighbourhood as close to a "
                "rigid body as it can, which does not shrink: the cells nearest the gap fold. What can: more cells "
                "in the gap, a smaller motion between remeshings, or a Laplacian motion solver for this case.";
    } else if (angle > 1.0) {
        text << "None of rbm's options will help: the boundary turns by " << angle
             << " degrees, more than the cells between it and the fixed boundary can take with the defaults in effect "
                "(nonlinear, 1/|d|^2 weights, automatic sub-steps, stiffening, untangling). What can: more cells "
                "around the moving body, or a smaller rotation between remeshings.";
    } else {
        text << "None of rbm's options will help: the defaults in effect (nonlinear, 1/|d|^2 weights, automatic "
                "sub-steps, stiffening, untangling) are its most robust choices. A prescribed motion that "
                "deforms a patch or crosses another boundary does this; the step's mesh shows where.";
    }
    return text.str();
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
        impl.hasState = true;
        impl.statePrescribed = target;
        impl.untangleState(report);
    }
    impl.writeBack();
    if (impl.unconstrained.watchesPlanes()) report.warnings = impl.unconstrained.planeWarnings(curPoints());
    report.invertedCellCount = impl.countInverted(impl.state.displacement, &report.worstQuality);
    report.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return report;
}

} // namespace rbm::motion

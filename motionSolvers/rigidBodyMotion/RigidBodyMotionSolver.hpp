#pragma once
// rigidBodyMotionSolver: the OpenFOAM-facing RBM motion solver (thesis ch. 2, docs/method.md). It
// turns a PolyMesh and the boundary conditions of its point displacement into an RBM problem,
// solves it with the variant chosen in `rigidBodyMotionSolverCoeffs`
// (RigidBodyMotionOptions.hpp), and writes the displacement of every point back.
//
//  - Dimension. A pseudo-3D mesh (one layer of cells between `empty` or `wedge` planes) is
//    solved in 2D on the nodes of its front plane (3 unknowns per node) and lifted back to both
//    planes, each point keeping its out-of-plane coordinate (docs/method.md §6); every other mesh is
//    solved in 3D (6 unknowns per node, any cell type: the method only needs the
//    cell-neighbour graph).
//  - Node classes from the patch conditions of every point: prescribed beats sliding beats
//    free. A point on two sliding patches with different normals slides along the line where
//    they meet (RbmProblem's line nodes); on three planes without a common line, or on two
//    lines in 2D (they meet in a point), it is held where it is. In 2D, sliding normals are
//    projected into the plane; a sliding patch parallel to the plane leaves its nodes free.
//  - Time stepping (docs/method.md §5). Every solve() is for the TOTAL displacement relative to
//    points0. The nonlinear variants minimise the energy on the initial mesh, warm-started
//    from the previous solve, with the graph, the weights and the PETSc objects kept alive
//    between calls. The linearized variants apply the thesis' sub-step method (§2.6) from
//    points0 each time, so the mesh at time t still depends only on the boundary at time t.
//  - Sub-steps (§2.6). `subSteps N`: N equal steps of the boundary motion. `subSteps auto`:
//    the thesis' count for the linearized formulations (the smallest n with every prescribed
//    node's step shorter than its shortest edge, at most maxSubSteps), one step for the
//    nonlinear ones (exact rotations need no small steps); in both cases a sub-step whose mesh
//    has more inverted cells than the initial mesh is halved and retried, up to
//    maxSubStepSplits times. A patch whose prescribed motion is rigid is split into rotations,
//    not chords.
//  - Untangling (`untangle on`, the default; src/Untangling.hpp): when a solve leaves inverted
//    cells the initial mesh did not have, the free and sliding points around them are moved
//    until none is, prescribed points untouched; the reason says how many cells were repaired,
//    or which stay inverted and where.
//  - solve() never throws because cells inverted: MotionSolveReport counts them (2D: signed
//    area ≤ 0; 3D: a face pyramid or the volume ≤ 0, as ThesisQuality counts them).

#include "MotionSolver.hpp"
#include "RbmProblem.hpp"
#include "RigidBodyMotionOptions.hpp"

#include <memory>

namespace rbm {
struct PseudoTwoDMesh;
}

namespace rbm::motion {

class RigidBodyMotionSolver final : public MotionSolver {
public:
    static constexpr std::string_view typeNameString = "rigidBodyMotionSolver";

    // Throws rbm::InputError for bad coefficients, a pseudo-3D mesh that is not a clean
    // one-layer extrusion, unknown stiffening patches, or boundary conditions that leave a
    // group of nodes without any prescribed node holding it. PETSc must be initialised.
    RigidBodyMotionSolver(const PolyMesh& mesh, const io::Dictionary& coefficients,
                          std::unique_ptr<BoundaryConditions> conditions, std::filesystem::path caseDirectory);
    // The boundary described by a host that evaluates the boundary conditions itself
    // (MotionSolver.hpp); the same errors.
    RigidBodyMotionSolver(const PolyMesh& mesh, const io::Dictionary& coefficients, BoundaryDescription boundary,
                          std::filesystem::path caseDirectory);
    ~RigidBodyMotionSolver() override;

    std::string_view typeName() const override { return typeNameString; }
    MotionSolveReport solve() override;
    // The options in effect that a robust choice would change (formulation, weighting,
    // sub-steps, stiffening, untangling), or, with the robust choices in effect, what the
    // motion does that none of them can take (a squeeze, a rotation) and what can.
    std::string invertedStepAdvice() const override;
    // MemoryFit.hpp: `linearSolver automatic` may go matrix-free; throws when nothing fits.
    std::string fitIntoMemory(const AvailableMemory& available) override;

    const RigidBodyMotionOptions& options() const;
    // 2 for pseudo-3D meshes (solved on the front plane), 3 otherwise.
    int dimension() const;
    // The 2D mesh and the point maps of a pseudo-3D mesh; nullptr in 3D.
    const PseudoTwoDMesh* twoDMesh() const override;
    // options().describe(), and the patches `stiffening auto` chose.
    std::string describe() const override;
    // The RBM problem of the last solve (node classes, graph, weights); nullptr before the first.
    const RbmProblem* problem() const;
    // Per node (2D: planar node, in the plane's frame; 3D: mesh point): displacement and
    // rotation of the last solve.
    const RbmState& state() const;
    // The stiffening factors f_ij per graph edge (Stiffening.hpp) of the last solve (before
    // the first: of the construction); empty without stiffening, and with `stiffening auto`
    // when a prescribed patch did not move rigidly.
    // A copy: the solver lets go of them once its problem's weights hold them.
    std::vector<double> stiffeningFactors() const;
    // The patches the stiffening measures the distance to (indices into mesh().patches; with
    // `stiffening auto`, the default, chosen by automaticStiffeningPatches); empty without stiffening.
    const std::vector<Label>& stiffeningPatches() const;
    // `stiffening movingAndFixed`: the patches of the moving distance (EdgeStiffening.hpp's
    // rule: prescribed non-zero in some solve so far); empty before such a solve and where the
    // single factor of `auto` applies.
    const std::vector<Label>& stiffeningMovingPatches() const;
    // Inverted cells of the initial mesh (sub-steps are judged against this count).
    Label initialInvertedCellCount() const;

private:
    void initialise();

    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace rbm::motion

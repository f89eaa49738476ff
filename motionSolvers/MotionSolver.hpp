#pragma once
// The motion-solver interface, shaped like OpenFOAM's displacement motion solvers
// (displacementMotionSolver): a solver is built from a mesh, its coefficient dictionary
// and the point displacement field with its boundary conditions; it holds the initial
// points (points0) and the displacement of every mesh point; solve() computes the
// displacement of the points the boundary conditions leave free; curPoints() is
// points0 + displacement.
//
// The solver itself sees the boundary only through a BoundaryDescription (node class and
// sliding planes per patch) and the prescribed values in pointDisplacement(). Who fills them:
//  - from a case (rbmMoveMesh): the constructor with BoundaryConditions, rbm's own patch
//    conditions of the field dictionary (boundaryMotion/PatchBoundaryConditions.hpp);
//    updateBoundaryConditions(t) evaluates them at time t, then solve();
//  - from C++ (a flow or structure solver): setPatchDisplacement() prescribes a patch's
//    displacement directly every time step, then solve();
//  - from a host that evaluates its own boundary conditions (the OpenFOAM plugin): the
//    constructor with a BoundaryDescription; the host writes the prescribed points'
//    displacement into pointDisplacement() before every solve().
//
// Points on several patches: prescribed beats sliding beats free (a point on a moving wall
// and on a symmetry plane moves with the wall).

#include "BoundaryConditions.hpp"
#include "BoundaryDescription.hpp"
#include "FoamDictionary.hpp"
#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rbm {
struct PseudoTwoDMesh;
}

namespace rbm::motion {

struct AvailableMemory;   // rigidBodyMotion/MemoryEstimate.hpp

// What one solve() did, for the per-time-step log line.
struct MotionSolveReport {
    int subStepCount = 0;
    int iterations = 0;          // summed over sub-steps
    double residual = 0.0;       // final residual of the last sub-step
    double energy = 0.0;         // RBM energy of the result
    bool converged = false;
    std::string reason;          // PETSc's converged/diverged reason, or the iteration's
    Label invertedCellCount = 0; // cells with non-positive volume (3D) or area (2D) in curPoints()
    double worstQuality = 0.0;   // smallest cell quality (2D: q / F_shape; 3D: smallest pyramid ratio)
    Label untangledCellCount = 0; // inverted cells the solver's untangling stage repaired (rigidBodyMotionSolver)
    std::vector<std::string> warnings;  // what the front door must tell the user (a patch leaving its plane, ...)
    double wallSeconds = 0.0;
};

class MotionSolver {
public:
    // Boundary conditions rbm evaluates (boundaryMotion/PatchBoundaryConditions.hpp for
    // 0/pointDisplacement: makePatchBoundaryConditions). Throws std::invalid_argument for none.
    MotionSolver(const PolyMesh& mesh, const io::Dictionary& coefficients,
                 std::unique_ptr<BoundaryConditions> conditions, std::filesystem::path caseDirectory);
    // A boundary described by the host, which evaluates the boundary conditions itself and
    // writes the prescribed displacements into pointDisplacement(); updateBoundaryConditions
    // and setPatchDisplacement are then errors. Throws std::invalid_argument when `boundary`
    // does not have one entry per mesh patch.
    MotionSolver(const PolyMesh& mesh, const io::Dictionary& coefficients, BoundaryDescription boundary,
                 std::filesystem::path caseDirectory);
    virtual ~MotionSolver();
    MotionSolver(const MotionSolver&) = delete;
    MotionSolver& operator=(const MotionSolver&) = delete;

    virtual std::string_view typeName() const = 0;

    const PolyMesh& mesh() const { return mesh_; }
    const io::Dictionary& coefficients() const { return coefficients_; }
    const std::vector<Vector3>& points0() const { return points0_; }
    std::vector<Vector3>& pointDisplacement() { return pointDisplacement_; }
    // Node classes and sliding planes per patch, as solve() uses them.
    const BoundaryDescription& boundary() const { return boundary_; }
    // Counts the changes of boundary() (setPatchDisplacement replacing a condition): a solver
    // keeps what it derived from it while this stays the same.
    std::uint64_t boundaryRevision() const { return boundaryRevision_; }
    const std::vector<Vector3>& pointDisplacement() const { return pointDisplacement_; }

    // Evaluates every patch's boundary condition at `time` into pointDisplacement().
    void updateBoundaryConditions(double time);
    // Prescribes the displacement of a patch's points (OpenFOAM's localPoints order, one
    // per patch point), replacing its boundary condition from then on. Throws for an
    // unknown patch or a wrong length.
    void setPatchDisplacement(std::string_view patchName, std::span<const Vector3> displacement);

    // Computes the displacement of the free and sliding points.
    virtual MotionSolveReport solve() = 0;

    // The solver's settings in words, for a program's header (e.g. "coupled nonlinear
    // (reducedNewton), weighting inverseDistanceSquared, ..."); empty: nothing to say.
    virtual std::string describe() const { return {}; }

    // The 2D mesh a pseudo-2D case is solved on (its quality checks reuse it); nullptr when
    // the solver works on the 3D mesh.
    virtual const PseudoTwoDMesh* twoDMesh() const { return nullptr; }

    // After a solve that left inverted cells: which of this solver's options can help for
    // this motion, or why none will (one or more sentences). Empty: no advice of its own.
    virtual std::string invertedStepAdvice() const { return {}; }

    // Before the first solve: make the solve fit in `available` memory, or stop. A solver
    // with a memory model may choose a leaner linear solver of its own (the returned note
    // says so, for the log; empty: nothing changed) and throws std::runtime_error saying what
    // it needs when nothing fits. Without a model: nothing to do.
    virtual std::string fitIntoMemory(const AvailableMemory& available);

    // points0 + pointDisplacement.
    std::vector<Vector3> curPoints() const;

    // Hooks for a host program: the mesh was moved to `points` by someone else (the RBM
    // reference stays points0, as in OpenFOAM's displacement solvers) / its topology changed
    // (not supported: throws std::logic_error).
    virtual void movePoints(std::span<const Vector3> points);
    virtual void updateMesh();

protected:
    const PolyMesh& mesh_;
    io::Dictionary coefficients_;
    std::filesystem::path caseDirectory_;
    std::vector<Vector3> points0_;
    std::vector<Vector3> pointDisplacement_;
    BoundaryDescription boundary_;   // assigned in MotionSolver.cpp only, which counts it in boundaryRevision_
    std::uint64_t boundaryRevision_ = 0;
    // The conditions rbm evaluates; null when the host describes the boundary.
    std::unique_ptr<BoundaryConditions> conditions_;
};

} // namespace rbm::motion

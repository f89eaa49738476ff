#pragma once
// What happens to the points of a boundary patch whose condition neither prescribes nor slides
// them (zeroGradient, calculated, ... in 0/pointDisplacement): OpenFOAM's Laplacian solvers
// keep a planar wall of that kind in its plane, so a user reads such a patch as part of the
// domain's fixed shape, not as a surface free to bulge. rbm's rule:
//
//   by default its points slide on the patch's surface: each on the plane through its
//   reference position normal to the patch's point normal there (OpenFOAM's
//   PrimitivePatch::pointNormals of the reference mesh). A planar patch stays exactly in its
//   plane; on a curved one a point that slides a distance s leaves the surface by about
//   s²/2R (R its radius), and CurvedPatchProjection puts it back onto the patch's reference
//   faces after each solve. Where such a point is also on another sliding
//   patch it slides on their intersection line, on three it stays.
//
//   a patch listed in `floatingPatches (names, groups or "regular expressions");` of
//   rigidBodyMotionSolverCoeffs floats instead: its points move like interior points. When a
//   floating patch was planar, every step warns if its points leave that plane (beyond 1e-6
//   of the patch's shortest edge), naming the patch and the distance.
//
// The rule is the same for both front doors (rbmMoveMesh and the OpenFOAM plugin), which
// describe such patches as BoundaryNodeClass::free.

#include "BoundaryDescription.hpp"
#include "PolyMesh.hpp"
#include "RigidBodyMotionOptions.hpp"
#include "Vector3.hpp"

#include <span>
#include <string>
#include <vector>

namespace rbm::motion {

class UnconstrainedPatches {
public:
    // Reads `options.floatingPatches`; throws InputError (the options' file and the entry's
    // line) for a name that matches no patch, listing the valid ones.
    UnconstrainedPatches(const PolyMesh& mesh, std::span<const Vector3> points0, const RigidBodyMotionOptions& options);

    // True when the patch is listed in floatingPatches.
    bool floats(Label patch) const { return floating_[static_cast<std::size_t>(patch)]; }

    // Unit normals of the patch's points (its meshPoints order) in the reference mesh, the
    // planes its points slide on when the patch does not float. Computed at first use.
    const std::vector<Vector3>& slidingNormals(Label patch, std::span<const Label> meshPoints);

    // For every floating patch that was planar: a warning when `points` (all mesh points, in
    // their moved positions) leave its plane by more than 1e-6 of its shortest edge.
    std::vector<std::string> planeWarnings(std::span<const Vector3> points) const;
    bool watchesPlanes() const { return !floatingPlanes_.empty(); }
    // The same measure per watched patch, for a part that reduces it over the ranks: how far
    // `points` leave the plane, and the tolerance (1e-6 of the patch's shortest edge here).
    struct PlaneDeparture {
        Label patch = -1;
        double farthest = 0.0;
        double tolerance = 0.0;
    };
    std::vector<PlaneDeparture> planeDepartures(std::span<const Vector3> points) const;
    // The warning's words for a departure beyond the tolerance.
    std::string planeWarning(Label patch, double farthest) const;

private:
    struct FloatingPlane {
        Label patch = -1;
        Vector3 normal;          // unit
        Vector3 origin;          // a point of the plane
        double tolerance = 0.0;  // 1e-6 of the patch's shortest edge
        std::vector<Label> meshPoints;
    };

    const PolyMesh& mesh_;
    std::span<const Vector3> points0_;
    std::vector<bool> floating_;
    std::vector<std::vector<Vector3>> normals_;   // per patch, empty until first use
    std::vector<FloatingPlane> floatingPlanes_;
};

} // namespace rbm::motion

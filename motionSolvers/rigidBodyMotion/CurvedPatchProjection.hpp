#pragma once
// The second half of UnconstrainedPatches' rule for curved patches. A point of an
// unconstrained patch (zeroGradient, calculated, ...) that does not float slides on the tangent
// plane at its reference position; on a curved patch a slide s leaves the surface by about
// s²/2R (R its radius of curvature). After each solve these points are put back onto the
// patch's reference surface: the nearest point of its reference faces (2D: of its boundary
// edges in the plane), so the domain keeps its shape to the resolution of the reference faces.
//
// A node where the curved patch meets a sliding plane (3D: it slides on their line) is put
// onto the curve where the surface and that plane meet (alternate projections onto the
// surface and the plane, ending on the plane). Prescribed and held nodes keep their place. A
// planar patch (every point within 1e-6 of its shortest edge of one plane) needs nothing: its
// points never leave its plane.

#include "BoundaryDescription.hpp"
#include "PolyMesh.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "RbmProblem.hpp"
#include "Stiffening.hpp"
#include "UnconstrainedPatches.hpp"

#include <vector>

namespace rbm::motion {

// Whether `points` lie in one plane (3D) or on one line (2D, z ignored), to 1e-6 of `scale`.
bool pointsAreFlat(const std::vector<Vector3>& points, int dimension, double scale);

class CurvedPatchProjection {
public:
    CurvedPatchProjection() = default;   // nothing to project
    // `problem`: the node classes (its nodes are planar nodes of `twoD` in 2D, mesh points in 3D).
    CurvedPatchProjection(const PolyMesh& mesh, const std::vector<Vector3>& points0, const PseudoTwoDMesh* twoD,
                          const BoundaryDescription& boundary, const UnconstrainedPatches& unconstrained,
                          const RbmProblem& problem);

    bool empty() const { return patches_.empty(); }
    // The names of the curved patches whose points are projected.
    std::vector<std::string> patchNames(const PolyMesh& mesh) const;

    // `displacement` per node, relative to `referencePoints` (the problem's): the selected
    // nodes moved onto their patch's reference surface.
    void project(const std::vector<Vector3>& referencePoints, std::vector<Vector3>& displacement) const;

private:
    struct CurvedPatch {
        Label patch = -1;
        NearestSurface surface;
        std::vector<int> nodes;        // sliding on the patch alone
        std::vector<int> lineNodes;    // also on another sliding plane
        std::vector<Vector3> keptPlaneNormals;  // per line node: that plane's unit normal
    };
    std::vector<CurvedPatch> patches_;
    int dimension_ = 3;
};

} // namespace rbm::motion

#pragma once
// OpenFOAM's pseudo-3D (2D) meshes and their 2D form (docs/method.md §6).
//
// OpenFOAM runs 2D cases on one layer of cells between two planes:
//  - "empty": both planes are in patches of type empty (usually one patch, frontAndBack,
//    or two); the planes are parallel and every point has a twin on the other plane;
//  - "wedge" (axisymmetric): the planes are two patches of type wedge that meet at the
//    axis; a point on the back plane is its front twin rotated about the axis by the wedge
//    angle, and points on the axis are shared by both planes (twin = itself). An empty
//    patch with no faces (the usual "axis" patch) may be present.
//
// Extraction checks that the mesh is a clean one-layer extrusion and fails with an
// rbm::InputError naming the cell, face or point otherwise: every cell has exactly one
// face on each plane, the planes are planar, every side face joins one front edge to its
// twin edge, every front point has exactly one twin, each cell's back face is the twin of
// its front face, and (wedge) twins are related by one rotation.
//
// The 2D mesh (PlanarMesh) has one node per front-plane point and one cell per 3D cell
// (same numbering), polygons counter-clockwise seen from the frame normal (positive area =
// valid), edges from the side faces with their patches (internal first, upper-triangular,
// as in 3D). Its coordinates are in the PlaneFrame below: (x, y) in-plane, z along the normal.
//
// Mapping back: new 2D positions (or displacements) give new 3D points on both planes,
// each keeping its own out-of-plane coordinate; for a wedge the back plane receives the
// front displacement rotated by the wedge rotation, so it stays on its plane.

#include "MeshTopology.hpp"
#include "PlanarMesh.hpp"
#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <array>
#include <span>
#include <vector>

namespace rbm {

enum class PseudoTwoDKind { None, Empty, Wedge };

// A right-handed orthonormal frame (e1, e2, normal) = (local x, y, z). When the normal is
// exactly +x, +y or +z (`axis` = 0, 1, 2) the frame is the cyclic permutation
// (y, z, x), (z, x, y) or (x, y, z) and conversions are exact; `axis` is -1 otherwise.
struct PlaneFrame {
    Vector3 e1{1.0, 0.0, 0.0};
    Vector3 e2{0.0, 1.0, 0.0};
    Vector3 normal{0.0, 0.0, 1.0};
    int axis = 2;

    // The frame with this unit normal: a permutation frame when the normal is an axis
    // direction, otherwise e1 = the given in-plane direction (or any if that is zero).
    static PlaneFrame fromNormal(const Vector3& unitNormal, const Vector3& inPlaneDirection = {});

    Vector3 toLocal(const Vector3& global) const;   // (e1·p, e2·p, normal·p)
    Vector3 toGlobal(const Vector3& local) const;   // local.x e1 + local.y e2 + local.z normal
};

struct PseudoTwoDOptions {
    // Tolerance for planarity and twin checks, relative to the diagonal of the mesh's
    // bounding box (1e-5 accepts points written with OpenFOAM's default 6 digits).
    double relativeTolerance = 1e-5;
};

struct PseudoTwoDMesh {
    PseudoTwoDKind kind = PseudoTwoDKind::None;
    PlanarMesh planar;
    PlaneFrame frame;   // of the front plane; the normal points from the front plane into the cells

    std::vector<Label> frontPointOfNode;   // 3D point on the front plane, per 2D node
    std::vector<Label> backPointOfNode;    // its twin on the back plane (the same point on a wedge axis)
    std::vector<Label> nodeOfPoint;        // 2D node of every 3D point (-1 for points no face uses)
    std::vector<Label> twinOfPoint;        // the other plane's point, per 3D point (itself on a wedge axis; -1 unused)
    std::vector<Label> frontFaceOfCell;    // 3D face of each cell on the front plane
    std::vector<Label> backFaceOfCell;     // ... and on the back plane
    std::vector<Label> faceOfEdge;         // 3D side face of each 2D edge (-1 for edges on a wedge axis)

    // Wedge only: back point = axisPoint + R (front point − axisPoint), with R the rotation
    // by wedgeAngle (radians, right-handed) about wedgeAxis (unit). Identity for empty.
    Vector3 wedgeAxisPoint;
    Vector3 wedgeAxis;
    double wedgeAngle = 0.0;
    std::array<Vector3, 3> frontToBackRotation{Vector3{1, 0, 0}, Vector3{0, 1, 0}, Vector3{0, 0, 1}};   // rows of R

    Label nodeCount() const { return planar.nodeCount(); }

    // R v (v unchanged for empty meshes).
    Vector3 rotateFrontToBack(const Vector3& v) const;

    // 3D displacement of every 3D point from 2D node displacements (x, y in the frame; z is
    // ignored): front points move by the in-plane vector, back points by the same vector
    // (empty) or the vector rotated by R (wedge). Unused points get zero.
    std::vector<Vector3> liftDisplacements(std::span<const Vector3> nodeDisplacements) const;

    // New 3D points from the current 3D points `points` (those the extraction saw) and new
    // 2D node positions (x, y in the frame; z ignored). Identity positions give back
    // `points` exactly; the out-of-plane coordinate of every point is kept (exactly for
    // axis-aligned empty meshes), and in axis-aligned empty meshes whose twins share
    // in-plane coordinates both planes receive the 2D coordinates exactly.
    std::vector<Vector3> liftPositions(std::span<const Vector3> points, std::span<const Vector3> nodePositions) const;
};

// Empty when a patch of type empty has faces, Wedge when a patch of type wedge has faces
// (wedge wins: its empty axis patch has none), None otherwise. Looks at the patches only.
PseudoTwoDKind detectPseudoTwoD(const PolyMesh& mesh);

// Extracts the 2D mesh; throws rbm::InputError (file "") when the mesh is not pseudo-2D or
// not a clean one-layer extrusion, saying which cell, face or point is wrong.
PseudoTwoDMesh extractPseudoTwoD(const PolyMesh& mesh, const PseudoTwoDOptions& options = {});
PseudoTwoDMesh extractPseudoTwoD(const PolyMesh& mesh, const MeshTopology& topology,
                                 const PseudoTwoDOptions& options = {});

} // namespace rbm

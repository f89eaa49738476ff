#include "PseudoTwoDExtraction.hpp"

#include "InputError.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>

namespace rbm {

namespace {

enum PlaneSide : std::uint8_t { NoPlane = 0, FrontPlane = 1, BackPlane = 2, BothPlanes = 3 };

[[noreturn]] void fail(const std::string& message) { throw InputError("", 0, message); }

std::string str(Label value) { return std::to_string(value); }

std::string str(double value)
{
    std::ostringstream out;
    out.precision(6);
    out << value;
    return out.str();
}

std::string str(const Vector3& v)
{
    std::ostringstream out;
    out.precision(6);
    out << v;
    return out.str();
}

Vector3 areaVector(const PolyMesh& mesh, Label f)
{
    const auto face = mesh.face(f);
    Vector3 sum;
    for (std::size_t i = 0; i < face.size(); ++i) sum += cross(mesh.points[face[i]], mesh.points[face[(i + 1) % face.size()]]);
    return 0.5 * sum;
}

Vector3 normalised(const Vector3& v) { return v / norm(v); }

// Snaps a unit vector to ±x, ±y or ±z when its other components are negligible, so that
// axis-aligned meshes get an exact permutation frame despite rounding in the area sums.
Vector3 snapToAxis(const Vector3& n)
{
    for (int axis = 0; axis < 3; ++axis) {
        const double off = std::hypot(n[(axis + 1) % 3], n[(axis + 2) % 3]);
        if (off <= 1e-9 * std::abs(n[axis])) {
            Vector3 snapped;
            snapped[axis] = n[axis] > 0.0 ? 1.0 : -1.0;
            return snapped;
        }
    }
    return n;
}

// Dominant eigenvector of Σ a aᵀ/|a| over the faces of the given patches (area vectors a):
// the plane normal most of the area agrees with, whatever the sign of each face.
Vector3 dominantNormal(const PolyMesh& mesh, const std::vector<Label>& patches)
{
    double tensor[3][3] = {};
    for (Label p : patches) {
        const Patch& patch = mesh.patches[p];
        for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f) {
            const Vector3 a = areaVector(mesh, f);
            const double length = norm(a);
            if (!(length > 0.0)) continue;
            for (int i = 0; i < 3; ++i) {
                for (int j = 0; j < 3; ++j) tensor[i][j] += a[i] * a[j] / length;
            }
        }
    }
    int start = 0;
    for (int i = 1; i < 3; ++i) {
        if (tensor[i][i] > tensor[start][start]) start = i;
    }
    Vector3 v;
    v[start] = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
        Vector3 next;
        for (int i = 0; i < 3; ++i) next[i] = tensor[i][0] * v.x + tensor[i][1] * v.y + tensor[i][2] * v.z;
        const double length = norm(next);
        if (!(length > 0.0)) break;
        next /= length;
        const bool converged = normSquared(next - v) < 1e-30;
        v = next;
        if (converged) break;
    }
    return v;
}

std::string faceDescription(const PolyMesh& mesh, Label f)
{
    const Label patch = mesh.patchOfFace(f);
    if (patch < 0) return "internal face " + str(f);
    return "face " + str(f) + " (patch '" + mesh.patches[patch].name + "')";
}

} // namespace

// ------------------------------------------------------------------------------------------
// PlaneFrame

PlaneFrame PlaneFrame::fromNormal(const Vector3& unitNormal, const Vector3& inPlaneDirection)
{
    PlaneFrame frame;
    if (unitNormal == Vector3{1.0, 0.0, 0.0}) {
        frame = {{0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, unitNormal, 0};
    } else if (unitNormal == Vector3{0.0, 1.0, 0.0}) {
        frame = {{0.0, 0.0, 1.0}, {1.0, 0.0, 0.0}, unitNormal, 1};
    } else if (unitNormal == Vector3{0.0, 0.0, 1.0}) {
        frame = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, unitNormal, 2};
    } else {
        Vector3 e1 = inPlaneDirection - dot(inPlaneDirection, unitNormal) * unitNormal;
        if (norm(e1) < 1e-12) {
            // Any direction in the plane: project the axis least aligned with the normal.
            int least = 0;
            for (int a = 1; a < 3; ++a) {
                if (std::abs(unitNormal[a]) < std::abs(unitNormal[least])) least = a;
            }
            Vector3 axis;
            axis[least] = 1.0;
            e1 = axis - dot(axis, unitNormal) * unitNormal;
        }
        e1 = normalised(e1);
        frame = {e1, cross(unitNormal, e1), unitNormal, -1};
    }
    return frame;
}

Vector3 PlaneFrame::toLocal(const Vector3& p) const
{
    switch (axis) {
    case 0: return {p.y, p.z, p.x};
    case 1: return {p.z, p.x, p.y};
    case 2: return p;
    default: return {dot(e1, p), dot(e2, p), dot(normal, p)};
    }
}

Vector3 PlaneFrame::toGlobal(const Vector3& local) const
{
    switch (axis) {
    case 0: return {local.z, local.x, local.y};
    case 1: return {local.y, local.z, local.x};
    case 2: return local;
    default: return local.x * e1 + local.y * e2 + local.z * normal;
    }
}

// ------------------------------------------------------------------------------------------
// Mapping back

Vector3 PseudoTwoDMesh::rotateFrontToBack(const Vector3& v) const
{
    if (kind != PseudoTwoDKind::Wedge) return v;
    return {dot(frontToBackRotation[0], v), dot(frontToBackRotation[1], v), dot(frontToBackRotation[2], v)};
}

std::vector<Vector3> PseudoTwoDMesh::liftDisplacements(std::span<const Vector3> nodeDisplacements) const
{
    if (nodeDisplacements.size() != static_cast<std::size_t>(nodeCount())) {
        throw std::invalid_argument("liftDisplacements: expected one displacement per 2D node");
    }
    std::vector<Vector3> result(nodeOfPoint.size());
    for (std::size_t p = 0; p < nodeOfPoint.size(); ++p) {
        const Label node = nodeOfPoint[p];
        if (node < 0) continue;
        const Vector3 inPlane = frame.toGlobal({nodeDisplacements[node].x, nodeDisplacements[node].y, 0.0});
        const bool back = frontPointOfNode[node] != static_cast<Label>(p);
        result[p] = back ? rotateFrontToBack(inPlane) : inPlane;
    }
    return result;
}

std::vector<Vector3> PseudoTwoDMesh::liftPositions(std::span<const Vector3> points,
                                                   std::span<const Vector3> nodePositions) const
{
    if (points.size() != nodeOfPoint.size() || nodePositions.size() != static_cast<std::size_t>(nodeCount())) {
        throw std::invalid_argument("liftPositions: expected one 3D point per mesh point and one position per 2D node");
    }
    std::vector<Vector3> result(points.begin(), points.end());
    const bool exactAxes = kind == PseudoTwoDKind::Empty && frame.axis >= 0;
    for (std::size_t p = 0; p < points.size(); ++p) {
        const Label node = nodeOfPoint[p];
        if (node < 0) continue;
        const Vector3& reference = planar.points[node];
        const Vector3 displacement{nodePositions[node].x - reference.x, nodePositions[node].y - reference.y, 0.0};
        if (exactAxes) {
            // Permutation frame: set each in-plane coordinate directly when this point shares
            // it with the 2D node (a clean extrusion), else add the displacement; the
            // out-of-plane coordinate is never touched.
            const Vector3 local = frame.toLocal(points[p]);
            Vector3 moved = local;
            moved.x = local.x == reference.x ? nodePositions[node].x : local.x + displacement.x;
            moved.y = local.y == reference.y ? nodePositions[node].y : local.y + displacement.y;
            result[p] = frame.toGlobal(moved);
            continue;
        }
        const Vector3 inPlane = frame.toGlobal(displacement);
        const bool back = frontPointOfNode[node] != static_cast<Label>(p);
        result[p] = points[p] + (back ? rotateFrontToBack(inPlane) : inPlane);
    }
    return result;
}

// ------------------------------------------------------------------------------------------
// Detection and extraction

PseudoTwoDKind detectPseudoTwoD(const PolyMesh& mesh)
{
    bool empty = false;
    bool wedge = false;
    for (const Patch& patch : mesh.patches) {
        if (patch.faceCount <= 0) continue;
        if (patch.type == "wedge") wedge = true;
        if (patch.type == "empty") empty = true;
    }
    if (wedge) return PseudoTwoDKind::Wedge;
    if (empty) return PseudoTwoDKind::Empty;
    return PseudoTwoDKind::None;
}

PseudoTwoDMesh extractPseudoTwoD(const PolyMesh& mesh, const PseudoTwoDOptions& options)
{
    return extractPseudoTwoD(mesh, buildMeshTopology(mesh), options);
}

namespace {

// One extraction in progress: the mesh, what is known so far about its two planes, and the
// 2D mesh being filled. Each step is one of the checks the header lists, in order.
struct Extraction {
    const PolyMesh& mesh;
    const MeshTopology& topology;
    PseudoTwoDMesh& result;
    bool wedge;
    std::string planeType;
    Label pointCount;
    Label faceCount;
    Label cellCount;
    double tolerance = 0.0;
    std::vector<bool> isPlanePatch;
    std::vector<Label> planePatches;
    std::vector<std::uint8_t> faceSide;
    Vector3 frontNormal;   // outward normal of the front plane faces (points out of the cells)
    Vector3 backNormal;
    std::vector<std::uint8_t> pointSide;
    std::vector<bool> used;
    double frontLevel = 0.0, backLevel = 0.0;
    std::vector<bool> covered;   // per polygon edge (cell, local index)
    Label axisPatch = -1;
    Label zeroFaceEmptyPatches = 0;

    // The state for `result`, whose kind is already detected (not None).
    Extraction(const PolyMesh& mesh, const MeshTopology& topology, PseudoTwoDMesh& result)
        : mesh(mesh), topology(topology), result(result), wedge(result.kind == PseudoTwoDKind::Wedge),
          planeType(wedge ? "wedge" : "empty"), pointCount(mesh.pointCount()), faceCount(mesh.faceCount()),
          cellCount(topology.cellCount)
    {
    }

    // The tolerance: options' relative tolerance times the bounding box diagonal.
    void measureTolerance(const PseudoTwoDOptions& options)
    {
        Vector3 low{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
        Vector3 high = -low;
        for (const Vector3& p : mesh.points) {
            for (int a = 0; a < 3; ++a) {
                low[a] = std::min(low[a], p[a]);
                high[a] = std::max(high[a], p[a]);
            }
        }
        tolerance = options.relativeTolerance * norm(high - low);
        if (!(tolerance > 0.0)) fail("the mesh has no extent (all points coincide)");
    }

    // The patches of the planes' type; a wedge needs exactly two with faces and no empty faces.
    void findPlanePatches()
    {
        isPlanePatch.assign(mesh.patches.size(), false);
        for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
            const Patch& patch = mesh.patches[p];
            if (patch.type != planeType) continue;
            isPlanePatch[p] = true;
            if (patch.faceCount > 0) planePatches.push_back(static_cast<Label>(p));
        }
        if (!wedge) return;
        for (const Patch& patch : mesh.patches) {
            if (patch.type == "empty" && patch.faceCount > 0) {
                fail("patch '" + patch.name + "' is of type empty and has " + str(patch.faceCount)
                     + " faces, but the mesh also has wedge patches; an axisymmetric case has exactly two wedge "
                       "patches and at most an empty axis patch without faces");
            }
        }
        if (planePatches.size() != 2) {
            fail("the mesh has " + std::to_string(planePatches.size())
                 + " wedge patches with faces; expected exactly 2 (the front and back planes of the wedge)");
        }
    }

    // Wedge: the first wedge patch is the front plane, the second the back; each one plane.
    void classifyWedgeFaces()
    {
        for (int side = 0; side < 2; ++side) {
            const Patch& patch = mesh.patches[planePatches[side]];
            Vector3 sum;
            for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f) sum += areaVector(mesh, f);
            if (!(norm(sum) > 0.0)) fail("wedge patch '" + patch.name + "' has zero total area");
            const Vector3 n = normalised(sum);
            for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f) {
                const Vector3 a = areaVector(mesh, f);
                if (!(dot(a, n) > 0.5 * norm(a))) {
                    fail(faceDescription(mesh, f) + " is not parallel to the rest of wedge patch '" + patch.name
                         + "' (patch normal " + str(n) + ", face area vector " + str(a) + "); a wedge patch is one plane");
                }
                faceSide[f] = side == 0 ? FrontPlane : BackPlane;
            }
            (side == 0 ? frontNormal : backNormal) = n;
        }
    }

    // Empty: the plane normal n, oriented so that its largest component is positive.
    Vector3 emptyPlaneNormal() const
    {
        // One or two empty patches hold both planes: split the faces by the direction of
        // their outward normal along the mean plane normal. The reference direction is the
        // dominant one of the area-weighted normals (so that a few wrong faces in an empty
        // patch are the ones reported, not the planes).
        const Vector3 reference = dominantNormal(mesh, planePatches);
        Vector3 sum;
        for (Label p : planePatches) {
            const Patch& patch = mesh.patches[p];
            for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f) {
                const Vector3 a = areaVector(mesh, f);
                sum += dot(a, reference) >= 0.0 ? a : -a;
            }
        }
        if (!(norm(sum) > 0.0)) fail("the empty patches have zero total area");
        Vector3 n = snapToAxis(normalised(sum));
        // Orient the normal so that its largest component is positive (+x, +y or +z for
        // axis-aligned meshes); the front plane is the one whose faces point along −n.
        int largest = 0;
        for (int a = 1; a < 3; ++a) {
            if (std::abs(n[a]) > std::abs(n[largest])) largest = a;
        }
        if (n[largest] < 0.0) n = -n;
        return n;
    }

    // Empty: each face of the empty patches on the front (along −n) or back (along n) plane.
    void classifyEmptyFaces()
    {
        const Vector3 n = emptyPlaneNormal();
        Label frontFaces = 0, backFaces = 0;
        for (Label p : planePatches) {
            const Patch& patch = mesh.patches[p];
            for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f) {
                const Vector3 a = areaVector(mesh, f);
                const double cosine = dot(a, n) / norm(a);
                if (cosine < -0.5) {
                    faceSide[f] = FrontPlane;
                    ++frontFaces;
                } else if (cosine > 0.5) {
                    faceSide[f] = BackPlane;
                    ++backFaces;
                } else {
                    fail(faceDescription(mesh, f) + " is not parallel to the empty planes (plane normal " + str(n)
                         + ", face area vector " + str(a) + "); empty patches must hold only the two planes");
                }
            }
        }
        if (frontFaces == 0 || backFaces == 0) {
            fail("all " + str(frontFaces + backFaces) + " faces of the empty patches point the same way (along "
                 + str(frontFaces == 0 ? n : -n) + "); expected a front and a back plane");
        }
        frontNormal = -n;
        backNormal = n;
    }

    // Every cell: exactly one face on each plane (one layer of cells).
    void findPlaneFacesOfCells()
    {
        result.frontFaceOfCell.assign(static_cast<std::size_t>(cellCount), -1);
        result.backFaceOfCell.assign(static_cast<std::size_t>(cellCount), -1);
        for (Label c = 0; c < cellCount; ++c) {
            Label front = 0, back = 0;
            for (Label f : topology.facesOf(c)) {
                if (faceSide[f] == FrontPlane) {
                    ++front;
                    result.frontFaceOfCell[c] = f;
                } else if (faceSide[f] == BackPlane) {
                    ++back;
                    result.backFaceOfCell[c] = f;
                }
            }
            if (front + back != 2) {
                fail("cell " + str(c) + " has " + str(front + back) + (front + back == 1 ? " face" : " faces") + " on " + planeType
                     + " patches; expected exactly 2, one on each plane (the mesh must be one layer of cells)");
            }
            if (front != 1) {
                fail("cell " + str(c) + " has both of its " + planeType + "-patch faces on the "
                     + (front == 2 ? "front" : "back") + " plane; expected one face on each plane");
            }
        }
    }

    // Points: which plane(s) they lie on, and which points any face uses.
    void classifyPoints()
    {
        pointSide.assign(static_cast<std::size_t>(pointCount), NoPlane);
        used.assign(static_cast<std::size_t>(pointCount), false);
        for (Label f = 0; f < faceCount; ++f) {
            for (Label p : mesh.face(f)) {
                pointSide[p] |= faceSide[f];
                used[p] = true;
            }
        }
    }

    // The mean level of each plane along its normal, and the planarity of each plane.
    void measurePlaneLevels()
    {
        Label frontCount = 0, backCount = 0;
        for (Label p = 0; p < pointCount; ++p) {
            if (pointSide[p] & FrontPlane) { frontLevel += dot(frontNormal, mesh.points[p]); ++frontCount; }
            if (pointSide[p] & BackPlane) { backLevel += dot(backNormal, mesh.points[p]); ++backCount; }
        }
        frontLevel /= static_cast<double>(frontCount);
        backLevel /= static_cast<double>(backCount);
        for (int side = 0; side < 2; ++side) {
            // Report the point farthest from the plane's mean level.
            double worst = 0.0;
            Label worstPoint = -1;
            for (Label p = 0; p < pointCount; ++p) {
                if (!(pointSide[p] & (side == 0 ? FrontPlane : BackPlane))) continue;
                const double distance = std::abs(dot(side == 0 ? frontNormal : backNormal, mesh.points[p])
                                                 - (side == 0 ? frontLevel : backLevel));
                if (distance > worst) {
                    worst = distance;
                    worstPoint = p;
                }
            }
            if (worst > tolerance) {
                fail(std::string("the ") + (side == 0 ? "front" : "back") + " " + planeType
                     + " plane is not planar: point " + str(worstPoint) + " " + str(mesh.points[worstPoint]) + " is "
                     + str(worst) + " away from it (tolerance " + str(tolerance) + ")");
            }
        }
    }

    // Empty planes apart; every used point on a plane, and (empty) on only one.
    void checkPointsOnPlanes() const
    {
        if (!wedge && !(-frontLevel < backLevel - tolerance)) {
            fail("the front and back empty planes are not separated: the front plane lies at " + str(-frontLevel)
                 + " and the back plane at " + str(backLevel) + " along " + str(backNormal));
        }
        for (Label p = 0; p < pointCount; ++p) {
            if (!used[p]) continue;
            if (pointSide[p] == NoPlane) {
                fail("point " + str(p) + " " + str(mesh.points[p]) + " lies on neither " + planeType
                     + " plane; a pseudo-2D mesh has all its points on the two planes (one layer of cells)");
            }
            if (pointSide[p] == BothPlanes && !wedge) {
                fail("point " + str(p) + " " + str(mesh.points[p])
                     + " is used by faces on both empty planes; the front and back planes must have distinct points");
            }
        }
    }

    // Records front and back as twins (found on face f); each point has exactly one twin.
    void link(Label front, Label back, Label f)
    {
        std::vector<Label>& twin = result.twinOfPoint;
        for (auto [from, to] : {std::pair{front, back}, std::pair{back, front}}) {
            if (twin[from] == -1) {
                twin[from] = to;
            } else if (twin[from] != to) {
                fail("point " + str(from) + " on the " + (from == front ? "front" : "back") + " plane is joined to "
                     "two points on the other plane (" + str(twin[from]) + " and " + str(to) + ", the second by "
                     + faceDescription(mesh, f) + "); expected exactly one twin");
            }
        }
    }

    // Side face f: checks it joins a front edge to a back edge and links the twins it joins.
    void linkSideFace(Label f)
    {
        const auto face = mesh.face(f);
        const std::size_t n = face.size();
        int frontCount = 0, backCount = 0;
        std::size_t firstFront = n, lastFront = n;
        for (std::size_t i = 0; i < n; ++i) {
            if (pointSide[face[i]] & FrontPlane) {
                ++frontCount;
                (firstFront == n ? firstFront : lastFront) = i;
            }
            if (pointSide[face[i]] & BackPlane) ++backCount;
        }
        if (frontCount != 2 || backCount != 2 || !(lastFront - firstFront == 1 || lastFront - firstFront == n - 1)) {
            fail(faceDescription(mesh, f) + " has " + std::to_string(frontCount) + " points on the front plane and "
                 + std::to_string(backCount) + " on the back plane; a side face of a one-layer mesh joins one edge "
                 "of the front plane (2 adjacent points) to its twin edge on the back plane");
        }
        for (std::size_t i = 0; i < n; ++i) {
            const Label p = face[i], q = face[(i + 1) % n];
            if (pointSide[p] == FrontPlane && pointSide[q] == BackPlane) link(p, q, f);
            if (pointSide[p] == BackPlane && pointSide[q] == FrontPlane) link(q, p, f);
        }
    }

    // Twins, from the side faces: each joins a front edge (a, b) to its twin (b', a').
    void findTwins()
    {
        std::vector<Label>& twin = result.twinOfPoint;
        twin.assign(static_cast<std::size_t>(pointCount), -1);
        for (Label p = 0; p < pointCount; ++p) {
            if (pointSide[p] == BothPlanes) twin[p] = p;   // on the wedge axis
        }
        for (Label f = 0; f < faceCount; ++f) {
            if (faceSide[f] != NoPlane) continue;
            linkSideFace(f);
        }
        for (Label p = 0; p < pointCount; ++p) {
            if (used[p] && twin[p] == -1) {
                fail("point " + str(p) + " " + str(mesh.points[p]) + " on the "
                     + (pointSide[p] == FrontPlane ? "front" : "back")
                     + " plane has no twin on the other plane: no side face joins it to the other plane");
            }
        }
    }

    // Wedge rotation: R takes the front plane's outward normal to minus the back's.
    void findWedgeRotation()
    {
        const Vector3 axisVector = cross(frontNormal, -backNormal);
        if (norm(axisVector) < 1e-12) {
            fail("the two wedge patches are parallel (normals " + str(frontNormal) + " and " + str(backNormal)
                 + "); expected two planes meeting at the axis");
        }
        const Vector3 k = normalised(axisVector);
        result.wedgeAxis = k;
        result.wedgeAngle = std::atan2(norm(axisVector), dot(frontNormal, -backNormal));
        // A point of the axis: the intersection of the two planes with the plane k·x = 0.
        result.wedgeAxisPoint = (frontLevel * cross(backNormal, k) + backLevel * cross(k, frontNormal))
                                / dot(frontNormal, cross(backNormal, k));
        const double c = std::cos(result.wedgeAngle), s = std::sin(result.wedgeAngle);
        for (int row = 0; row < 3; ++row) {
            Vector3 unit;
            unit[row] = 1.0;
            // Row `row` of R = R^T applied to e_row (Rodrigues' formula with angle −θ).
            result.frontToBackRotation[row] = c * unit - s * cross(k, unit) + (1.0 - c) * dot(k, unit) * k;
        }
        checkWedgeTwins(k);
    }

    // Wedge: every back twin is its front point rotated by R about the axis (within 10 tolerances).
    void checkWedgeTwins(const Vector3& k) const
    {
        const std::vector<Label>& twin = result.twinOfPoint;
        for (Label p = 0; p < pointCount; ++p) {
            if (pointSide[p] != FrontPlane || !used[p]) continue;
            const Vector3 expected =
                result.wedgeAxisPoint + result.rotateFrontToBack(mesh.points[p] - result.wedgeAxisPoint);
            const double error = norm(expected - mesh.points[twin[p]]);
            if (error > 10.0 * tolerance) {
                fail("point " + str(p) + " " + str(mesh.points[p]) + " and its twin " + str(twin[p]) + " "
                     + str(mesh.points[twin[p]]) + " are not related by the wedge rotation of "
                     + str(result.wedgeAngle * 180.0 / std::numbers::pi) + " degrees about the axis through "
                     + str(result.wedgeAxisPoint) + " along " + str(k) + " (off by " + str(error) + ")");
            }
        }
    }

    // Frame and nodes: one node per front-plane point, in point order.
    void numberNodes()
    {
        const std::vector<Label>& twin = result.twinOfPoint;
        result.frame = wedge ? PlaneFrame::fromNormal(snapToAxis(-frontNormal), result.wedgeAxis)
                             : PlaneFrame::fromNormal(backNormal);
        result.nodeOfPoint.assign(static_cast<std::size_t>(pointCount), -1);
        PlanarMesh& planar = result.planar;
        for (Label p = 0; p < pointCount; ++p) {
            if (!used[p] || !(pointSide[p] & FrontPlane)) continue;
            result.nodeOfPoint[p] = static_cast<Label>(result.frontPointOfNode.size());
            result.frontPointOfNode.push_back(p);
            result.backPointOfNode.push_back(twin[p]);
            planar.points.push_back(result.frame.toLocal(mesh.points[p]));
        }
        for (Label p = 0; p < pointCount; ++p) {
            if (used[p] && pointSide[p] == BackPlane) result.nodeOfPoint[p] = result.nodeOfPoint[twin[p]];
        }
    }

    // Cells: the front face reversed is counter-clockwise seen from the frame normal.
    void buildCells()
    {
        const std::vector<Label>& twin = result.twinOfPoint;
        PlanarMesh& planar = result.planar;
        planar.cellOffsets.assign(1, 0);
        planar.cellOffsets.reserve(static_cast<std::size_t>(cellCount) + 1);
        planar.cellPoints.reserve(mesh.facePoints.size() / 4 + 16);
        for (Label c = 0; c < cellCount; ++c) {
            const auto front = mesh.face(result.frontFaceOfCell[c]);
            const auto back = mesh.face(result.backFaceOfCell[c]);
            bool twinFaces = front.size() == back.size();
            for (std::size_t i = 0; i < back.size() && twinFaces; ++i) {
                twinFaces = std::find(front.begin(), front.end(), twin[back[i]]) != front.end();
            }
            if (!twinFaces) {
                fail("cell " + str(c) + ": its back-plane face " + str(result.backFaceOfCell[c])
                     + " is not the twin of its front-plane face " + str(result.frontFaceOfCell[c]) + " (" + str(Label(front.size()))
                     + " and " + str(Label(back.size())) + " points)");
            }
            for (auto it = front.rbegin(); it != front.rend(); ++it) planar.cellPoints.push_back(result.nodeOfPoint[*it]);
            planar.cellOffsets.push_back(static_cast<Label>(planar.cellPoints.size()));
        }
    }

    // Local index k in cell c of the edge from node a to node b, or -1.
    Label polygonEdge(Label c, Label a, Label b) const
    {
        const auto polygon = result.planar.cell(c);
        for (std::size_t k = 0; k < polygon.size(); ++k) {
            if (polygon[k] == a && polygon[(k + 1) % polygon.size()] == b) return static_cast<Label>(k);
        }
        return -1;
    }

    // Marks edge `local` of cell c (nodes a, b) as covered by side face f; twice is an error.
    void cover(Label c, Label local, Label a, Label b, Label f)
    {
        const std::size_t index = static_cast<std::size_t>(result.planar.cellOffsets[c] + local);
        if (covered[index]) {
            fail("cell " + str(c) + " has two side faces on its edge between points " + str(result.frontPointOfNode[a])
                 + " and " + str(result.frontPointOfNode[b]) + " (the second is " + faceDescription(mesh, f) + ")");
        }
        covered[index] = true;
    }

    // The 2D edge of side face f: its front nodes, in its owner's (and neighbour's) polygon.
    void addEdge(Label f)
    {
        PlanarMesh& planar = result.planar;
        const auto face = mesh.face(f);
        Label a = -1, b = -1;
        for (Label p : face) {
            if (pointSide[p] & FrontPlane) (a == -1 ? a : b) = result.nodeOfPoint[p];
        }
        const Label owner = mesh.owner[f];
        Label k = polygonEdge(owner, a, b);
        if (k < 0) {
            std::swap(a, b);
            k = polygonEdge(owner, a, b);
        }
        if (k < 0) {
            fail(faceDescription(mesh, f) + " joins front-plane points " + str(result.frontPointOfNode[a]) + " and "
                 + str(result.frontPointOfNode[b]) + ", which are not an edge of its owner cell " + str(owner));
        }
        cover(owner, k, a, b, f);
        if (f < mesh.internalFaceCount()) {
            const Label neighbour = mesh.neighbour[f];
            const Label kn = polygonEdge(neighbour, b, a);
            if (kn < 0) {
                fail(faceDescription(mesh, f) + " joins cells " + str(owner) + " and " + str(neighbour)
                     + ", but its front edge is not an edge of cell " + str(neighbour) + " in the opposite direction");
            }
            cover(neighbour, kn, a, b, f);
            planar.edgeNeighbour.push_back(neighbour);
        }
        planar.edgePoints.push_back(a);
        planar.edgePoints.push_back(b);
        planar.edgeOwner.push_back(owner);
        result.faceOfEdge.push_back(f);
    }

    // Edges from the side faces, in face order (internal first, then patch by patch).
    void addSideFaceEdges()
    {
        PlanarMesh& planar = result.planar;
        covered.assign(planar.cellPoints.size(), false);
        for (Label f = 0; f < mesh.internalFaceCount(); ++f) addEdge(f);
        for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
            const Patch& patch = mesh.patches[p];
            if (isPlanePatch[p]) continue;
            if (wedge && patch.type == "empty") {   // no faces (checked above): the axis
                ++zeroFaceEmptyPatches;
                axisPatch = static_cast<Label>(p);
                continue;
            }
            PlanarPatch planarPatch{patch.name, patch.type, planar.edgeCount(), 0, static_cast<Label>(p)};
            for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f) addEdge(f);
            planarPatch.edgeCount = planar.edgeCount() - planarPatch.startEdge;
            planar.patches.push_back(std::move(planarPatch));
        }
    }

    // Polygon edges without a side face: allowed only on a wedge axis (collapsed faces).
    void addAxisEdges()
    {
        PlanarMesh& planar = result.planar;
        PlanarPatch axis{"axis", "empty", planar.edgeCount(), 0, -1};
        if (zeroFaceEmptyPatches == 1) {
            axis.name = mesh.patches[axisPatch].name;
            axis.polyMeshPatch = axisPatch;
        }
        for (Label c = 0; c < cellCount; ++c) {
            const auto polygon = planar.cell(c);
            for (std::size_t k = 0; k < polygon.size(); ++k) {
                if (covered[static_cast<std::size_t>(planar.cellOffsets[c]) + k]) continue;
                const Label a = polygon[k], b = polygon[(k + 1) % polygon.size()];
                const bool onAxis = result.frontPointOfNode[a] == result.backPointOfNode[a]
                                    && result.frontPointOfNode[b] == result.backPointOfNode[b];
                if (!onAxis) {
                    fail("the edge between points " + str(result.frontPointOfNode[a]) + " and "
                         + str(result.frontPointOfNode[b]) + " of cell " + str(c)
                         + " on the front plane has no side face joining it to the back plane");
                }
                planar.edgePoints.push_back(a);
                planar.edgePoints.push_back(b);
                planar.edgeOwner.push_back(c);
                result.faceOfEdge.push_back(-1);
            }
        }
        axis.edgeCount = planar.edgeCount() - axis.startEdge;
        if (axis.edgeCount > 0 || zeroFaceEmptyPatches > 0) planar.patches.push_back(std::move(axis));
    }
};

} // namespace

PseudoTwoDMesh extractPseudoTwoD(const PolyMesh& mesh, const MeshTopology& topology, const PseudoTwoDOptions& options)
{
    PseudoTwoDMesh result;
    result.kind = detectPseudoTwoD(mesh);
    if (result.kind == PseudoTwoDKind::None) {
        fail("the mesh has no patch of type empty or wedge with faces, so it is not a pseudo-2D case "
             "(one layer of cells between two empty or wedge planes)");
    }
    Extraction extraction(mesh, topology, result);
    extraction.measureTolerance(options);
    // Plane patches and the front / back side of every plane face.
    extraction.findPlanePatches();
    extraction.faceSide.assign(static_cast<std::size_t>(mesh.faceCount()), NoPlane);
    if (extraction.wedge) extraction.classifyWedgeFaces();
    else extraction.classifyEmptyFaces();
    extraction.findPlaneFacesOfCells();
    extraction.classifyPoints();
    extraction.measurePlaneLevels();
    extraction.checkPointsOnPlanes();
    extraction.findTwins();
    if (extraction.wedge) extraction.findWedgeRotation();
    extraction.numberNodes();
    extraction.buildCells();
    extraction.addSideFaceEdges();
    extraction.addAxisEdges();
    return result;
}

} // namespace rbm

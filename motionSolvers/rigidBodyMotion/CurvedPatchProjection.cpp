#include "CurvedPatchProjection.hpp"

#include "PatchNormals.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rbm::motion {

bool pointsAreFlat(const std::vector<Vector3>& points, int dimension, double scale)
{
    if (points.size() < 3) return true;
    const Vector3 origin = points.front();
    // The farthest point from the first and, in 3D, the one farthest from their line span the
    // plane; in 2D the first two spanning a line suffice.
    std::size_t far = 0;
    for (std::size_t k = 1; k < points.size(); ++k)
        if (normSquared(points[k] - origin) > normSquared(points[far] - origin)) far = k;
    const Vector3 axis = points[far] - origin;
    if (!(norm(axis) > 0.0)) return true;
    const Vector3 direction = axis / norm(axis);
    const double tolerance = 1e-6 * scale;
    if (dimension == 2) {
        for (const Vector3& p : points) {
            const Vector3 r{p.x - origin.x, p.y - origin.y, 0.0};
            if (std::abs(r.x * direction.y - r.y * direction.x) > tolerance) return false;
        }
        return true;
    }
    Vector3 normal{};
    double largest = 0.0;
    for (const Vector3& p : points) {
        const Vector3 candidate = cross(direction, p - origin);
        if (norm(candidate) > largest) {
            largest = norm(candidate);
            normal = candidate;
        }
    }
    if (!(largest > 0.0)) return true;   // all on one line
    normal = normal / largest;
    return std::all_of(points.begin(), points.end(),
                       [&](const Vector3& p) { return std::abs(dot(p - origin, normal)) <= tolerance; });
}

namespace {


double shortestEdge(const std::vector<Vector3>& points, const CellNeighbourGraph& graph, const std::vector<int>& nodes)
{
    double shortest = std::numeric_limits<double>::infinity();
    for (int node : nodes)
        for (int e = graph.offsets[node]; e < graph.offsets[node + 1]; ++e)
            shortest = std::min(shortest, norm(points[graph.neighbours[e]] - points[node]));
    return shortest;
}

} // namespace

CurvedPatchProjection::CurvedPatchProjection(const PolyMesh& mesh, const std::vector<Vector3>& points0,
                                             const PseudoTwoDMesh* twoD, const BoundaryDescription& boundary,
                                             const UnconstrainedPatches& unconstrained, const RbmProblem& problem)
{
    const std::vector<Vector3>& reference = problem.referencePoints();
    dimension_ = problem.dimension();
    for (std::size_t p = 0; p < boundary.size() && p < mesh.patches.size(); ++p) {
        const Label patch = static_cast<Label>(p);
        if (boundary[p].nodeClass != BoundaryNodeClass::free || unconstrained.floats(patch) ||
            boundary[p].meshPoints.empty())
            continue;
        // The patch's nodes, and those of them that slide on it alone.
        std::vector<int> patchNodes;
        for (Label point : boundary[p].meshPoints) {
            const int node = twoD ? twoD->nodeOfPoint[point] : static_cast<int>(point);
            if (node >= 0) patchNodes.push_back(node);
        }
        std::sort(patchNodes.begin(), patchNodes.end());
        patchNodes.erase(std::unique(patchNodes.begin(), patchNodes.end()), patchNodes.end());
        std::vector<Vector3> positions;
        for (int node : patchNodes) positions.push_back(reference[node]);
        if (pointsAreFlat(positions, problem.dimension(), shortestEdge(reference, problem.graph(), patchNodes))) continue;
        CurvedPatch curved;
        curved.patch = patch;
        // In 3D, the patch's own point normals tell its tangent plane from the other plane of a
        // line node: the other is the one of the two less aligned with the patch's normal.
        std::vector<Vector3> pointNormals;
        if (!twoD) pointNormals = patchPointNormals(mesh, patch, boundary[p].meshPoints, points0);
        for (std::size_t k = 0; k < patchNodes.size(); ++k) {
            const int node = patchNodes[k];
            const NodeConstraint& constraint = problem.constraints()[node];
            if (constraint.kind != NodeKind::sliding) continue;
            if (constraint.secondNormal == Vector3{}) {
                curved.nodes.push_back(node);
                continue;
            }
            if (twoD) continue;
            // patchNodes is sorted; meshPoints is not: find the node's own normal.
            const auto at = std::find(boundary[p].meshPoints.begin(), boundary[p].meshPoints.end(), node);
            const Vector3& own = pointNormals[static_cast<std::size_t>(at - boundary[p].meshPoints.begin())];
            const Vector3 first = constraint.normal / norm(constraint.normal);
            const Vector3 second = constraint.secondNormal / norm(constraint.secondNormal);
            curved.lineNodes.push_back(node);
            curved.keptPlaneNormals.push_back(std::abs(dot(first, own)) < std::abs(dot(second, own)) ? first : second);
        }
        if (curved.nodes.empty() && curved.lineNodes.empty()) continue;
        if (twoD) {
            std::vector<Label> planarPatches;
            for (Label q = 0; q < static_cast<Label>(twoD->planar.patches.size()); ++q)
                if (twoD->planar.patches[q].polyMeshPatch == patch) planarPatches.push_back(q);
            curved.surface = patchSurface(twoD->planar, planarPatches);
        } else {
            const std::vector<Label> patches{patch};
            curved.surface = patchSurface(mesh, points0, patches);
        }
        if (curved.surface.empty()) continue;
        patches_.push_back(std::move(curved));
    }
}

std::vector<std::string> CurvedPatchProjection::patchNames(const PolyMesh& mesh) const
{
    std::vector<std::string> names;
    for (const CurvedPatch& curved : patches_) names.push_back(mesh.patches[static_cast<std::size_t>(curved.patch)].name);
    return names;
}

void CurvedPatchProjection::project(const std::vector<Vector3>& referencePoints,
                                    std::vector<Vector3>& displacement) const
{
    for (const CurvedPatch& curved : patches_) {
        int hint = -1;
        for (int node : curved.nodes) {
            Vector3 moved = referencePoints[node] + displacement[node];
            if (dimension_ == 2) moved.z = 0.0;   // the planar patch's edges lie in z = 0
            const Vector3 onSurface = curved.surface.nearestPoint(moved, hint);
            displacement[node].x = onSurface.x - referencePoints[node].x;
            displacement[node].y = onSurface.y - referencePoints[node].y;
            if (dimension_ == 3) displacement[node].z = onSurface.z - referencePoints[node].z;
        }
        for (std::size_t k = 0; k < curved.lineNodes.size(); ++k) {
            const int node = curved.lineNodes[k];
            const Vector3& origin = referencePoints[node];
            const Vector3& normal = curved.keptPlaneNormals[k];
            Vector3 moved = origin + displacement[node];
            // Each pass halves the distance to the curve at the least (surfaces meeting at an
            // angle); at right angles one pass is exact.
            for (int pass = 0; pass < 4; ++pass) {
                moved = curved.surface.nearestPoint(moved, hint);
                moved -= dot(moved - origin, normal) * normal;
            }
            displacement[node] = moved - origin;
        }
    }
}

} // namespace rbm::motion

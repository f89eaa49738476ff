#include "UnconstrainedPatches.hpp"

#include "InputError.hpp"
#include "KeywordPattern.hpp"
#include "PatchNormals.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace rbm::motion {

namespace {

bool patchMatches(const Patch& patch, const std::string& name)
{
    if (patch.name == name) return true;
    if (std::find(patch.inGroups.begin(), patch.inGroups.end(), name) != patch.inGroups.end()) return true;
    return io::isPatternKeyword(name) && io::patternMatches(name, patch.name);
}

double shortestPatchEdge(const PolyMesh& mesh, const Patch& patch, std::span<const Vector3> points)
{
    double shortest = std::numeric_limits<double>::infinity();
    for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f) {
        const auto face = mesh.face(f);
        for (std::size_t i = 0; i < face.size(); ++i)
            shortest = std::min(shortest, norm(points[face[(i + 1) % face.size()]] - points[face[i]]));
    }
    return shortest;
}

} // namespace

UnconstrainedPatches::UnconstrainedPatches(const PolyMesh& mesh, std::span<const Vector3> points0,
                                           const RigidBodyMotionOptions& options)
    : mesh_(mesh), points0_(points0), floating_(mesh.patches.size(), false), normals_(mesh.patches.size())
{
    for (const std::string& name : options.floatingPatches) {
        bool found = false;
        for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
            if (!patchMatches(mesh.patches[p], name)) continue;
            floating_[p] = true;
            found = true;
        }
        if (!found)
            throw InputError(options.file, options.floatingPatchesLine,
                             "floatingPatches: no patch matches " + name + ". Valid patches are: " + patchNameList(mesh));
    }
    // The floating patches that are planar in the reference mesh: their plane is watched.
    for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
        const Patch& patch = mesh.patches[p];
        if (!floating_[p] || patch.faceCount == 0) continue;
        FloatingPlane plane;
        plane.patch = static_cast<Label>(p);
        plane.meshPoints = patchMeshPoints(mesh, plane.patch);
        Vector3 areaSum{};
        for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f)
            areaSum += faceAreaNormal(mesh.face(f), points0);
        if (!(norm(areaSum) > 0.0)) continue;
        plane.normal = areaSum / norm(areaSum);
        plane.origin = points0[plane.meshPoints.front()];
        plane.tolerance = 1e-6 * shortestPatchEdge(mesh, patch, points0);
        bool planar = true;
        for (Label point : plane.meshPoints)
            planar = planar && std::abs(dot(points0[point] - plane.origin, plane.normal)) <= plane.tolerance;
        if (planar) floatingPlanes_.push_back(std::move(plane));
    }
}

const std::vector<Vector3>& UnconstrainedPatches::slidingNormals(Label patch, std::span<const Label> meshPoints)
{
    std::vector<Vector3>& normals = normals_[static_cast<std::size_t>(patch)];
    if (normals.size() != meshPoints.size()) normals = patchPointNormals(mesh_, patch, meshPoints, points0_);
    return normals;
}

std::vector<UnconstrainedPatches::PlaneDeparture> UnconstrainedPatches::planeDepartures(
    std::span<const Vector3> points) const
{
    std::vector<PlaneDeparture> departures;
    for (const FloatingPlane& plane : floatingPlanes_) {
        double farthest = 0.0;
        for (Label point : plane.meshPoints)
            farthest = std::max(farthest, std::abs(dot(points[point] - plane.origin, plane.normal)));
        departures.push_back({plane.patch, farthest, plane.tolerance});
    }
    return departures;
}

std::string UnconstrainedPatches::planeWarning(Label patch, double farthest) const
{
    std::ostringstream text;
    text << "patch " << mesh_.patches[static_cast<std::size_t>(patch)].name
         << " (in floatingPatches) was planar; its points now leave its plane by up to " << farthest
         << " (remove it from floatingPatches to keep it in its plane)";
    return text.str();
}

std::vector<std::string> UnconstrainedPatches::planeWarnings(std::span<const Vector3> points) const
{
    std::vector<std::string> warnings;
    for (const PlaneDeparture& departure : planeDepartures(points))
        if (departure.farthest > departure.tolerance) warnings.push_back(planeWarning(departure.patch, departure.farthest));
    return warnings;
}

} // namespace rbm::motion

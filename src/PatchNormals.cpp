#include "PatchNormals.hpp"

namespace rbm {

namespace {
constexpr double vSmall = 1e-300;   // OpenFOAM VSMALL
} // namespace

Vector3 faceAreaNormal(std::span<const Label> face, std::span<const Vector3> points)
{
    const std::size_t n = face.size();
    if (n == 3) {
        const Vector3& a = points[face[0]];
        return 0.5 * cross(points[face[1]] - a, points[face[2]] - a);
    }
    Vector3 centre{};
    for (Label p : face) centre += points[p];
    centre /= static_cast<double>(n);
    Vector3 area{};
    for (std::size_t i = 0; i < n; ++i) {
        const Vector3& a = points[face[i]];
        const Vector3& b = points[face[(i + 1) % n]];
        area += 0.5 * cross(b - a, centre - a);
    }
    return area;
}

Vector3 faceUnitNormal(std::span<const Label> face, std::span<const Vector3> points)
{
    const Vector3 area = faceAreaNormal(face, points);
    return area / (norm(area) + vSmall);
}

std::vector<Vector3> patchPointNormals(const PolyMesh& mesh, Label patchIndex, std::span<const Label> meshPoints,
                                       std::span<const Vector3> points)
{
    const Patch& patch = mesh.patches.at(static_cast<std::size_t>(patchIndex));
    // Mesh point -> patch point, only for this patch's points.
    std::vector<Label> localIndex(static_cast<std::size_t>(mesh.pointCount()), -1);
    for (std::size_t i = 0; i < meshPoints.size(); ++i) localIndex[static_cast<std::size_t>(meshPoints[i])] = static_cast<Label>(i);
    std::vector<Vector3> normals(meshPoints.size(), Vector3{});
    for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f) {
        const Vector3 n = faceUnitNormal(mesh.face(f), points);
        for (Label p : mesh.face(f)) normals[static_cast<std::size_t>(localIndex[static_cast<std::size_t>(p)])] += n;
    }
    for (Vector3& n : normals) n /= norm(n) + vSmall;
    return normals;
}

} // namespace rbm

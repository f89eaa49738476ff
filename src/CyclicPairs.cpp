#include "CyclicPairs.hpp"

#include "InputError.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace rbm {

namespace {

// OpenFOAM's default matchTolerance: a partner within this fraction of the face's shortest edge.
constexpr double matchTolerance = 1e-4;

std::string quoted(const Patch& patch) { return "'" + patch.name + "'"; }

// The mean of a face's points (the matching only needs corresponding points of both faces).
Vector3 pointAverage(std::span<const Label> face, std::span<const Vector3> points)
{
    Vector3 sum{};
    for (Label p : face) sum += points[p];
    return sum / static_cast<double>(face.size());
}

double shortestEdge(std::span<const Label> face, std::span<const Vector3> points)
{
    double shortest = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < face.size(); ++k)
        shortest = std::min(shortest, norm(points[face[(k + 1) % face.size()]] - points[face[k]]));
    return shortest;
}

// The neighbour of `spec`, checked: it exists, is a cyclic patch of `specs` and names spec back.
const CyclicPatchSpec& neighbourOf(const PolyMesh& mesh, const CyclicPatchSpec& spec,
                                   std::span<const CyclicPatchSpec> specs, const std::string& file)
{
    const Patch& patch = mesh.patches[spec.patch];
    const Label other = mesh.findPatch(spec.neighbourPatch);
    const auto found = std::find_if(specs.begin(), specs.end(), [&](const CyclicPatchSpec& s) { return s.patch == other; });
    if (other < 0 || found == specs.end() || other == spec.patch)
        throw InputError(file, 0,
                         "cyclic patch " + quoted(patch) + ": its neighbourPatch '" + spec.neighbourPatch +
                             "' is not another cyclic patch of the mesh. Valid patches are: " + patchNameList(mesh));
    if (found->neighbourPatch != patch.name)
        throw InputError(file, 0,
                         "cyclic patch " + quoted(patch) + " names '" + spec.neighbourPatch +
                             "' as its neighbourPatch, but that patch names '" + found->neighbourPatch + "'");
    return *found;
}

// The transform x_B = R (x_A − c) + c + t of a pairing from the specification and the face
// centres: the rotation angle about the given axis, or the mean separation.
void measureTransform(const PolyMesh& mesh, std::span<const Vector3> points, const CyclicPatchSpec& spec,
                      CyclicPatchPairing& pairing, const std::string& file)
{
    const Patch& a = mesh.patches[pairing.patchA];
    const Patch& b = mesh.patches[pairing.patchB];
    if (spec.transform == CyclicTransformKind::rotational) {
        const double length = norm(spec.rotationAxis);
        if (!(length > 0.0) || !std::isfinite(length))
            throw InputError(file, 0, "cyclic patch " + quoted(mesh.patches[spec.patch]) + ": rotationAxis is zero");
        const Vector3 axis = spec.rotationAxis / length;
        // Σ over the faces of the angle's sine and cosine (weighted by the radii): atan2 of the sums.
        double sine = 0.0, cosine = 0.0;
        for (Label i = 0; i < a.faceCount; ++i) {
            Vector3 fromA = pointAverage(mesh.face(a.startFace + i), points) - spec.rotationCentre;
            Vector3 fromB = pointAverage(mesh.face(b.startFace + i), points) - spec.rotationCentre;
            fromA -= dot(fromA, axis) * axis;
            fromB -= dot(fromB, axis) * axis;
            sine += dot(axis, cross(fromA, fromB));
            cosine += dot(fromA, fromB);
        }
        pairing.rotation = rotationMatrix(axis, std::atan2(sine, cosine));
        pairing.centre = spec.rotationCentre;
        return;
    }
    Vector3 sum{};
    for (Label i = 0; i < a.faceCount; ++i)
        sum += pointAverage(mesh.face(b.startFace + i), points) - pointAverage(mesh.face(a.startFace + i), points);
    pairing.separation = a.faceCount > 0 ? sum / static_cast<double>(a.faceCount) : Vector3{};
}

std::string describeTransform(const CyclicPatchPairing& pairing)
{
    std::ostringstream text;
    const Matrix3& r = pairing.rotation;
    const double angle = std::acos(std::clamp(0.5 * (r(0, 0) + r(1, 1) + r(2, 2) - 1.0), -1.0, 1.0));
    if (angle > 0.0) text << "the rotation of " << angle * 180.0 / 3.141592653589793 << " degrees about " << pairing.centre;
    else text << "the separation " << pairing.separation;
    return text.str();
}

// Every point of A's face i paired with the nearest point of B's face i to its image.
void matchPoints(const PolyMesh& mesh, std::span<const Vector3> points, CyclicPatchPairing& pairing,
                 const std::string& file)
{
    const Patch& a = mesh.patches[pairing.patchA];
    const Patch& b = mesh.patches[pairing.patchB];
    std::map<Label, Label> partnerOfA, partnerOfB;
    for (Label i = 0; i < a.faceCount; ++i) {
        const std::span<const Label> faceA = mesh.face(a.startFace + i);
        const std::span<const Label> faceB = mesh.face(b.startFace + i);
        if (faceA.size() != faceB.size())
            throw InputError(file, 0,
                             "cyclic patches " + quoted(a) + " and " + quoted(b) + ": face " + std::to_string(i) +
                                 " has " + std::to_string(faceA.size()) + " points on one and " +
                                 std::to_string(faceB.size()) + " on the other (their faces must match in order)");
        const double tolerance = matchTolerance * shortestEdge(faceA, points);
        for (Label pa : faceA) {
            const Vector3 image = pairing.rotation * (points[pa] - pairing.centre) + pairing.centre + pairing.separation;
            Label best = -1;
            double bestDistance = std::numeric_limits<double>::infinity();
            for (Label pb : faceB)
                if (const double d = norm(points[pb] - image); d < bestDistance) {
                    bestDistance = d;
                    best = pb;
                }
            if (!(bestDistance <= tolerance)) {
                std::ostringstream message;
                message << "cyclic patch " << quoted(a) << ": point " << pa << " at " << points[pa] << " (face "
                        << i << ") has no partner on " << quoted(b) << ": under " << describeTransform(pairing)
                        << " its image " << image << " is " << bestDistance << " from the nearest point of face " << i
                        << " of " << quoted(b) << ", more than " << matchTolerance
                        << " of the face's shortest edge. The two patches do not match"
                        << " (check their faces, and transform, separationVector, rotationAxis and rotationCentre)";
                throw InputError(file, 0, message.str());
            }
            const auto [atA, newA] = partnerOfA.emplace(pa, best);
            const auto [atB, newB] = partnerOfB.emplace(best, pa);
            if (atA->second != best || atB->second != pa)
                throw InputError(file, 0,
                                 "cyclic patches " + quoted(a) + " and " + quoted(b) + ": point " + std::to_string(pa) +
                                     " of " + quoted(a) + " matches two different points (or two points match point " +
                                     std::to_string(best) + " of " + quoted(b) + ")");
            if (newA) pairing.points.emplace_back(pa, best);
        }
    }
}

} // namespace

std::vector<CyclicPatchPairing> pairCyclicPatches(const PolyMesh& mesh, std::span<const Vector3> points,
                                                  std::span<const CyclicPatchSpec> specs, const std::string& file)
{
    std::vector<CyclicPatchPairing> pairings;
    for (const CyclicPatchSpec& spec : specs) {
        const CyclicPatchSpec& neighbour = neighbourOf(mesh, spec, specs, file);
        if (spec.patch > neighbour.patch) continue;  // paired from the lower index
        CyclicPatchPairing pairing;
        pairing.patchA = spec.patch;
        pairing.patchB = neighbour.patch;
        const Patch& a = mesh.patches[pairing.patchA];
        const Patch& b = mesh.patches[pairing.patchB];
        if (a.faceCount != b.faceCount)
            throw InputError(file, 0,
                             "cyclic patches " + quoted(a) + " and " + quoted(b) + " have " +
                                 std::to_string(a.faceCount) + " and " + std::to_string(b.faceCount) +
                                 " faces (the two halves of a cyclic must match face by face)");
        // A rotation given on either side (OpenFOAM writes it on both); else a translation.
        const CyclicPatchSpec& given = spec.transform == CyclicTransformKind::rotational ? spec : neighbour;
        measureTransform(mesh, points, given, pairing, file);
        matchPoints(mesh, points, pairing, file);
        pairings.push_back(std::move(pairing));
    }
    return pairings;
}

} // namespace rbm

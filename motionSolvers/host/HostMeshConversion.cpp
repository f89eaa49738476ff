#include "HostMeshConversion.hpp"

#include <stdexcept>
#include <string>

namespace rbm::host {

PolyMesh toPolyMesh(const HostMesh& host)
{
    if (host.points.size() % 3 != 0) throw std::invalid_argument("HostMesh: points is not a multiple of 3 long");
    if (host.faceOffsets.empty() || host.faceOffsets.size() != host.owner.size() + 1)
        throw std::invalid_argument("HostMesh: faceOffsets needs one entry per face and one more");
    PolyMesh mesh;
    mesh.points.resize(host.points.size() / 3);
    for (std::size_t p = 0; p < mesh.points.size(); ++p)
        mesh.points[p] = {host.points[3 * p], host.points[3 * p + 1], host.points[3 * p + 2]};
    mesh.faceOffsets.assign(host.faceOffsets.begin(), host.faceOffsets.end());
    mesh.facePoints.assign(host.faceVertices.begin(), host.faceVertices.end());
    mesh.owner.assign(host.owner.begin(), host.owner.end());
    mesh.neighbour.assign(host.neighbour.begin(), host.neighbour.end());
    for (const HostPatch& patch : host.patches)
        mesh.patches.push_back({patch.name, patch.type, patch.groups, patch.startFace, patch.faceCount, patch.entries});
    return mesh;
}

motion::BoundaryDescription toBoundaryDescription(const PolyMesh& mesh, const std::vector<HostPatchBoundary>& boundary,
                                                  const char* solverName)
{
    const std::string name(solverName);
    if (boundary.size() != mesh.patches.size())
        throw std::invalid_argument(name + ": " + std::to_string(boundary.size()) + " patch boundaries given for " +
                                    std::to_string(mesh.patches.size()) + " patches");
    motion::BoundaryDescription description(boundary.size());
    for (std::size_t p = 0; p < boundary.size(); ++p) {
        const HostPatchBoundary& host = boundary[p];
        motion::BoundaryPatchDescription& patch = description[p];
        patch.meshPoints = patchMeshPoints(mesh, static_cast<Label>(p));
        switch (host.nodeClass) {
        case HostNodeClass::prescribed: patch.nodeClass = motion::BoundaryNodeClass::prescribed; break;
        case HostNodeClass::free: patch.nodeClass = motion::BoundaryNodeClass::free; break;
        case HostNodeClass::ignored: patch.nodeClass = motion::BoundaryNodeClass::ignored; break;
        case HostNodeClass::coupled: patch.nodeClass = motion::BoundaryNodeClass::coupled; break;
        case HostNodeClass::sliding:
            patch.nodeClass = motion::BoundaryNodeClass::sliding;
            patch.mirror = host.mirror;
            if (host.slidingNormals.size() != 3 * patch.meshPoints.size())
                throw std::invalid_argument(name + ": sliding patch " + mesh.patches[p].name + " has " +
                                            std::to_string(host.slidingNormals.size()) + " normal components for " +
                                            std::to_string(patch.meshPoints.size()) + " points");
            patch.slidingNormals.resize(patch.meshPoints.size());
            for (std::size_t k = 0; k < patch.meshPoints.size(); ++k)
            {
                const Vector3 n{host.slidingNormals[3 * k], host.slidingNormals[3 * k + 1], host.slidingNormals[3 * k + 2]};
                const double length = norm(n);
                patch.slidingNormals[k] = length > 0.0 ? n / length : n;
            }
            break;
        }
    }
    return description;
}

void readVectors(const double* displacement, std::vector<Vector3>& vectors)
{
    for (std::size_t p = 0; p < vectors.size(); ++p)
        vectors[p] = {displacement[3 * p], displacement[3 * p + 1], displacement[3 * p + 2]};
}

void writeVectors(const std::vector<Vector3>& vectors, double* displacement)
{
    for (std::size_t p = 0; p < vectors.size(); ++p) {
        displacement[3 * p] = vectors[p].x;
        displacement[3 * p + 1] = vectors[p].y;
        displacement[3 * p + 2] = vectors[p].z;
    }
}

} // namespace rbm::host

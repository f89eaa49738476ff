#pragma once
// A PolyMesh in the host interface's form (motionSolvers/host/HostMotionSolver.hpp's HostMesh),
// as a host such as the OpenFOAM plugin hands it over: for the host solvers' tests.

#include "HostMotionSolver.hpp"
#include "PolyMesh.hpp"

namespace rbm::test {

inline host::HostMesh toHostMesh(const PolyMesh& mesh)
{
    host::HostMesh host;
    for (const Vector3& p : mesh.points) host.points.insert(host.points.end(), {p.x, p.y, p.z});
    host.faceOffsets.assign(mesh.faceOffsets.begin(), mesh.faceOffsets.end());
    host.faceVertices.assign(mesh.facePoints.begin(), mesh.facePoints.end());
    host.owner.assign(mesh.owner.begin(), mesh.owner.end());
    host.neighbour.assign(mesh.neighbour.begin(), mesh.neighbour.end());
    for (const Patch& patch : mesh.patches)
        host.patches.push_back({patch.name, patch.type, patch.inGroups, patch.startFace, patch.faceCount,
                                patch.otherEntries});
    return host;
}

} // namespace rbm::test

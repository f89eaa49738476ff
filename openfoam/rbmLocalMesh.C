#include "rbmLocalMesh.H"

#include "rbmHostPatch.H"
#include "rbmPointNumbering.H"

Foam::rbmLocalMesh::rbmLocalMesh(const polyMesh& mesh, const pointField& points0)
:
    nRealPatches_(rbmRealPatchCount(mesh.boundaryMesh()))
{
    const rbmPointNumbering numbering = rbmGlobalPointNumbering(mesh);
    globalPointLabels_.assign(numbering.pointToGlobal.begin(), numbering.pointToGlobal.end());

    host_.points.reserve(3*points0.size());
    for (const point& p : points0)
    {
        host_.points.push_back(p.x());
        host_.points.push_back(p.y());
        host_.points.push_back(p.z());
    }
    const faceList& faces = mesh.faces();
    host_.faceOffsets.reserve(faces.size() + 1);
    for (const face& f : faces)
    {
        host_.faceVertices.insert(host_.faceVertices.end(), f.begin(), f.end());
        host_.faceOffsets.push_back(static_cast<int>(host_.faceVertices.size()));
    }
    host_.owner.assign(mesh.faceOwner().begin(), mesh.faceOwner().end());
    host_.neighbour.assign(mesh.faceNeighbour().begin(), mesh.faceNeighbour().end());
    for (const polyPatch& patch : mesh.boundaryMesh())
    {
        rbm::host::HostPatch hostPatch = rbmHostPatch(patch);
        hostPatch.startFace = static_cast<int>(patch.start());
        hostPatch.faceCount = static_cast<int>(patch.size());
        host_.patches.push_back(hostPatch);
    }
}

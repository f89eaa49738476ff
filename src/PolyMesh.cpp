#include "PolyMesh.hpp"

#include <algorithm>

namespace rbm {

Label PolyMesh::cellCount() const
{
    Label largest = -1;
    for (Label c : owner) largest = std::max(largest, c);
    for (Label c : neighbour) largest = std::max(largest, c);
    return largest + 1;
}

void PolyMesh::addFace(std::span<const Label> pointLabels)
{
    facePoints.insert(facePoints.end(), pointLabels.begin(), pointLabels.end());
    faceOffsets.push_back(static_cast<Label>(facePoints.size()));
}

Label PolyMesh::patchOfFace(Label f) const
{
    for (std::size_t p = 0; p < patches.size(); ++p) {
        if (f >= patches[p].startFace && f < patches[p].startFace + patches[p].faceCount) return static_cast<Label>(p);
    }
    return -1;
}

Label PolyMesh::findPatch(const std::string& name) const
{
    for (std::size_t p = 0; p < patches.size(); ++p) {
        if (patches[p].name == name) return static_cast<Label>(p);
    }
    return -1;
}

std::string patchNameList(const PolyMesh& mesh)
{
    std::string names;
    for (const Patch& patch : mesh.patches) names += (names.empty() ? "" : " ") + patch.name;
    return names;
}

std::vector<Label> patchMeshPoints(const PolyMesh& mesh, Label patchIndex)
{
    const Patch& patch = mesh.patches.at(static_cast<std::size_t>(patchIndex));
    std::vector<Label> meshPoints;
    std::vector<bool> seen(static_cast<std::size_t>(mesh.pointCount()), false);
    for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f)
        for (Label p : mesh.face(f))
            if (!seen[static_cast<std::size_t>(p)]) {
                seen[static_cast<std::size_t>(p)] = true;
                meshPoints.push_back(p);
            }
    return meshPoints;
}

} // namespace rbm

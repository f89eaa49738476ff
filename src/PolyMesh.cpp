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

} // namespace rbm

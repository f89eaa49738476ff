#pragma once
// One processor's polyMesh of a whole mesh split by cells, made in memory as decomposePar
// writes processorN/constant/polyMesh, for the tests of the distributed parts on any rank
// count (the committed fixture tests/data/decomposed has 4 processors only):
//
//   cells     the processor's cells in their whole-mesh order;
//   points    the points of those cells in whole-mesh order (pointProcAddressing);
//   faces     the internal faces between two of its cells in whole-mesh order, then each
//             patch of the whole mesh with the faces of its cells (every patch kept, empty or
//             not), then one `processor` patch per neighbouring processor (ascending,
//             myProcNo/neighbProcNo), its faces in whole-mesh order on both sides;
//   orientation  a processor face as in the whole mesh on the side of the whole mesh's owner
//             cell, reversed (first point kept, the rest in reverse order) on the other, so
//             that on both sides it points out of the processor's cell.

#include "DecomposedCase.hpp"
#include "PolyMesh.hpp"

#include <algorithm>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace rbm::test {

inline io::ProcessorMesh splitProcessorMesh(const PolyMesh& whole, std::span<const int> cellProcessors, int processor)
{
    const Label cellCount = whole.cellCount();
    std::vector<Label> localCell(static_cast<std::size_t>(cellCount), -1);
    Label localCells = 0;
    for (Label c = 0; c < cellCount; ++c)
        if (cellProcessors[c] == processor) localCell[c] = localCells++;

    io::ProcessorMesh part;
    std::vector<Label> localPoint(whole.points.size(), -1);
    const auto usePoints = [&](Label f) {
        for (Label p : whole.face(f)) localPoint[p] = 0;
    };
    for (Label f = 0; f < whole.faceCount(); ++f)
        if (localCell[whole.owner[f]] >= 0 || (f < whole.internalFaceCount() && localCell[whole.neighbour[f]] >= 0))
            usePoints(f);
    for (Label p = 0; p < whole.pointCount(); ++p)
        if (localPoint[p] == 0) {
            localPoint[p] = part.mesh.pointCount();
            part.mesh.points.push_back(whole.points[p]);
            part.pointProcAddressing.push_back(p);
        }

    const auto addFace = [&](Label f, bool reversed, Label owner) {
        std::vector<Label> points;
        for (Label p : whole.face(f)) points.push_back(localPoint[p]);
        if (reversed) std::reverse(points.begin() + 1, points.end());
        part.mesh.addFace(points);
        part.mesh.owner.push_back(owner);
    };
    for (Label f = 0; f < whole.internalFaceCount(); ++f)
        if (localCell[whole.owner[f]] >= 0 && localCell[whole.neighbour[f]] >= 0) {
            addFace(f, false, localCell[whole.owner[f]]);
            part.mesh.neighbour.push_back(localCell[whole.neighbour[f]]);
        }
    for (const Patch& patch : whole.patches) {
        Patch local = patch;
        local.startFace = part.mesh.faceCount();
        for (Label f = patch.startFace; f < patch.startFace + patch.faceCount; ++f)
            if (localCell[whole.owner[f]] >= 0) addFace(f, false, localCell[whole.owner[f]]);
        local.faceCount = part.mesh.faceCount() - local.startFace;
        part.mesh.patches.push_back(local);
    }
    std::map<int, std::vector<Label>> facesTo;   // per neighbouring processor, whole-mesh faces in order
    for (Label f = 0; f < whole.internalFaceCount(); ++f) {
        const int ownerSide = cellProcessors[whole.owner[f]], neighbourSide = cellProcessors[whole.neighbour[f]];
        if (ownerSide == neighbourSide) continue;
        if (ownerSide == processor) facesTo[neighbourSide].push_back(f);
        if (neighbourSide == processor) facesTo[ownerSide].push_back(f);
    }
    for (const auto& [neighbourProcessor, faces] : facesTo) {
        Patch patch;
        patch.name = "procBoundary" + std::to_string(processor) + "to" + std::to_string(neighbourProcessor);
        patch.type = "processor";
        patch.inGroups = {"processor"};
        patch.startFace = part.mesh.faceCount();
        patch.faceCount = static_cast<Label>(faces.size());
        patch.otherEntries = {{"myProcNo", std::to_string(processor)}, {"neighbProcNo", std::to_string(neighbourProcessor)}};
        for (Label f : faces) {
            const bool ownsIt = cellProcessors[whole.owner[f]] == processor;
            addFace(f, !ownsIt, localCell[ownsIt ? whole.owner[f] : whole.neighbour[f]]);
        }
        part.mesh.patches.push_back(patch);
    }
    return part;
}

} // namespace rbm::test

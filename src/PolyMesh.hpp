#pragma once
// The polyhedral mesh model, in OpenFOAM's face-based form (constant/polyMesh):
// points, faces (compact CSR storage), owner and neighbour cell of every face,
// boundary patches as contiguous face ranges, optional zones.
//
// Conventions are OpenFOAM's:
//  - internal faces come first (0 .. internalFaceCount()-1), ordered upper-triangular;
//  - the face normal (right-hand rule on the point order) points from owner to neighbour,
//    and out of the domain on boundary faces;
//  - patch p holds faces [patches[p].startFace, patches[p].startFace + patches[p].faceCount).
// This header knows nothing about files: io/ fills it, src/ computes with it.

#include "Vector3.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace rbm {

// Point, face and cell labels. 32 bits, like PETSc's PetscInt on Debian; readers of
// 64-bit-label files check that every value fits.
using Label = std::int32_t;

struct Patch {
    std::string name;
    std::string type;                 // "patch", "wall", "empty", "wedge", "symmetryPlane", ...
    std::vector<std::string> inGroups;
    Label startFace = 0;
    Label faceCount = 0;
    // Every other entry of the patch dictionary in the boundary file, verbatim
    // ("keyword value"), so the writer can reproduce them (e.g. neighbourPatch of cyclics).
    std::vector<std::pair<std::string, std::string>> otherEntries;
};

// pointZones / faceZones / cellZones: named label lists, kept but not required.
struct Zone {
    std::string name;
    std::vector<Label> labels;
    std::vector<bool> flipMap;        // faceZones only
};

class PolyMesh {
public:
    std::vector<Vector3> points;
    // Faces in compact form: face f has points facePoints[faceOffsets[f] .. faceOffsets[f+1]).
    std::vector<Label> faceOffsets{0};
    std::vector<Label> facePoints;
    std::vector<Label> owner;         // one per face
    std::vector<Label> neighbour;     // one per internal face
    std::vector<Patch> patches;
    std::vector<Zone> pointZones;
    std::vector<Zone> faceZones;
    std::vector<Zone> cellZones;

    Label pointCount() const { return static_cast<Label>(points.size()); }
    Label faceCount() const { return static_cast<Label>(owner.size()); }
    Label internalFaceCount() const { return static_cast<Label>(neighbour.size()); }
    // Number of cells: one more than the largest owner/neighbour label.
    Label cellCount() const;

    std::span<const Label> face(Label f) const
    {
        return {facePoints.data() + faceOffsets[f], static_cast<std::size_t>(faceOffsets[f + 1] - faceOffsets[f])};
    }
    void addFace(std::span<const Label> pointLabels);

    // Index of the patch holding boundary face f, or -1 for an internal face.
    Label patchOfFace(Label f) const;
    // Index of the patch with that name, or -1.
    Label findPatch(const std::string& name) const;
};

// OpenFOAM's localPoints order of patch `patchIndex` (PrimitivePatch::meshPoints): mesh point
// labels in the order of their first appearance walking the patch's faces, each face's points
// in order.
std::vector<Label> patchMeshPoints(const PolyMesh& mesh, Label patchIndex);

// The patch names separated by spaces, in patch order (for "Valid patches are: ..." messages).
std::string patchNameList(const PolyMesh& mesh);

} // namespace rbm

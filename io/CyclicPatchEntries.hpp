#pragma once
// The entries of OpenFOAM's plain `cyclic` patches in constant/polyMesh/boundary (kept verbatim
// in Patch::otherEntries by PolyMeshReader), read into CyclicPatchSpec (src/CyclicPairs.hpp,
// which pairs the points): neighbourPatch, the transform and, for a rotation, rotationAxis and
// rotationCentre. The transform keyword is `transform` in OpenFOAM v1912 and `transformType` in
// OpenFOAM 13; the separation (separationVector, separation) and rotationAngle are not read:
// the pairing measures them from the matched faces, so both versions' files give the same pairs.

#include "CyclicPairs.hpp"
#include "PolyMesh.hpp"

#include <string>
#include <vector>

namespace rbm::io {

// The specification of every patch of type `cyclic`, in patch order. Throws rbm::InputError
// naming `file` (the boundary file) and the patch: no neighbourPatch, an unknown transform, a
// rotational transform without rotationAxis or rotationCentre, a value of the wrong kind.
std::vector<CyclicPatchSpec> readCyclicPatchSpecs(const PolyMesh& mesh, const std::string& file);

} // namespace rbm::io

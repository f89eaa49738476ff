#pragma once
// Reading OpenFOAM's constant/polyMesh (and the polyMesh/points of a time folder).
//
// Files: points, faces (faceList or faceCompactList), owner, neighbour, boundary, and
// pointZones / faceZones / cellZones when present; any of them may be `name.gz`, ascii or
// binary, with 32- or 64-bit labels as the header's arch says (a 64-bit label that does not
// fit in 32 bits is an error: rbm's Label is 32-bit).
//
// The mesh is validated, each problem an rbm::InputError naming the file and the line or
// the entry: truncated files, list sizes that disagree with their data, sizes larger than
// the file can hold, faces with fewer than 3 points, point and cell labels out of range,
// owner/neighbour lengths that disagree with the faces, patches that overlap, leave gaps or
// run past the face list, non-finite coordinates, binary data whose size does not match
// the arch.

#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <filesystem>
#include <string_view>
#include <vector>

namespace rbm::io {

// Reads the mesh in `polyMeshDir` (e.g. "<case>/constant/polyMesh").
PolyMesh readPolyMesh(const std::filesystem::path& polyMeshDir);

// Reads only the points: of `path`/points(.gz) when `path` is a polyMesh folder
// ("<case>/<time>/polyMesh"), of `path`/polyMesh/points(.gz) when it is a time folder
// ("<case>/<time>"), else of the file `path` (or `path`.gz) itself.
std::vector<Vector3> readPolyMeshPoints(const std::filesystem::path& path);

// Reads a labelList file of the polyMesh (e.g. decomposePar's pointProcAddressing), `path` or
// `path`.gz, ascii or binary; `what` names an entry in messages, at most maxCount entries.
std::vector<Label> readLabelListFile(const std::filesystem::path& path, std::string_view what, std::size_t maxCount);

// Reads a boundary file's patches (not checked against a mesh).
std::vector<Patch> readBoundaryFile(const std::filesystem::path& boundaryFile);

// Checks patches against the face counts the way OpenFOAM's polyBoundaryMesh does: the first
// patch starts at `internalFaceCount`, each one where the previous one ends, the last one ends
// at `faceCount`. `file` names the boundary file in messages.
void checkPatchRanges(const std::vector<Patch>& patches, Label internalFaceCount, Label faceCount,
                      const std::string& file);

} // namespace rbm::io

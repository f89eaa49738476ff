#pragma once
// Writing OpenFOAM polyMesh files: the moved points of a time step
// (<case>/<time>/polyMesh/points) and, for tests and tools, a whole polyMesh.
//
// Files are what OpenFOAM v1912 writes: its banner, a FoamFile header (version 2.0, format,
// class, arch "LSB;label=32;scalar=64", note for owner/neighbour, location, object), lists
// as in FoamListIO.hpp, faces as a faceList in ascii and a faceCompactList in binary.
// FoamWriteOptions (FoamListIO.hpp) come from the case's controlDict (ControlDict.hpp:
// binary, writePrecision, writeCompression). Compressed files get ".gz"; the uncompressed
// twin of a file written compressed (and the other way round) is removed, as OpenFOAM does,
// so a stale file never shadows the new one.

#include "FoamListIO.hpp"
#include "PolyMesh.hpp"
#include "TextFileWriter.hpp"
#include "Vector3.hpp"

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>

namespace rbm::io {

// Writes `points` into <caseDir>/<timeName>/polyMesh/points (folders created as needed),
// location "<timeName>/polyMesh". Returns the path written (with ".gz" when compressed).
std::filesystem::path writePolyMeshPoints(const std::filesystem::path& caseDir, const std::string& timeName,
                                          std::span<const Vector3> points, const FoamWriteOptions& options);

// Writes a points file at `file` (".gz" appended when compressed) with header location
// `location` (e.g. "0.5/polyMesh"). Returns the path written. The text goes to the file in
// pieces of `pieceSize` bytes (TextFileWriter.hpp), never whole; tests use small pieces.
std::filesystem::path writePointsFile(const std::filesystem::path& file, std::span<const Vector3> points,
                                      const std::string& location, const FoamWriteOptions& options,
                                      std::size_t pieceSize = TextFileWriter::defaultPieceSize);

// Writes points, faces, owner, neighbour, boundary and, when the mesh has zones, pointZones,
// faceZones and cellZones into `polyMeshDir` (created as needed). The header location is the
// last two components of the path ("constant/polyMesh"). The boundary file is never
// compressed (as in OpenFOAM). The mesh is written as it is, without checks.
void writePolyMesh(const std::filesystem::path& polyMeshDir, const PolyMesh& mesh, const FoamWriteOptions& options);

} // namespace rbm::io

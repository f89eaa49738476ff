#pragma once
// pointVectorField files (e.g. 0/pointDisplacement): reading with OpenFOAM v1912's rules for
// which boundaryField entry applies to which patch, and writing (ascii).
//
//   dimensions      [0 1 0 0 0 0 0];
//   internalField   uniform (0 0 0);                  // or nonuniform List<vector> N(...)
//   boundaryField
//   {
//       airfoil         { type fixedValue; value uniform (0 0 0); }
//       "(inlet|outlet)" { type fixedValue; value uniform (0 0 0); }
//       wall            { type slip; }                // a patch group (inGroups)
//   }
//
// Precedence (GeometricBoundaryField::readField of OpenFOAM v1912), for every patch:
//   1. a literal keyword equal to the patch name;
//   2. a literal keyword equal to one of the patch's groups (its inGroups, and its type for
//      constraint types such as empty, wedge, cyclic, symmetryPlane, which OpenFOAM adds to
//      inGroups itself); when several group entries apply, the last one in the file wins;
//   3. a regular-expression keyword matching the patch name, the last one in the file first;
//   4. an `empty` patch without any entry gets `type empty`.
// Note that groups come before regular expressions, as in OpenFOAM's code.
//
// Checks beyond OpenFOAM's (which silently ignores unused entries): a dictionary entry that
// applies to no patch is an error naming the file, line and entry, unless its type is `empty`
// or its keyword is the name of one of OpenFOAM's patch types (`wall`, `patch`, `empty`,
// `wedge`, `symmetryPlane`, ...: group names that case templates use for meshes without such
// patches). Primitive entries of boundaryField (variables for `$` substitution) are ignored.

#include "FoamDictionary.hpp"
#include "PolyMesh.hpp"
#include "TextFileWriter.hpp"

#include <array>
#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace rbm::io {

// The boundaryField entry that applies to one patch.
struct PointPatchFieldEntry {
    enum class Match { PatchName, Group, Pattern, ImplicitEmpty };

    std::string patchName;
    std::string type;             // the entry's `type`, e.g. "fixedValue", "slip", "empty"
    std::string keyword;          // the boundaryField keyword that applied ("inlet", "(a|b)", "wall")
    Match match = Match::PatchName;
    Dictionary dictionary;        // the applying sub-dictionary (type and every other entry)
};

struct PointVectorField {
    FoamFileHeader header;                             // sizes needed to decode binary values
    std::array<double, 7> dimensions{0, 1, 0, 0, 0, 0, 0};  // [kg m s K mol A cd]
    bool internalFieldUniform = true;
    std::vector<Vector3> internalField;                // one value per mesh point (uniform expanded)
    std::vector<PointPatchFieldEntry> boundaryField;   // one per mesh patch, in mesh order
    Dictionary dictionary;                             // the whole file, for any other entry
};

// Reads a pointVectorField file (plain or .gz) for `mesh`: checks the header class,
// the dimensions, the size of internalField against the number of points, and the size of
// every patch's nonuniform `value` against the number of points of the patch.
PointVectorField readPointVectorField(const std::filesystem::path& path, const PolyMesh& mesh);

// The precedence rules above, on their own: one entry per patch of `patches`, in order.
// `boundaryField` is the boundaryField dictionary; errors name its file.
std::vector<PointPatchFieldEntry> resolveBoundaryField(const Dictionary& boundaryField, const std::vector<Patch>& patches);

// The mesh points of patch `patch`, in the order OpenFOAM's point patch uses (first appearance
// while walking the patch's faces, PrimitivePatch::meshPoints): the order of a patch's
// nonuniform `value` list.
std::vector<Label> patchPointLabels(const PolyMesh& mesh, Label patch);

struct PointVectorFieldWriteOptions {
    std::array<double, 7> dimensions{0, 1, 0, 0, 0, 0, 0};
    int precision = 6;          // controlDict writePrecision
    bool compressed = false;    // controlDict writeCompression: the file gets ".gz"
    std::string location;       // header location; default: the name of the file's folder (the time)
    // Bytes of text held before they go to the file (TextFileWriter.hpp): the write's memory
    // is about this much whatever the size of the field. Tests use small pieces.
    std::size_t pieceSize = TextFileWriter::defaultPieceSize;
};

// Writes an ascii pointVectorField: `internalField` (written `uniform` when all values are
// equal, as OpenFOAM does) and one `patchName { ... }` entry per element of `boundaryField`,
// in order. Returns the path written (with ".gz" when compressed).
std::filesystem::path writePointVectorField(const std::filesystem::path& path, std::span<const Vector3> internalField,
                                            const std::vector<PointPatchFieldEntry>& boundaryField,
                                            const PointVectorFieldWriteOptions& options = {});

} // namespace rbm::io

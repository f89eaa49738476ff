#include "PolyMeshWriter.hpp"

#include "CompressedFile.hpp"
#include "TextFileWriter.hpp"

#include <algorithm>
#include <system_error>

namespace rbm::io {

namespace fs = std::filesystem;

namespace {

// Removes the other variant of `file` (plain or .gz) than the one just written, which would
// otherwise shadow (plain) or confuse (.gz) readers of the new file.
void removeTwin(const fs::path& file, bool compressed)
{
    const fs::path twin = compressed ? file : fs::path(file.string() + ".gz");
    std::error_code ignored;
    fs::remove(twin, ignored);
}

// Writes `contents` to `file` (or `file`.gz) and removes the other variant.
fs::path writeMeshFile(const fs::path& file, const std::string& contents, bool compressed)
{
    const fs::path written = writeFileContents(file, contents, compressed);
    removeTwin(file, compressed);
    return written;
}

int pointPrecision(const FoamWriteOptions& options)
{
    return std::max(options.precision, options.minimumPointPrecision);
}

// "constant/polyMesh" from ".../case/constant/polyMesh".
std::string locationOf(const fs::path& polyMeshDir)
{
    fs::path normal = polyMeshDir.lexically_normal();
    if (normal.filename().empty()) normal = normal.parent_path();   // trailing separator
    const std::string parent = normal.parent_path().filename().string();
    return parent.empty() ? normal.filename().string() : parent + "/" + normal.filename().string();
}

// OpenFOAM's Ostream::writeKeyword: 8 spaces of indentation inside a patch, keyword padded to 16.
void appendKeyword(std::string& out, const std::string& keyword, int indent)
{
    out.append(static_cast<std::size_t>(indent), ' ');
    out += keyword;
    out.append(keyword.size() < 16 ? 16 - keyword.size() : 1, ' ');
}

std::string boundaryFileText(const std::vector<Patch>& patches, const std::string& location, bool binary)
{
    // The boundary file holds no binary lists; its header still names the case's format.
    std::string text = foamFileHeaderText(binary, "polyBoundaryMesh", location, "boundary");
    appendLabel(text, static_cast<std::int64_t>(patches.size()));
    text += "\n(\n";
    for (const Patch& patch : patches) {
        text += "    " + patch.name + "\n    {\n";
        appendKeyword(text, "type", 8);
        text += patch.type + ";\n";
        if (!patch.inGroups.empty()) {
            appendKeyword(text, "inGroups", 8);
            appendLabel(text, static_cast<std::int64_t>(patch.inGroups.size()));
            text += '(';
            for (std::size_t g = 0; g < patch.inGroups.size(); ++g) {
                if (g > 0) text += ' ';
                text += patch.inGroups[g];
            }
            text += ");\n";
        }
        appendKeyword(text, "nFaces", 8);
        appendLabel(text, patch.faceCount);
        text += ";\n";
        appendKeyword(text, "startFace", 8);
        appendLabel(text, patch.startFace);
        text += ";\n";
        for (const auto& [keyword, value] : patch.otherEntries) {
            appendKeyword(text, keyword, 8);
            text += value;
            // A sub-dictionary kept as "{ ... }" takes no ';'.
            if (value.empty() || value.front() != '{') text += ';';
            text += '\n';
        }
        text += "    }\n";
    }
    text += ")";
    text += foamFileFooterText();
    return text;
}

std::string zonesFileText(const std::vector<Zone>& zones, const char* object, const char* zoneType, const char* labelsKeyword,
                          bool withFlipMap, const std::string& location, bool binary)
{
    std::string text = foamFileHeaderText(binary, "regIOobject", location, object);
    appendLabel(text, static_cast<std::int64_t>(zones.size()));
    text += "\n(\n";
    for (const Zone& zone : zones) {
        text += zone.name + "\n{\n";
        appendKeyword(text, "type", 4);
        text += zoneType;
        text += ";\n";
        appendKeyword(text, labelsKeyword, 4);
        text += "List<label> ";
        appendLabelList(text, zone.labels, binary);
        text += ";\n";
        if (withFlipMap) {
            appendKeyword(text, "flipMap", 4);
            text += "List<bool> ";
            std::vector<bool> flipMap = zone.flipMap;
            flipMap.resize(zone.labels.size(), false);
            appendBoolList(text, flipMap, binary);
            text += ";\n";
        }
        text += "}\n";
    }
    text += ")";
    text += foamFileFooterText();
    return text;
}

} // namespace

// Streamed (TextFileWriter.hpp): the one file of a time step as large as the mesh (~60 MB of
// ascii text for 10^6 points), written at every write time, goes to the file a piece at a
// time instead of being held whole (and compressed whole).
fs::path writePointsFile(const fs::path& file, std::span<const Vector3> points, const std::string& location,
                         const FoamWriteOptions& options, std::size_t pieceSize)
{
    TextFileWriter writer(file, options.compressed, pieceSize);
    writer.text() += foamFileHeaderText(options.binary, "vectorField", location, "points");
    appendVectorList(writer, points, options.binary, pointPrecision(options));
    writer.text() += foamFileFooterText();
    const fs::path written = writer.finish();
    removeTwin(file, options.compressed);
    return written;
}

fs::path writePolyMeshPoints(const fs::path& caseDir, const std::string& timeName, std::span<const Vector3> points,
                             const FoamWriteOptions& options)
{
    const fs::path folder = caseDir / timeName / "polyMesh";
    fs::create_directories(folder);
    return writePointsFile(folder / "points", points, timeName + "/polyMesh", options);
}

void writePolyMesh(const fs::path& polyMeshDir, const PolyMesh& mesh, const FoamWriteOptions& options)
{
    fs::create_directories(polyMeshDir);
    const std::string location = locationOf(polyMeshDir);
    const bool binary = options.binary;

    writePointsFile(polyMeshDir / "points", mesh.points, location, options);

    {
        // OpenFOAM writes faces as a faceCompactList in binary and as a faceList in ascii.
        std::string text = foamFileHeaderText(binary, binary ? "faceCompactList" : "faceList", location, "faces");
        if (binary) {
            appendFaceCompactList(text, mesh.faceOffsets, mesh.facePoints, true);
        } else {
            appendFaceList(text, mesh.faceOffsets, mesh.facePoints);
        }
        text += foamFileFooterText();
        writeMeshFile(polyMeshDir / "faces", text, options.compressed);
    }

    const std::string note = "nPoints:" + std::to_string(mesh.pointCount()) + "  nCells:" + std::to_string(mesh.cellCount()) +
                             "  nFaces:" + std::to_string(mesh.faceCount()) +
                             "  nInternalFaces:" + std::to_string(mesh.internalFaceCount());
    for (const auto& [object, labels] : {std::pair{"owner", &mesh.owner}, std::pair{"neighbour", &mesh.neighbour}}) {
        std::string text = foamFileHeaderText(binary, "labelList", location, object, note);
        appendLabelList(text, *labels, binary);
        text += foamFileFooterText();
        writeMeshFile(polyMeshDir / object, text, options.compressed);
    }

    writeMeshFile(polyMeshDir / "boundary", boundaryFileText(mesh.patches, location, binary), false);

    if (!mesh.pointZones.empty())
        writeMeshFile(polyMeshDir / "pointZones",
                      zonesFileText(mesh.pointZones, "pointZones", "pointZone", "pointLabels", false, location, binary),
                      options.compressed);
    if (!mesh.faceZones.empty())
        writeMeshFile(polyMeshDir / "faceZones",
                      zonesFileText(mesh.faceZones, "faceZones", "faceZone", "faceLabels", true, location, binary),
                      options.compressed);
    if (!mesh.cellZones.empty())
        writeMeshFile(polyMeshDir / "cellZones",
                      zonesFileText(mesh.cellZones, "cellZones", "cellZone", "cellLabels", false, location, binary),
                      options.compressed);
}

} // namespace rbm::io

#include "PolyMeshReader.hpp"

#include "CompressedFile.hpp"
#include "FoamDictionary.hpp"
#include "FoamListIO.hpp"
#include "InputError.hpp"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <limits>
#include <string>

namespace rbm::io {

namespace fs = std::filesystem;

namespace {

// One file of the mesh, read whole, with its parsed header and the offset of its body.
struct MeshFile {
    fs::path path;
    std::string text;
    FoamFileHeader header;
    std::size_t bodyOffset = 0;

    FoamListReader listReader() const { return FoamListReader(text, bodyOffset, path.string(), header); }
};

// fs::is_directory without an error_code throws for names the system refuses (too long).
bool isFolder(const fs::path& path)
{
    std::error_code error;
    return fs::is_directory(path, error) && !error;
}

MeshFile openMeshFile(const fs::path& pathWithoutGz)
{
    MeshFile file;
    file.path = resolveMaybeCompressed(pathWithoutGz);
    file.text = readFileContents(file.path);
    int bodyLine = 1;
    file.header = parseFoamFileHeader(file.text, file.path.string(), file.bodyOffset, bodyLine);
    return file;
}

std::vector<Vector3> readPointsOf(const MeshFile& file)
{
    FoamListReader reader = file.listReader();
    std::vector<Vector3> points = reader.readVectorList("point", file.text.size());
    reader.expectEnd();
    return points;
}

// ---- Token-level decoding of the lists inside boundary and zone dictionaries ---------------

[[noreturn]] void failEntry(const Entry& entry, const Token* token, const std::string& message)
{
    throw InputError(entry.file(), token ? token->line : entry.line(), "entry '" + entry.keyword() + "': " + message);
}

std::string describe(const Token& token)
{
    switch (token.kind) {
    case Token::Kind::Binary: return "binary data";
    case Token::Kind::String: return "\"" + token.text + "\"";
    default: return "'" + token.text + "'";
    }
}

std::int64_t integerOf(const Entry& entry, const Token& token, std::string_view what)
{
    std::int64_t value = 0;
    const char* begin = token.text.data();
    const char* end = begin + token.text.size();
    const auto [stop, error] = std::from_chars(begin, end, value);
    if (token.kind != Token::Kind::Number || error != std::errc() || stop != end)
        failEntry(entry, &token, "expected " + std::string(what) + " (an integer) but found " + describe(token));
    return value;
}

Label labelOf(const Entry& entry, const Token& token, std::string_view what)
{
    const std::int64_t value = integerOf(entry, token, what);
    if (value > std::numeric_limits<Label>::max() || value < std::numeric_limits<Label>::min())
        failEntry(entry, &token, std::string(what) + " " + std::to_string(value) +
                                     " does not fit in a 32-bit label (rbm uses 32-bit labels)");
    return static_cast<Label>(value);
}

bool boolOf(const Entry& entry, const Token& token, std::string_view what)
{
    const std::string& t = token.text;
    if (t == "1" || t == "true" || t == "yes" || t == "on" || t == "y" || t == "t") return true;
    if (t == "0" || t == "false" || t == "no" || t == "off" || t == "n" || t == "f") return false;
    failEntry(entry, &token, "expected " + std::string(what) + " (0 or 1) but found " + describe(token));
}

// Decodes an entry value that is one list: [List<T>] [N] ( ... ) | N{v} | N <binary>.
// `decodeText` turns one ascii token into a value, `decodeBinary` one element of
// `elementBytes` raw bytes. `maxCount` bounds a uniform list's size.
template <class T, class DecodeText, class DecodeBinary>
std::vector<T> decodeListEntry(const Entry& entry, std::string_view what, std::size_t elementBytes, std::size_t maxCount,
                               DecodeText decodeText, DecodeBinary decodeBinary)
{
    const std::vector<Token>& tokens = entry.tokens();
    std::size_t i = 0;
    const auto at = [&](std::size_t k) -> const Token* { return k < tokens.size() ? &tokens[k] : nullptr; };
    const std::string plural = std::string(what) + "s";
    if (at(i) && at(i)->kind == Token::Kind::Word && at(i)->text.rfind("List<", 0) == 0) ++i;

    std::vector<T> values;
    std::int64_t count = -1;
    if (at(i) && at(i)->kind == Token::Kind::Number) {
        count = integerOf(entry, *at(i), "the size of the list of " + plural);
        if (count < 0 || count > std::numeric_limits<Label>::max())
            failEntry(entry, at(i), "list size " + std::to_string(count) + " is out of range");
        ++i;
    }
    const Token* token = at(i);
    if (count >= 0 && (token == nullptr || token->kind == Token::Kind::Binary)) {
        // Binary block (or nothing after a bare 0, OpenFOAM's empty binary list).
        // Lists of words are never binary: without this check `inGroups 2000000000;` passed the
        // byte count (0 bytes per word) and reserved room for 2e9 strings (found by fuzzing).
        if (elementBytes == 0 && count > 0)
            failEntry(entry, token, "expected '(' after the size " + std::to_string(count) + " of the list of " + plural);
        const std::string empty;
        const std::string& bytes = token ? token->text : empty;
        if (bytes.size() != static_cast<std::size_t>(count) * elementBytes)
            failEntry(entry, token, "binary list of " + std::to_string(count) + " " + plural + " should hold " +
                                        std::to_string(static_cast<std::size_t>(count) * elementBytes) + " bytes but holds " +
                                        std::to_string(bytes.size()) +
                                        " (a label size in the header's arch that does not match the data?)");
        values.reserve(static_cast<std::size_t>(count));
        for (std::int64_t k = 0; k < count; ++k) values.push_back(decodeBinary(bytes.data() + k * static_cast<std::int64_t>(elementBytes), token));
        if (token) ++i;
    } else if (count >= 0 && token->isPunctuation('{')) {
        if (static_cast<std::size_t>(count) > maxCount)
            failEntry(entry, token, "uniform list of " + std::to_string(count) + " " + plural + " is longer than the " +
                                        std::to_string(maxCount) + " possible");
        const Token* value = at(i + 1);
        if (!value) failEntry(entry, nullptr, "uniform list is truncated");
        const T v = decodeText(*value);
        if (!at(i + 2) || !at(i + 2)->isPunctuation('}'))
            failEntry(entry, at(i + 2), "expected '}' closing a uniform list");
        values.assign(static_cast<std::size_t>(count), v);
        i += 3;
    } else if (token && token->isPunctuation('(')) {
        if (count >= 0) values.reserve(static_cast<std::size_t>(std::min<std::int64_t>(count, static_cast<std::int64_t>(tokens.size()))));
        ++i;
        while (true) {
            const Token* t = at(i);
            if (!t) failEntry(entry, nullptr, "list of " + plural + " is truncated: expected ')'");
            if (t->isPunctuation(')')) break;
            values.push_back(decodeText(*t));
            ++i;
        }
        ++i;
        if (count >= 0 && values.size() != static_cast<std::size_t>(count))
            failEntry(entry, at(i - 1), "list size " + std::to_string(count) + " disagrees with the " +
                                            std::to_string(values.size()) + " " + plural + " it holds");
    } else {
        failEntry(entry, token, "expected a list of " + plural + " but found " + (token ? describe(*token) : "nothing"));
    }
    if (at(i)) failEntry(entry, at(i), "unexpected " + describe(*at(i)) + " after the list of " + plural);
    return values;
}

std::vector<Label> decodeLabelListEntry(const Entry& entry, const FoamFileHeader& header, std::string_view what,
                                        std::size_t maxCount)
{
    const int labelBytes = header.labelBytes;
    return decodeListEntry<Label>(
        entry, what, static_cast<std::size_t>(labelBytes), maxCount,
        [&](const Token& t) { return labelOf(entry, t, what); },
        [&](const char* bytes, const Token* token) -> Label {
            if (labelBytes == 4) {
                std::int32_t v;
                std::memcpy(&v, bytes, 4);
                return v;
            }
            std::int64_t v;
            std::memcpy(&v, bytes, 8);
            if (v > std::numeric_limits<Label>::max() || v < std::numeric_limits<Label>::min())
                failEntry(entry, token, std::string(what) + " " + std::to_string(v) +
                                            " does not fit in a 32-bit label (rbm uses 32-bit labels)");
            return static_cast<Label>(v);
        });
}

std::vector<bool> decodeBoolListEntry(const Entry& entry, std::string_view what, std::size_t maxCount)
{
    return decodeListEntry<bool>(
        entry, what, 1, maxCount, [&](const Token& t) { return boolOf(entry, t, what); },
        [&](const char* bytes, const Token* token) -> bool {
            if (*bytes != 0 && *bytes != 1) failEntry(entry, token, std::string(what) + " in binary is neither 0 nor 1");
            return *bytes == 1;
        });
}

std::vector<std::string> decodeWordListEntry(const Entry& entry, std::string_view what)
{
    return decodeListEntry<std::string>(
        entry, what, 0, 0,
        [&](const Token& t) {
            if (t.kind != Token::Kind::Word && t.kind != Token::Kind::String)
                failEntry(entry, &t, "expected " + std::string(what) + " (a word) but found " + describe(t));
            return t.text;
        },
        [&](const char*, const Token* token) -> std::string { failEntry(entry, token, "a word list cannot be binary"); });
}

// A patch dictionary's entry as text, for Patch::otherEntries: a primitive entry's value
// ("0.0001", "back", "(0 0 1)"), a sub-dictionary as "{ key value; ... }".
std::string entryValueText(const Entry& entry)
{
    if (!entry.isDictionary()) return entry.valueText();
    std::string text = "{";
    for (const Entry& e : entry.dictionary().entries()) {
        text += " " + e.keyword() + " " + entryValueText(e);
        if (!e.isDictionary()) text += ";";
    }
    return text + " }";
}

Patch patchFromEntry(const Entry& entry)
{
    if (!entry.isDictionary())
        failEntry(entry, nullptr, "expected a patch dictionary { type ...; nFaces ...; startFace ...; }");
    const Dictionary& dict = entry.dictionary();
    Patch patch;
    patch.name = entry.keyword();
    patch.type = dict.get<std::string>("type");
    patch.faceCount = dict.get<Label>("nFaces");
    patch.startFace = dict.get<Label>("startFace");
    if (patch.faceCount < 0)
        throw InputError(dict.lookup("nFaces").file(), dict.lookup("nFaces").line(),
                         "patch '" + patch.name + "': nFaces must not be negative but is " + std::to_string(patch.faceCount));
    if (patch.startFace < 0)
        throw InputError(dict.lookup("startFace").file(), dict.lookup("startFace").line(),
                         "patch '" + patch.name + "': startFace must not be negative but is " + std::to_string(patch.startFace));
    for (const Entry& e : dict.entries()) {
        const std::string& key = e.keyword();
        if (key == "type" || key == "nFaces" || key == "startFace") continue;
        if (key == "inGroups") {
            if (e.isDictionary()) failEntry(e, nullptr, "expected a list of group names, not a dictionary");
            patch.inGroups = decodeWordListEntry(e, "group name");
            continue;
        }
        patch.otherEntries.emplace_back(key, entryValueText(e));
    }
    return patch;
}

// pointZones / faceZones / cellZones. `labelsKeyword` is pointLabels/faceLabels/cellLabels,
// `limit` the number of points/faces/cells the labels index.
std::vector<Zone> readZonesFile(const fs::path& file, std::string_view labelsKeyword, bool withFlipMap, Label limit,
                                std::string_view limitName)
{
    FoamFileHeader header;
    const std::vector<Entry> entries = readDictionaryListFile(file, header);
    std::vector<Zone> zones;
    zones.reserve(entries.size());
    for (const Entry& entry : entries) {
        if (!entry.isDictionary())
            failEntry(entry, nullptr, "expected a zone dictionary { type ...; " + std::string(labelsKeyword) + " ...; }");
        const Dictionary& dict = entry.dictionary();
        Zone zone;
        zone.name = entry.keyword();
        const Entry& labelsEntry = dict.lookup(labelsKeyword);
        if (labelsEntry.isDictionary()) failEntry(labelsEntry, nullptr, "expected a label list, not a dictionary");
        zone.labels = decodeLabelListEntry(labelsEntry, header, "label", static_cast<std::size_t>(limit));
        for (std::size_t k = 0; k < zone.labels.size(); ++k) {
            if (zone.labels[k] < 0 || zone.labels[k] >= limit)
                failEntry(labelsEntry, nullptr, "zone '" + zone.name + "': label " + std::to_string(zone.labels[k]) + " (entry " +
                                                    std::to_string(k) + ") is out of range; the mesh has " + std::to_string(limit) +
                                                    " " + std::string(limitName));
        }
        if (withFlipMap) {
            if (const Entry* flipEntry = dict.find("flipMap")) {
                if (flipEntry->isDictionary()) failEntry(*flipEntry, nullptr, "expected a bool list, not a dictionary");
                zone.flipMap = decodeBoolListEntry(*flipEntry, "flip flag", zone.labels.size());
                if (zone.flipMap.size() != zone.labels.size())
                    failEntry(*flipEntry, nullptr, "zone '" + zone.name + "': flipMap has " + std::to_string(zone.flipMap.size()) +
                                                       " entries but faceLabels has " + std::to_string(zone.labels.size()));
            } else {
                zone.flipMap.assign(zone.labels.size(), false);
            }
        }
        zones.push_back(std::move(zone));
    }
    return zones;
}

} // namespace

std::vector<Vector3> readPolyMeshPoints(const fs::path& path)
{
    fs::path file = path;
    if (!existsMaybeCompressed(path))
        throw InputError(path.string(), 0, "not found (expected a time folder, a polyMesh folder or a points file)");
    if (isFolder(path)) {
        // A polyMesh folder, or a time folder holding one.
        file = !existsMaybeCompressed(path / "points") && isFolder(path / "polyMesh") ? path / "polyMesh" / "points"
                                                                                       : path / "points";
    }
    return readPointsOf(openMeshFile(file));
}

std::vector<Label> readLabelListFile(const fs::path& path, std::string_view what, std::size_t maxCount)
{
    const MeshFile file = openMeshFile(path);
    FoamListReader reader = file.listReader();
    std::vector<Label> labels = reader.readLabelList(what, maxCount);
    reader.expectEnd();
    return labels;
}

std::vector<Patch> readBoundaryFile(const fs::path& boundaryFile)
{
    FoamFileHeader header;
    const std::vector<Entry> entries = readDictionaryListFile(resolveMaybeCompressed(boundaryFile), header);
    std::vector<Patch> patches;
    patches.reserve(entries.size());
    for (const Entry& entry : entries) {
        patches.push_back(patchFromEntry(entry));
        for (std::size_t p = 0; p + 1 < patches.size(); ++p) {
            if (patches[p].name == patches.back().name)
                failEntry(entry, nullptr, "patch name '" + entry.keyword() + "' is used twice");
        }
    }
    return patches;
}

void checkPatchRanges(const std::vector<Patch>& patches, Label internalFaceCount, Label faceCount, const std::string& file)
{
    std::int64_t expectedStart = internalFaceCount;
    std::string previous = "the internal faces (one per neighbour entry) end";
    for (const Patch& patch : patches) {
        if (patch.startFace != expectedStart) {
            const std::int64_t difference = patch.startFace - expectedStart;
            const std::string problem = difference < 0 ? "overlap of " + std::to_string(-difference) + " faces"
                                                       : "gap of " + std::to_string(difference) + " faces";
            throw InputError(file, 0, "patch '" + patch.name + "' starts at face " + std::to_string(patch.startFace) + " but " +
                                          previous + " at face " + std::to_string(expectedStart) + " (" + problem +
                                          "): expected startFace " + std::to_string(expectedStart));
        }
        expectedStart += patch.faceCount;
        if (expectedStart > faceCount)
            throw InputError(file, 0, "patch '" + patch.name + "' (startFace " + std::to_string(patch.startFace) + ", nFaces " +
                                          std::to_string(patch.faceCount) + ") runs past the last face; the mesh has " +
                                          std::to_string(faceCount) + " faces");
        previous = "the previous patch '" + patch.name + "' ends";
    }
    if (expectedStart != faceCount)
        throw InputError(file, 0, "patches cover faces up to " + std::to_string(expectedStart) + " but the mesh has " +
                                      std::to_string(faceCount) + " faces: the last " + std::to_string(faceCount - expectedStart) +
                                      " faces belong to no patch");
}

PolyMesh readPolyMesh(const fs::path& polyMeshDir)
{
    if (!isFolder(polyMeshDir))
        throw InputError(polyMeshDir.string(), 0, "polyMesh folder not found (expected points, faces, owner, neighbour, boundary in it)");
    PolyMesh mesh;

    mesh.points = readPointsOf(openMeshFile(polyMeshDir / "points"));
    const Label pointCount = mesh.pointCount();

    // faces
    {
        const MeshFile file = openMeshFile(polyMeshDir / "faces");
        FoamListReader reader = file.listReader();
        mesh.faceOffsets.clear();
        mesh.facePoints.clear();
        if (file.header.className == "faceCompactList") {
            reader.readFaceCompactList(mesh.faceOffsets, mesh.facePoints);
        } else if (file.header.className == "faceList" || file.header.className.empty()) {
            reader.readFaceList(mesh.faceOffsets, mesh.facePoints);
        } else {
            throw InputError(file.path.string(), 0, "header class is '" + file.header.className +
                                                        "' but a faces file must be a faceList or faceCompactList");
        }
        reader.expectEnd();
        const std::size_t faceCount = mesh.faceOffsets.size() - 1;
        for (std::size_t f = 0; f < faceCount; ++f) {
            for (Label i = mesh.faceOffsets[f]; i < mesh.faceOffsets[f + 1]; ++i) {
                const Label p = mesh.facePoints[static_cast<std::size_t>(i)];
                if (p < 0 || p >= pointCount)
                    throw InputError(file.path.string(), 0, "face " + std::to_string(f) + " refers to point " + std::to_string(p) +
                                                                " but the points file has " + std::to_string(pointCount) +
                                                                " points (valid labels 0 to " + std::to_string(pointCount - 1) + ")");
            }
        }
    }
    const std::size_t faceCount = mesh.faceOffsets.size() - 1;

    // owner, neighbour
    const auto readCellLabels = [&](const char* name, std::string_view what) {
        const MeshFile file = openMeshFile(polyMeshDir / name);
        FoamListReader reader = file.listReader();
        std::vector<Label> labels = reader.readLabelList(what, faceCount);
        reader.expectEnd();
        for (std::size_t f = 0; f < labels.size(); ++f) {
            if (labels[f] < 0)
                throw InputError(file.path.string(), 0, std::string(what) + " of face " + std::to_string(f) + " is " +
                                                            std::to_string(labels[f]) + " but cell labels must not be negative");
        }
        return std::pair{std::move(labels), file.path.string()};
    };
    auto [owner, ownerFile] = readCellLabels("owner", "owner cell");
    if (owner.size() != faceCount)
        throw InputError(ownerFile, 0, "owner has " + std::to_string(owner.size()) + " entries but the faces file has " +
                                           std::to_string(faceCount) + " faces (expected one owner cell per face)");
    auto [neighbour, neighbourFile] = readCellLabels("neighbour", "neighbour cell");
    if (neighbour.size() > faceCount)
        throw InputError(neighbourFile, 0, "neighbour has " + std::to_string(neighbour.size()) + " entries but the faces file has only " +
                                               std::to_string(faceCount) + " faces (expected one per internal face)");
    for (std::size_t f = 0; f < neighbour.size(); ++f) {
        if (neighbour[f] == owner[f])
            throw InputError(neighbourFile, 0, "internal face " + std::to_string(f) + " has cell " + std::to_string(owner[f]) +
                                                   " as both owner and neighbour");
    }
    mesh.owner = std::move(owner);
    mesh.neighbour = std::move(neighbour);
    {
        // Every cell label up to the largest must have at least the 4 faces of a tetrahedron;
        // fewer means corrupt or inconsistent owner/neighbour files. So the owner and neighbour
        // entries bound the number of cells, checked before the count array is allocated: a
        // corrupt label such as 2147483647 asked for 8 GB (and overflowed cellCount()); found
        // by fuzzing.
        const auto largestOf = [](const std::vector<Label>& labels) {
            return labels.empty() ? Label{-1} : *std::max_element(labels.begin(), labels.end());
        };
        const Label largestOwner = largestOf(mesh.owner);
        const Label largest = std::max(largestOwner, largestOf(mesh.neighbour));
        const std::size_t mostCells = (mesh.owner.size() + mesh.neighbour.size()) / 4;
        if (largest >= 0 && static_cast<std::size_t>(largest) >= mostCells) {
            const bool inOwner = largestOwner == largest;
            throw InputError(inOwner ? ownerFile : neighbourFile, 0,
                             std::string(inOwner ? "owner" : "neighbour") + " cell label " + std::to_string(largest) +
                                 " is too large: the " + std::to_string(mesh.owner.size() + mesh.neighbour.size()) +
                                 " owner and neighbour entries make at most " + std::to_string(mostCells) +
                                 " cells of at least 4 faces");
        }
        std::vector<Label> facesOfCell(static_cast<std::size_t>(mesh.cellCount()), 0);
        for (Label c : mesh.owner) ++facesOfCell[static_cast<std::size_t>(c)];
        for (Label c : mesh.neighbour) ++facesOfCell[static_cast<std::size_t>(c)];
        for (std::size_t c = 0; c < facesOfCell.size(); ++c) {
            if (facesOfCell[c] < 4)
                throw InputError(ownerFile, 0, "cell " + std::to_string(c) + " has " + std::to_string(facesOfCell[c]) +
                                                   " faces in owner and neighbour; a cell needs at least 4 (cell labels run from 0 to " +
                                                   std::to_string(facesOfCell.size() - 1) + ")");
        }
    }

    // boundary
    const fs::path boundaryPath = resolveMaybeCompressed(polyMeshDir / "boundary");
    mesh.patches = readBoundaryFile(boundaryPath);
    checkPatchRanges(mesh.patches, mesh.internalFaceCount(), mesh.faceCount(), boundaryPath.string());

    // zones (optional)
    const Label cellCount = mesh.cellCount();
    if (existsMaybeCompressed(polyMeshDir / "pointZones"))
        mesh.pointZones = readZonesFile(resolveMaybeCompressed(polyMeshDir / "pointZones"), "pointLabels", false, pointCount, "points");
    if (existsMaybeCompressed(polyMeshDir / "faceZones"))
        mesh.faceZones = readZonesFile(resolveMaybeCompressed(polyMeshDir / "faceZones"), "faceLabels", true, mesh.faceCount(), "faces");
    if (existsMaybeCompressed(polyMeshDir / "cellZones"))
        mesh.cellZones = readZonesFile(resolveMaybeCompressed(polyMeshDir / "cellZones"), "cellLabels", false, cellCount, "cells");
    return mesh;
}

} // namespace rbm::io

#include "PointVectorField.hpp"

#include "CompressedFile.hpp"
#include "FoamDictionaryWriter.hpp"
#include "FoamListIO.hpp"
#include "KeywordPattern.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace rbm::io {

namespace fs = std::filesystem;

namespace {

// Patch types OpenFOAM adds to a patch's inGroups itself (polyPatch constructor:
// constraintType(patchType) -> inGroups().appendUniq(patchType)).
bool isConstraintType(const std::string& type)
{
    static const char* const types[] = {"empty",    "wedge",           "cyclic",         "cyclicAMI",
                                        "cyclicACMI", "cyclicSlip",    "cyclicPeriodicAMI", "nonuniformTransformCyclic",
                                        "symmetry", "symmetryPlane",   "processor",      "processorCyclic"};
    return std::find(std::begin(types), std::end(types), type) != std::end(types);
}

// Keywords that name a patch type, and so a group a case template may address even when this
// mesh has no such patch.
bool isPatchTypeName(const std::string& keyword)
{
    return isConstraintType(keyword) || keyword == "patch" || keyword == "wall" || keyword == "mappedPatch" ||
           keyword == "mappedWall" || keyword == "overset";
}

std::string describePatch(const Patch& patch)
{
    std::string text = "'" + patch.name + "' (type " + patch.type;
    if (!patch.inGroups.empty()) {
        text += ", groups";
        for (const std::string& g : patch.inGroups) text += " " + g;
    }
    return text + ")";
}

std::array<double, 7> readDimensions(const Entry& entry)
{
    TokenStream stream = entry.stream();
    std::array<double, 7> dimensions{};
    if (stream.atEnd() || !stream.peek().isPunctuation('[')) {
        stream.fail("dimensions: expected '[kg m s K mol A cd]', e.g. [0 1 0 0 0 0 0]");
    }
    stream.next();
    int count = 0;
    while (!stream.atEnd() && !stream.peek().isPunctuation(']')) {
        if (count == 7) stream.fail("dimensions: more than 7 exponents");
        dimensions[static_cast<std::size_t>(count++)] = stream.readScalar();
    }
    stream.expectPunctuation(']');
    if (count != 5 && count != 7) {
        throw InputError(entry.file(), entry.line(),
                         "dimensions: expected 7 exponents [kg m s K mol A cd] (or 5), found " + std::to_string(count));
    }
    if (!stream.atEnd()) stream.fail("dimensions: unexpected " + stream.peek().text + " after ']'");
    return dimensions;
}

// Reads `uniform value` or `nonuniform List<vector> ...`; `expectedSize` checks the list.
std::vector<Vector3> readVectorFieldValue(const Entry& entry, const FoamFileHeader& header, std::size_t expectedSize,
                                          const std::string& what, bool& uniform)
{
    TokenStream stream = entry.stream(header);
    if (stream.atEnd() || stream.peek().kind != Token::Kind::Word) {
        throw InputError(entry.file(), entry.line(), what + ": expected 'uniform' or 'nonuniform' followed by the value");
    }
    const std::string kind = stream.readWord();
    std::vector<Vector3> values;
    if (kind == "uniform") {
        uniform = true;
        values.assign(expectedSize, stream.readVector());
    } else if (kind == "nonuniform") {
        uniform = false;
        values = stream.readVectorList(expectedSize);
        if (values.size() != expectedSize) {
            throw InputError(entry.file(), entry.line(),
                             what + " has " + std::to_string(values.size()) + " values but " + std::to_string(expectedSize) +
                                 " are needed");
        }
    } else {
        throw InputError(entry.file(), entry.line(), what + ": expected 'uniform' or 'nonuniform' but found '" + kind + "'");
    }
    if (!stream.atEnd()) stream.fail(what + ": unexpected " + stream.peek().text + " after the value");
    return values;
}

void appendDimensions(std::string& out, const std::array<double, 7>& dimensions)
{
    out += "dimensions      [";
    for (std::size_t i = 0; i < dimensions.size(); ++i) {
        if (i > 0) out += ' ';
        appendScalar(out, dimensions[i], 6);
    }
    out += "];\n\n";
}

} // namespace

std::vector<PointPatchFieldEntry> resolveBoundaryField(const Dictionary& boundaryField, const std::vector<Patch>& patches)
{
    const std::vector<Entry>& entries = boundaryField.entries();
    std::vector<const Entry*> chosen(patches.size(), nullptr);
    std::vector<PointPatchFieldEntry::Match> how(patches.size(), PointPatchFieldEntry::Match::PatchName);
    std::vector<bool> used(entries.size(), false);

    // Patches by name and by group: meshes with thousands of patches (processor patches)
    // must not cost entries x patches string comparisons.
    std::unordered_map<std::string, std::size_t> patchByName;
    std::unordered_map<std::string, std::vector<std::size_t>> patchesByGroup;
    for (std::size_t p = 0; p < patches.size(); ++p) {
        patchByName.emplace(patches[p].name, p);
        for (const std::string& group : patches[p].inGroups) patchesByGroup[group].push_back(p);
        if (isConstraintType(patches[p].type) &&
            std::find(patches[p].inGroups.begin(), patches[p].inGroups.end(), patches[p].type) == patches[p].inGroups.end()) {
            patchesByGroup[patches[p].type].push_back(p);
        }
    }

    // 1. Literal keywords equal to a patch name.
    for (std::size_t k = 0; k < entries.size(); ++k) {
        const Entry& entry = entries[k];
        if (!entry.isDictionary() || isPatternKeyword(entry.keyword())) continue;
        const auto found = patchByName.find(entry.keyword());
        if (found == patchByName.end()) continue;
        chosen[found->second] = &entry;
        used[k] = true;
    }
    // 2. Literal keywords naming a group, the last entry first.
    for (std::size_t k = entries.size(); k-- > 0;) {
        const Entry& entry = entries[k];
        if (!entry.isDictionary() || isPatternKeyword(entry.keyword())) continue;
        const auto found = patchesByGroup.find(entry.keyword());
        if (found == patchesByGroup.end()) continue;
        used[k] = true;
        for (std::size_t p : found->second) {
            if (chosen[p] == nullptr) {
                chosen[p] = &entry;
                how[p] = PointPatchFieldEntry::Match::Group;
            }
        }
    }
    // 3. Regular expressions (Dictionary::find: the last matching one first); empty patches
    //    without an entry are empty.
    std::vector<std::size_t> patternEntries;
    for (std::size_t k = 0; k < entries.size(); ++k) {
        if (entries[k].isDictionary() && isPatternKeyword(entries[k].keyword())) patternEntries.push_back(k);
    }
    for (std::size_t p = 0; p < patches.size(); ++p) {
        for (std::size_t k : patternEntries) {
            if (!used[k] && patternMatches(entries[k].keyword(), patches[p].name)) used[k] = true;
        }
        if (chosen[p] != nullptr || patches[p].type == "empty" || patternEntries.empty()) continue;
        const Entry* entry = boundaryField.find(patches[p].name);
        if (entry == nullptr) continue;
        if (!entry->isDictionary()) {
            throw InputError(entry->file(), entry->line(),
                             "boundaryField entry '" + entry->keyword() + "' for patch '" + patches[p].name +
                                 "' should be a dictionary { type ...; }");
        }
        chosen[p] = entry;
        how[p] = PointPatchFieldEntry::Match::Pattern;
    }

    std::vector<PointPatchFieldEntry> result(patches.size());
    for (std::size_t p = 0; p < patches.size(); ++p) {
        PointPatchFieldEntry& out = result[p];
        out.patchName = patches[p].name;
        if (chosen[p] == nullptr) {
            if (patches[p].type != "empty") {
                throw InputError(boundaryField.file(), boundaryField.line(),
                                 "boundaryField has no entry for patch " + describePatch(patches[p]) +
                                     ": add '" + patches[p].name + " { type ...; }' (or an entry for one of its groups)");
            }
            out.type = "empty";
            out.keyword = patches[p].name;
            out.match = PointPatchFieldEntry::Match::ImplicitEmpty;
            out.dictionary = Dictionary(boundaryField.name() + "/" + patches[p].name, boundaryField.file(), boundaryField.line());
            out.dictionary.set(Entry("type", boundaryField.file(), boundaryField.line(),
                                     std::vector<Token>{Token{Token::Kind::Word, "empty", 0.0, false, boundaryField.line()}}));
            continue;
        }
        const Entry& entry = *chosen[p];
        const Dictionary& dictionary = entry.dictionary();
        if (!dictionary.contains("type")) {
            throw InputError(entry.file(), entry.line(),
                             "boundaryField entry '" + entry.keyword() + "' (for patch '" + patches[p].name + "') has no 'type'");
        }
        out.type = dictionary.get<std::string>("type");
        out.keyword = entry.keyword();
        out.match = how[p];
        out.dictionary = dictionary;
    }

    for (std::size_t k = 0; k < entries.size(); ++k) {
        const Entry& entry = entries[k];
        if (used[k] || !entry.isDictionary()) continue;
        if (isPatchTypeName(entry.keyword())) continue;
        const Entry* type = entry.dictionary().find("type");
        if (type != nullptr && !type->isDictionary() && type->tokens().size() == 1 && type->tokens()[0].text == "empty") continue;
        throw InputError(entry.file(), entry.line(),
                         "boundaryField entry '" + entry.keyword() +
                             "' matches no patch of the mesh (no patch has that name or group" +
                             (isPatternKeyword(entry.keyword()) ? std::string(", and no patch name matches the expression") : "") +
                             ")");
    }
    return result;
}

std::vector<Label> patchPointLabels(const PolyMesh& mesh, Label patch)
{
    const Patch& p = mesh.patches.at(static_cast<std::size_t>(patch));
    std::vector<char> seen(static_cast<std::size_t>(mesh.pointCount()), 0);
    std::vector<Label> labels;
    for (Label f = p.startFace; f < p.startFace + p.faceCount; ++f) {
        for (Label point : mesh.face(f)) {
            if (!seen[static_cast<std::size_t>(point)]) {
                seen[static_cast<std::size_t>(point)] = 1;
                labels.push_back(point);
            }
        }
    }
    return labels;
}

PointVectorField readPointVectorField(const fs::path& path, const PolyMesh& mesh)
{
    PointVectorField field;
    field.dictionary = Dictionary::readFile(path);
    const Dictionary& dictionary = field.dictionary;
    field.header = dictionary.header();
    const std::string& file = dictionary.file();
    if (dictionary.hasHeader() && !field.header.className.empty() && field.header.className != "pointVectorField") {
        throw InputError(file, 0, "the header's class is '" + field.header.className + "', expected pointVectorField");
    }
    field.dimensions = readDimensions(dictionary.lookup("dimensions"));
    field.internalField = readVectorFieldValue(dictionary.lookup("internalField"), field.header,
                                               static_cast<std::size_t>(mesh.pointCount()),
                                               "internalField (one value per mesh point)", field.internalFieldUniform);
    const Entry& boundaryEntry = dictionary.lookup("boundaryField");
    if (!boundaryEntry.isDictionary()) {
        throw InputError(boundaryEntry.file(), boundaryEntry.line(), "boundaryField should be a dictionary { ... }");
    }
    field.boundaryField = resolveBoundaryField(boundaryEntry.dictionary(), mesh.patches);

    // The size of every nonuniform `value` is the number of points of its patch.
    for (std::size_t p = 0; p < field.boundaryField.size(); ++p) {
        const PointPatchFieldEntry& patchField = field.boundaryField[p];
        const Entry* value = patchField.dictionary.find("value");
        if (value == nullptr || value->isDictionary() || patchField.type == "empty") continue;
        if (value->tokens().empty() || !value->tokens()[0].isWord("nonuniform")) continue;
        const std::size_t patchPoints = patchPointLabels(mesh, static_cast<Label>(p)).size();
        bool uniform = false;
        readVectorFieldValue(*value, field.header, patchPoints,
                             "value of patch '" + patchField.patchName + "' (one value per patch point)", uniform);
    }
    return field;
}

fs::path writePointVectorField(const fs::path& path, std::span<const Vector3> internalField,
                               const std::vector<PointPatchFieldEntry>& boundaryField,
                               const PointVectorFieldWriteOptions& options)
{
    std::string object = path.filename().string();
    const std::string location = options.location.empty() ? path.parent_path().filename().string() : options.location;
    if (!path.parent_path().empty()) fs::create_directories(path.parent_path());
    // Streamed: the text of internalField (~55 MB for 10^6 points) goes to the file a piece at
    // a time instead of being held whole (and compressed whole) next to the solver's memory.
    TextFileWriter writer(path, options.compressed, options.pieceSize);
    std::string& out = writer.text();
    out += foamFileHeaderText(false, "pointVectorField", location, object);
    appendDimensions(out, options.dimensions);

    bool uniform = !internalField.empty();
    for (std::size_t i = 1; i < internalField.size() && uniform; ++i) uniform = internalField[i] == internalField[0];
    if (uniform) {
        out += "internalField   uniform (";
        appendScalar(out, internalField[0].x, options.precision);
        out += ' ';
        appendScalar(out, internalField[0].y, options.precision);
        out += ' ';
        appendScalar(out, internalField[0].z, options.precision);
        out += ");\n\n";
    } else {
        out += "internalField   nonuniform List<vector> ";
        appendVectorList(writer, internalField, false, options.precision);
        out += ";\n\n";
    }

    out += "boundaryField\n{\n";
    for (const PointPatchFieldEntry& patchField : boundaryField) {
        out += "    ";
        if (keywordNeedsQuotes(patchField.patchName)) {
            out += '"' + patchField.patchName + '"';
        } else {
            out += patchField.patchName;
        }
        out += "\n    {\n";
        if (!patchField.dictionary.contains("type") && !patchField.type.empty()) {
            appendEntry(out, wordEntry("type", patchField.type), 2, options.precision);
        }
        appendDictionaryEntries(out, patchField.dictionary, 2, options.precision);
        out += "    }\n";
        // A patch's nonuniform value is a list of its points: a piece boundary between patches.
        writer.pieceDone();
    }
    out += "}\n";
    out += foamFileFooterText();
    return writer.finish();
}

} // namespace rbm::io

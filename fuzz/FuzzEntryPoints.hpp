#pragma once
// The entry functions of rbm's fuzz targets, shared by the libFuzzer programs in fuzz/ and by
// tests/fuzz/FuzzRegressionTest.cpp, which replays every committed corpus and regression input
// through them in the normal build.
//
// Contract: each function takes arbitrary bytes and either returns (the input was read) or
// throws rbm::InputError (bad input). Anything else -- another exception, a crash, a hang, a
// huge allocation, a sanitizer report -- is a bug in the reader. Where a reader accepted its
// input, the result is checked for the invariants its callers rely on (face point labels in
// range, patches covering the boundary faces, ...); a violation throws std::logic_error,
// which is a bug too.
//
// Files the readers need on disk go to a private temporary folder (the sandbox), created
// once per process and removed at normal exit. The dictionary parser sees its input as
// <sandbox>/case/system/fuzzDict: relative `#include`s resolve inside the sandbox (which holds
// a few files to include, see Sandbox) and `<case>` expands to <sandbox>/case. Absolute
// includes still reach the real file system, as in OpenFOAM; the reader refuses anything but
// regular files (folders, devices such as /dev/zero, FIFOs, sockets).

#include "CompressedFile.hpp"
#include "FoamDictionary.hpp"
#include "FoamDictionaryWriter.hpp"
#include "FoamListIO.hpp"
#include "InputError.hpp"
#include "MeshTopology.hpp"
#include "PointVectorField.hpp"
#include "PolyMesh.hpp"
#include "PolyMeshReader.hpp"

#include <array>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <unistd.h>

#ifndef RBM_TEST_DATA_DIR
#error "RBM_TEST_DATA_DIR (the folder tests/data) must be defined: the point-field target reads its mesh from there"
#endif

namespace rbm::fuzz {

namespace detail {

inline void writeFile(const std::filesystem::path& path, std::string_view bytes)
{
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw std::runtime_error("fuzz harness: cannot write " + path.string());
}

// The per-process temporary folder, created on first use, removed at normal exit.
class Sandbox {
public:
    static const std::filesystem::path& root()
    {
        static Sandbox sandbox;
        return sandbox.root_;
    }

private:
    Sandbox()
    {
        if (const char* fixed = std::getenv("RBM_FUZZ_SANDBOX"); fixed && *fixed) {
            // scripts/fuzz.sh --ci: the same path every run, so that no input's path (whose
            // length and characters the readers loop over) makes two runs differ.
            root_ = fixed;
            std::filesystem::remove_all(root_);
            std::filesystem::create_directories(root_);
        } else {
            std::string pattern = (std::filesystem::temp_directory_path() / "rbm-fuzz-XXXXXX").string();
            if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot create a temporary folder " + pattern);
            root_ = pattern;
        }
        // Files a dictionary input may include ("includeDict", "sub/loopA", "zipped",
        // "<case>/constant/header"): successful includes, a nested one, a loop, a file with
        // its own (binary, 64-bit label) header and a gzip one.
        const std::filesystem::path system = root_ / "case" / "system";
        std::filesystem::create_directories(system / "sub");
        std::filesystem::create_directories(root_ / "case" / "constant");
        writeFile(system / "includeDict", "included 1;\nincludedDict { a 2; b (1 2 3); }\n#include \"sub/nested\"\n");
        writeFile(system / "sub" / "nested", "nested $included;\n");
        writeFile(system / "sub" / "loopA", "#include \"loopB\"\n");
        writeFile(system / "sub" / "loopB", "#include \"loopA\"\n");
        writeFile(root_ / "case" / "constant" / "header",
                  "FoamFile { format binary; class dictionary; arch \"LSB;label=64;scalar=32\"; }\nfromHeader 3;\n");
        // gzip of "zipped 4;\n"
        static constexpr unsigned char zipped[] = {0x1f, 0x8b, 0x08, 0x00, 0x00, 0x00, 0x00, 0x00, 0x02, 0x03, 0xab, 0xca,
                                                   0x2c, 0x28, 0x48, 0x4d, 0x51, 0x30, 0xb1, 0xe6, 0x02, 0x00, 0x53, 0xa0,
                                                   0xa5, 0xd9, 0x0a, 0x00, 0x00, 0x00};
        writeFile(system / "zipped.gz", std::string_view(reinterpret_cast<const char*>(zipped), sizeof zipped));
    }
    ~Sandbox()
    {
        std::error_code ignored;
        std::filesystem::remove_all(root_, ignored);
    }
    std::filesystem::path root_;
};

// An empty folder `name` inside the sandbox (emptied when it exists).
inline std::filesystem::path freshFolder(const std::string& name)
{
    const std::filesystem::path folder = Sandbox::root() / name;
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
    return folder;
}

[[noreturn]] inline void invariantBroken(const std::string& what)
{
    throw std::logic_error("reader accepted input that breaks an invariant: " + what);
}

// Runs `action`, swallowing rbm::InputError (bad input is an expected outcome of each probe).
template <class Action>
void tolerateInputError(Action action)
{
    try {
        action();
    } catch (const InputError&) {
    }
}

// Exercises what callers do with a parsed dictionary: typed getters, list readers,
// pattern lookups, recursively; and writes it back, which must parse again.
inline void exerciseDictionary(const io::Dictionary& dictionary, int depth)
{
    if (depth > 64) return;  // nesting is bounded by the parser; this only keeps the probe cheap
    for (const io::Entry& entry : dictionary.entries()) {
        const std::string& key = entry.keyword();
        if (dictionary.find(key) == nullptr) invariantBroken("find() does not find the entry '" + key + "'");
        if (entry.isDictionary()) {
            exerciseDictionary(entry.dictionary(), depth + 1);
            continue;
        }
        tolerateInputError([&] { (void)dictionary.get<double>(key); });
        tolerateInputError([&] { (void)dictionary.get<Label>(key); });
        tolerateInputError([&] { (void)dictionary.get<std::int64_t>(key); });
        tolerateInputError([&] { (void)dictionary.get<std::string>(key); });
        tolerateInputError([&] { (void)dictionary.get<bool>(key); });
        tolerateInputError([&] { (void)dictionary.get<Vector3>(key); });
        (void)entry.valueText();
        // The list readers on the value, and on the value after a leading word (`uniform`,
        // `nonuniform`, as in field files).
        for (std::size_t skip = 0; skip < 2; ++skip) {
            const auto readList = [&](auto reader) {
                tolerateInputError([&] {
                    io::TokenStream stream = entry.stream(dictionary.header());
                    for (std::size_t k = 0; k < skip && !stream.atEnd(); ++k) stream.next();
                    reader(stream);
                });
            };
            // Bounded, as callers that know the size they expect read lists (a uniform list
            // `2000000000{0}` is valid syntax for 16 GB; the bound is what makes it an error).
            constexpr std::size_t maxCount = std::size_t{1} << 20;
            readList([](io::TokenStream& s) { (void)s.readScalarList(maxCount); });
            readList([](io::TokenStream& s) { (void)s.readLabelList(maxCount); });
            readList([](io::TokenStream& s) { (void)s.readVectorList(maxCount); });
            readList([](io::TokenStream& s) { (void)s.readWordList(maxCount); });
            readList([](io::TokenStream& s) { (void)s.readBool(); });
        }
    }
    // Lookups of names that regular-expression keywords may match.
    for (const char* name : {"inlet", "outlet", "lowerWall", "frontAndBack", "aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa!"}) {
        (void)dictionary.find(name);
    }
}

} // namespace detail

// The OpenFOAM dictionary parser (Dictionary::parseText) on arbitrary text, then the typed
// accessors on every entry, then a write/re-parse round trip.
inline void parseDictionary(std::string_view bytes)
{
    namespace fs = std::filesystem;
    const fs::path file = detail::Sandbox::root() / "case" / "system" / "fuzzDict";
    const io::Dictionary dictionary = io::Dictionary::parseText(bytes, file.string());
    detail::exerciseDictionary(dictionary, 0);

    // What the writer makes of a parsed dictionary must parse again, with the same keywords.
    std::string written;
    try {
        io::appendDictionaryEntries(written, dictionary, 0, 17);
    } catch (const InputError&) {
        return;  // binary data the writer does not know how to print: documented as an InputError
    }
    io::Dictionary reparsed;
    try {
        reparsed = io::Dictionary::parseText(written, file.string());
    } catch (const InputError& error) {
        detail::invariantBroken("the writer's output of a parsed dictionary does not parse: " + std::string(error.what()) +
                                "\n--- written ---\n" + written);
    }
    if (reparsed.keywords() != dictionary.keywords())
        detail::invariantBroken("the writer's output of a parsed dictionary parses to other keywords\n--- written ---\n" +
                                written);
}

// One list file of a polyMesh (header and body, as FoamListReader sees points, faces, owner,
// neighbour): the header's class chooses the list reader, as readPolyMesh does.
inline void readListFile(std::string_view bytes)
{
    const std::string fileName = "fuzzList";
    std::size_t bodyOffset = 0;
    int bodyLine = 1;
    const io::FoamFileHeader header = io::parseFoamFileHeader(bytes, fileName, bodyOffset, bodyLine);
    io::FoamListReader reader(bytes, bodyOffset, fileName, header);
    const std::string& className = header.className;
    if (className == "vectorField") {
        (void)reader.readVectorList("point", bytes.size());
    } else if (className == "faceList" || className == "faceCompactList") {
        std::vector<Label> faceOffsets{0};
        std::vector<Label> facePoints;
        if (className == "faceList") {
            reader.readFaceList(faceOffsets, facePoints);
        } else {
            reader.readFaceCompactList(faceOffsets, facePoints);
        }
        // The compact form PolyMesh relies on: offsets from 0, at least 3 points a face, the
        // last offset the number of point labels.
        if (faceOffsets.empty() || faceOffsets.front() != 0) detail::invariantBroken("face offsets do not start at 0");
        for (std::size_t f = 0; f + 1 < faceOffsets.size(); ++f) {
            if (faceOffsets[f + 1] - faceOffsets[f] < 3) detail::invariantBroken("a face with fewer than 3 points");
        }
        if (static_cast<std::size_t>(faceOffsets.back()) != facePoints.size())
            detail::invariantBroken("the last face offset is not the number of point labels");
    } else if (className == "labelList") {
        (void)reader.readLabelList("label", bytes.size());
    } else if (className == "scalarField" || className == "scalarList") {
        (void)reader.readScalarList("scalar", bytes.size());
    } else if (className == "boolList") {
        (void)reader.readBoolList("flag", bytes.size());
    } else {
        return;  // no list reader for this class; the header parser has been exercised
    }
    reader.expectEnd();
}

// A binary list file: the first byte chooses the list (bits 0-2), 64-bit labels (bit 3) and
// 32-bit scalars (bit 4); a binary FoamFile header saying so is put before the other bytes,
// which form the body. Lets the fuzzer mutate raw binary payloads without breaking headers.
inline void readBinaryListFile(std::string_view bytes)
{
    if (bytes.empty()) return;
    const auto selector = static_cast<unsigned char>(bytes.front());
    static constexpr std::array<const char*, 8> classes = {"vectorField", "faceList",    "faceCompactList", "labelList",
                                                           "scalarField", "boolList",    "labelList",       "vectorField"};
    std::string text = "FoamFile\n{\n    version 2.0;\n    format binary;\n    class ";
    text += classes[selector & 7u];
    text += ";\n    arch \"LSB;label=";
    text += (selector & 8u) != 0 ? "64" : "32";
    text += ";scalar=";
    text += (selector & 16u) != 0 ? "32" : "64";
    text += "\";\n    object fuzzList;\n}\n";
    text.append(bytes.substr(1));
    readListFile(text);
}

// A pointVectorField file (e.g. 0/pointDisplacement) read against the fixed mesh
// tests/data/dictionaries/pointField/ascii (30 points, 5 patches with groups and an empty one).
inline void readPointField(std::string_view bytes)
{
    static const PolyMesh mesh =
        io::readPolyMesh(std::filesystem::path(RBM_TEST_DATA_DIR) / "dictionaries" / "pointField" / "ascii" / "constant" / "polyMesh");
    static const std::filesystem::path folder = detail::freshFolder("pointField/1");
    const std::filesystem::path file = folder / "pointDisplacement";
    detail::writeFile(file, bytes);
    const io::PointVectorField field = io::readPointVectorField(file, mesh);
    if (field.internalField.size() != mesh.points.size())
        detail::invariantBroken("internalField has " + std::to_string(field.internalField.size()) + " values for " +
                                std::to_string(mesh.points.size()) + " points");
    if (field.boundaryField.size() != mesh.patches.size())
        detail::invariantBroken("boundaryField resolved to " + std::to_string(field.boundaryField.size()) + " entries for " +
                                std::to_string(mesh.patches.size()) + " patches");
}

// The separator between the files of a polyMesh in one fuzz input.
inline constexpr std::string_view polyMeshFileSeparator = "@@file@@";
// The files, in the order of the parts of a fuzz input; missing parts leave files absent.
inline constexpr std::array<const char*, 8> polyMeshFileNames = {"points", "faces", "owner", "neighbour", "boundary",
                                                                 "pointZones", "faceZones", "cellZones"};

// Checks what code using a PolyMesh relies on and readPolyMesh promises to validate.
inline void checkPolyMesh(const PolyMesh& mesh)
{
    const auto pointCount = static_cast<std::int64_t>(mesh.points.size());
    if (mesh.faceOffsets.empty() || mesh.faceOffsets.front() != 0) detail::invariantBroken("face offsets do not start at 0");
    const std::size_t faceCount = mesh.faceOffsets.size() - 1;
    if (static_cast<std::size_t>(mesh.faceOffsets.back()) != mesh.facePoints.size())
        detail::invariantBroken("the last face offset is not the number of point labels");
    for (std::size_t f = 0; f < faceCount; ++f) {
        if (mesh.faceOffsets[f + 1] - mesh.faceOffsets[f] < 3) detail::invariantBroken("a face with fewer than 3 points");
    }
    for (Label p : mesh.facePoints) {
        if (p < 0 || p >= pointCount) detail::invariantBroken("point label " + std::to_string(p) + " out of range");
    }
    if (mesh.owner.size() != faceCount) detail::invariantBroken("owner size differs from the number of faces");
    if (mesh.neighbour.size() > faceCount) detail::invariantBroken("more neighbours than faces");
    for (Label c : mesh.owner) {
        if (c < 0) detail::invariantBroken("negative owner");
    }
    for (Label c : mesh.neighbour) {
        if (c < 0) detail::invariantBroken("negative neighbour");
    }
    std::int64_t next = static_cast<std::int64_t>(mesh.neighbour.size());
    for (const Patch& patch : mesh.patches) {
        if (patch.startFace != next || patch.faceCount < 0) detail::invariantBroken("patch '" + patch.name + "' out of order");
        next += patch.faceCount;
    }
    if (next != static_cast<std::int64_t>(faceCount)) detail::invariantBroken("patches do not end at the last face");
    const std::int64_t cellCount = mesh.cellCount();
    const auto checkZones = [](const std::vector<Zone>& zones, std::int64_t limit, const char* kind) {
        for (const Zone& zone : zones) {
            for (Label l : zone.labels) {
                if (l < 0 || l >= limit) detail::invariantBroken(std::string(kind) + " zone label out of range");
            }
        }
    };
    checkZones(mesh.pointZones, pointCount, "point");
    checkZones(mesh.faceZones, static_cast<std::int64_t>(faceCount), "face");
    checkZones(mesh.cellZones, cellCount, "cell");
    for (const Zone& zone : mesh.faceZones) {
        if (zone.flipMap.size() != zone.labels.size()) detail::invariantBroken("flipMap size differs from faceLabels");
    }
}

// A whole polyMesh folder: the input is split at polyMeshFileSeparator into the files
// points, faces, owner, neighbour, boundary (then pointZones, faceZones, cellZones), written
// to an empty folder that readPolyMesh reads; a mesh it accepts then goes through the
// topology code every program runs next.
inline void readPolyMeshFolder(std::string_view bytes)
{
    const std::filesystem::path folder = detail::freshFolder("polyMesh");
    std::size_t start = 0;
    for (const char* name : polyMeshFileNames) {
        const std::size_t end = bytes.find(polyMeshFileSeparator, start);
        detail::writeFile(folder / name, bytes.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
        if (end == std::string_view::npos) break;
        start = end + polyMeshFileSeparator.size();
    }
    const PolyMesh mesh = io::readPolyMesh(folder);
    checkPolyMesh(mesh);
    // What the programs do next with a mesh they have read (rbmCheckMesh, rbmMoveMesh): the
    // cell connectivity, and the check of OpenFOAM's ordering and closed cells. They may
    // reject the mesh with an InputError, but must not fail otherwise.
    (void)buildMeshTopology(mesh);
    (void)checkPolyMeshOrdering(mesh);
}

} // namespace rbm::fuzz

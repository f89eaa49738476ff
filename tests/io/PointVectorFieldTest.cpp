// Tests of pointVectorField reading and writing (io/PointVectorField.hpp). The reference for
// which boundaryField entry applies to which patch is OpenFOAM v1912 itself: the fixture
// tests/data/dictionaries/pointField (makePointFieldFixture.sh) holds a 0/pointDisplacement
// mixing expressions, groups and names, and the 1/pointDisplacement that moveMesh wrote from
// it, with one explicit entry per patch.

#include "CompressedFile.hpp"
#include "FoamDictionaryWriter.hpp"
#include "PointVectorField.hpp"
#include "PolyMeshReader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

namespace fs = std::filesystem;
using rbm::InputError;
using rbm::Label;
using rbm::Patch;
using rbm::PolyMesh;
using rbm::Vector3;
using rbm::io::Dictionary;
using rbm::io::PointPatchFieldEntry;
using rbm::io::PointVectorField;

namespace {

fs::path fixture(const std::string& name)
{
    return fs::path(RBM_TEST_DATA_DIR) / "dictionaries" / "pointField" / name;
}

fs::path scratchFolder(const std::string& name)
{
    fs::path folder = fs::path(testing::TempDir()) / ("rbmPointVectorFieldTest_" + name);
    fs::remove_all(folder);
    fs::create_directories(folder);
    return folder;
}

const PolyMesh& fixtureMesh()
{
    static const PolyMesh mesh = rbm::io::readPolyMesh(fixture("ascii/constant/polyMesh"));
    return mesh;
}

// The vector values of a patch entry's `value` (uniform expanded to `size`).
std::vector<Vector3> patchValues(const PointPatchFieldEntry& entry, std::size_t size, const rbm::io::FoamFileHeader& header)
{
    auto stream = entry.dictionary.lookup("value").stream(header);
    const std::string kind = stream.readWord();
    if (kind == "uniform") return std::vector<Vector3>(size, stream.readVector());
    return stream.readVectorList();
}

// One hexahedron, every face its own patch:
//   inlet (x=0, patch), outlet (x=1, patch), lowerWall (y=0, wall, groups wall),
//   upperWall (y=1, wall, groups wall movingWalls), back (z=0, empty), front (z=1, empty).
PolyMesh unitCube()
{
    PolyMesh mesh;
    mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const std::vector<std::vector<Label>> faces = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4},
                                                   {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};
    for (const auto& f : faces) {
        mesh.addFace(f);
        mesh.owner.push_back(0);
    }
    mesh.patches = {Patch{"inlet", "patch", {}, 0, 1, {}},
                    Patch{"outlet", "patch", {}, 1, 1, {}},
                    Patch{"lowerWall", "wall", {"wall"}, 2, 1, {}},
                    Patch{"upperWall", "wall", {"wall", "movingWalls"}, 3, 1, {}},
                    Patch{"back", "empty", {}, 4, 1, {}},
                    Patch{"front", "empty", {}, 5, 1, {}}};
    return mesh;
}

const std::string header = "FoamFile\n{\n    format ascii;\n    class pointVectorField;\n    object pointDisplacement;\n}\n";  // 6 lines

// Writes a pointVectorField with `boundary` as the body of boundaryField: dimensions on line 7,
// internalField on line 9, boundaryField on line 10, its first entry on line 12.
fs::path writeField(const std::string& name, const std::string& boundary, const std::string& internal = "uniform (0 0 0)")
{
    const fs::path folder = scratchFolder(name);
    const fs::path path = folder / "pointDisplacement";
    std::ofstream(path) << header << "dimensions [0 1 0 0 0 0 0];\n\ninternalField " << internal
                        << ";\nboundaryField\n{\n" << boundary << "}\n";
    return path;
}

InputError readError(const fs::path& path, const PolyMesh& mesh)
{
    try {
        rbm::io::readPointVectorField(path, mesh);
    } catch (const InputError& error) {
        return error;
    }
    ADD_FAILURE() << "no InputError reading " << path;
    return InputError("", 0, "");
}

const std::string allPatches = "    \"(inlet|outlet)\" { type fixedValue; value uniform (0 0 0); }\n"
                               "    wall { type slip; }\n";

} // namespace

// ---- against OpenFOAM ----

TEST(PointVectorField, ResolvesEntriesExactlyAsOpenFoamDoes)
{
    const PolyMesh& mesh = fixtureMesh();
    ASSERT_EQ(mesh.patches.size(), 5u);
    const PointVectorField input = rbm::io::readPointVectorField(fixture("ascii/0/pointDisplacement"), mesh);
    const PointVectorField resolvedByOpenFoam = rbm::io::readPointVectorField(fixture("ascii/1/pointDisplacement"), mesh);

    using Match = PointPatchFieldEntry::Match;
    const std::vector<std::string> keywords = {"(inlet|outlet)", "outlet", "movingWalls", "upperWall", "frontAndBack"};
    const std::vector<Match> matches = {Match::Pattern, Match::PatchName, Match::Group, Match::PatchName, Match::ImplicitEmpty};
    ASSERT_EQ(input.boundaryField.size(), 5u);
    for (std::size_t p = 0; p < 5; ++p) {
        const PointPatchFieldEntry& ours = input.boundaryField[p];
        const PointPatchFieldEntry& openFoams = resolvedByOpenFoam.boundaryField[p];
        SCOPED_TRACE(mesh.patches[p].name);
        EXPECT_EQ(ours.patchName, mesh.patches[p].name);
        EXPECT_EQ(ours.keyword, keywords[p]);
        EXPECT_EQ(ours.match, matches[p]);
        EXPECT_EQ(openFoams.match, Match::PatchName);  // OpenFOAM writes every patch by name
        EXPECT_EQ(ours.type, openFoams.type);
        if (ours.type != "empty") {
            const std::size_t size = rbm::io::patchPointLabels(mesh, static_cast<Label>(p)).size();
            EXPECT_EQ(patchValues(ours, size, input.header), patchValues(openFoams, size, resolvedByOpenFoam.header));
        }
    }
    EXPECT_EQ(input.boundaryField[1].dictionary.lookup("value").valueText(), "uniform ( 4 0 0 )");
    EXPECT_TRUE(input.internalFieldUniform);
    EXPECT_EQ(input.internalField.size(), 30u);
    EXPECT_FALSE(resolvedByOpenFoam.internalFieldUniform);
    EXPECT_EQ(input.dimensions, (std::array<double, 7>{0, 1, 0, 0, 0, 0, 0}));
}

TEST(PointVectorField, PatchPointOrderIsOpenFoams)
{
    // OpenFOAM copied upperWall's nonuniform value into the internal field at the patch's
    // points: value[i] belongs to patchPointLabels[i]. The end points shared with inlet and
    // outlet take another patch's value and are skipped.
    const PolyMesh& mesh = fixtureMesh();
    const PointVectorField field = rbm::io::readPointVectorField(fixture("ascii/1/pointDisplacement"), mesh);
    const Label upperWall = mesh.findPatch("upperWall");
    const std::vector<Label> points = rbm::io::patchPointLabels(mesh, upperWall);
    ASSERT_EQ(points.size(), 10u);
    std::set<Label> shared;
    for (const char* other : {"inlet", "outlet"}) {
        for (Label p : rbm::io::patchPointLabels(mesh, mesh.findPatch(other))) shared.insert(p);
    }
    const std::vector<Vector3> values = patchValues(field.boundaryField[static_cast<std::size_t>(upperWall)], 10, field.header);
    int compared = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (shared.count(points[i])) continue;
        EXPECT_EQ(field.internalField[static_cast<std::size_t>(points[i])], values[i]) << "patch point " << i;
        ++compared;
    }
    EXPECT_EQ(compared, 6);
    // Distinct values: a wrong order could not pass.
    EXPECT_EQ(values[0], (Vector3{0.5, 0, 0}));
    EXPECT_EQ(values[9], (Vector3{0.59, 0, 0}));
}

TEST(PointVectorField, BinaryFileGivesTheAsciiValues)
{
    const PolyMesh& mesh = fixtureMesh();
    const PointVectorField ascii = rbm::io::readPointVectorField(fixture("ascii/1/pointDisplacement"), mesh);
    const PointVectorField binary = rbm::io::readPointVectorField(fixture("binary/1/pointDisplacement"), mesh);
    ASSERT_TRUE(binary.header.isBinary());
    ASSERT_EQ(binary.internalField.size(), ascii.internalField.size());
    for (std::size_t i = 0; i < ascii.internalField.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            // The ascii file has 6 significant digits.
            EXPECT_NEAR(binary.internalField[i][c], ascii.internalField[i][c], 5e-6 * std::abs(ascii.internalField[i][c]) + 1e-12);
        }
    }
    const Label upperWall = mesh.findPatch("upperWall");
    const auto& entry = binary.boundaryField[static_cast<std::size_t>(upperWall)];
    EXPECT_EQ(entry.dictionary.lookup("value").tokens().back().kind, rbm::io::Token::Kind::Binary);
    EXPECT_EQ(patchValues(entry, 10, binary.header), patchValues(ascii.boundaryField[static_cast<std::size_t>(upperWall)], 10, ascii.header));
}

// ---- writing ----

TEST(PointVectorField, WrittenFileReadsBackWithTheSameEntriesAndValues)
{
    const PolyMesh& mesh = fixtureMesh();
    const PointVectorField binary = rbm::io::readPointVectorField(fixture("binary/1/pointDisplacement"), mesh);
    const fs::path folder = scratchFolder("write");
    rbm::io::PointVectorFieldWriteOptions options;
    options.precision = 15;
    const fs::path written = rbm::io::writePointVectorField(folder / "0.005" / "pointDisplacement", binary.internalField,
                                                            binary.boundaryField, options);
    EXPECT_EQ(written, folder / "0.005" / "pointDisplacement");
    const std::string text = rbm::io::readFileContents(written);
    EXPECT_NE(text.find("location    \"0.005\";"), std::string::npos);
    EXPECT_NE(text.find("object      pointDisplacement;"), std::string::npos);
    EXPECT_NE(text.find("class       pointVectorField;"), std::string::npos);
    EXPECT_NE(text.find("    upperWall\n    {\n        type            fixedValue;\n"), std::string::npos) << text;

    const PointVectorField back = rbm::io::readPointVectorField(written, mesh);
    EXPECT_FALSE(back.header.isBinary());
    ASSERT_EQ(back.internalField.size(), binary.internalField.size());
    for (std::size_t i = 0; i < back.internalField.size(); ++i) {
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(back.internalField[i][c], binary.internalField[i][c], 1e-14 * (1 + std::abs(binary.internalField[i][c])));
    }
    for (std::size_t p = 0; p < back.boundaryField.size(); ++p) {
        EXPECT_EQ(back.boundaryField[p].type, binary.boundaryField[p].type);
        EXPECT_EQ(back.boundaryField[p].match, PointPatchFieldEntry::Match::PatchName);
    }
    const Label upperWall = mesh.findPatch("upperWall");
    EXPECT_EQ(patchValues(back.boundaryField[static_cast<std::size_t>(upperWall)], 10, back.header)[3], (Vector3{0.53, 0, 0}));
}

TEST(PointVectorField, WriterUsesUniformWhenAllValuesAreEqualAndCompresses)
{
    const PolyMesh& mesh = fixtureMesh();
    PointVectorField field = rbm::io::readPointVectorField(fixture("ascii/0/pointDisplacement"), mesh);
    // Replace upperWall's value by 12 values... of which the patch has 10: use the right count.
    const Label upperWall = mesh.findPatch("upperWall");
    std::vector<Vector3> newValues;
    for (int i = 0; i < 10; ++i) newValues.push_back({0.1 * i, 1.0 / 3.0, -1e-7 * i});
    field.boundaryField[static_cast<std::size_t>(upperWall)].dictionary.set(rbm::io::vectorFieldEntry("value", newValues));

    rbm::io::PointVectorFieldWriteOptions options;
    options.compressed = true;
    options.precision = 17;
    const fs::path folder = scratchFolder("uniform");
    const fs::path written = rbm::io::writePointVectorField(folder / "1" / "pointDisplacement", field.internalField,
                                                            field.boundaryField, options);
    EXPECT_EQ(written.filename(), "pointDisplacement.gz");
    const std::string text = rbm::io::readFileContents(written);
    EXPECT_NE(text.find("internalField   uniform (0 0 0);"), std::string::npos) << text;
    EXPECT_NE(text.find("value           uniform (3 0 0);"), std::string::npos) << text;  // inlet, from "(inlet|outlet)"

    const PointVectorField back = rbm::io::readPointVectorField(folder / "1" / "pointDisplacement", mesh);
    EXPECT_EQ(patchValues(back.boundaryField[static_cast<std::size_t>(upperWall)], 10, back.header), newValues);
    EXPECT_EQ(back.boundaryField[4].type, "empty");
}

TEST(PointVectorField, StreamedWriteIsTheWholeTextWrite)
{
    // A field of 5000 points written in pieces of 512 bytes (about 300 of them) and in one
    // piece (the whole text, then writeFileContents: how every field was written before):
    // the same text, plain and gzip-compressed.
    const PolyMesh& mesh = fixtureMesh();
    const PointVectorField field = rbm::io::readPointVectorField(fixture("binary/1/pointDisplacement"), mesh);
    std::vector<Vector3> values;
    for (int i = 0; i < 5000; ++i) values.push_back({1e-3 * std::sin(i), -0.25 * i, i % 7 == 0 ? 0.0 : 1.0 / (i + 3)});
    const fs::path folder = scratchFolder("streamed");
    for (const bool compressed : {false, true}) {
        SCOPED_TRACE(compressed ? "gzip" : "plain");
        rbm::io::PointVectorFieldWriteOptions options;
        options.compressed = compressed;
        options.location = "0.5";   // the same header in both folders
        options.pieceSize = 512;
        const fs::path pieces = rbm::io::writePointVectorField(folder / "pieces" / "pointDisplacement", values,
                                                               field.boundaryField, options);
        options.pieceSize = std::size_t{1} << 30;
        const fs::path whole = rbm::io::writePointVectorField(folder / "whole" / "pointDisplacement", values,
                                                              field.boundaryField, options);
        const std::string text = rbm::io::readFileContents(whole);
        EXPECT_GT(text.size(), 100u * 512);
        EXPECT_EQ(rbm::io::readFileContents(pieces), text);
        EXPECT_NE(text.find("location    \"0.5\";"), std::string::npos);
    }
}

TEST(PointVectorField, DictionaryWriterLaysOutEntriesLikeOpenFoam)
{
    Dictionary d = Dictionary::parseText("a 1;\nlongKeywordOfMoreThan16 (1 2);\n\"(in|out)\" { type slip; s \"x y\"; }\n"
                                         "div(phi,U) Gauss linear;\nempty;\n",
                                         "dict");
    std::string out;
    rbm::io::appendDictionaryEntries(out, d, 1, 6);
    EXPECT_EQ(out, "    a               1;\n"
                   "    longKeywordOfMoreThan16 (1 2);\n"
                   "    \"(in|out)\"\n    {\n        type            slip;\n        s               \"x y\";\n    }\n"
                   "    div(phi,U)      Gauss linear;\n"
                   "    empty;\n");
    std::vector<Vector3> many(12, Vector3{1, 2, 3});
    many[5] = {0.1234567, 0, 0};
    out.clear();
    rbm::io::appendEntry(out, rbm::io::vectorFieldEntry("value", many), 0, 3);
    EXPECT_EQ(out.rfind("value           nonuniform List<vector>\n12\n(\n(1 2 3)\n", 0), 0u) << out;
    EXPECT_NE(out.find("\n(0.123 0 0)\n"), std::string::npos) << out;
    EXPECT_EQ(out.substr(out.size() - 5), "\n)\n;\n");
}

// ---- errors ----

TEST(PointVectorFieldErrors, MissingPatchEntryNamesFileAndPatch)
{
    const fs::path path = writeField("missing", "    wall { type slip; }\n");
    const InputError error = readError(path, unitCube());
    EXPECT_EQ(error.file(), path.string());
    EXPECT_EQ(error.line(), 10);  // the boundaryField keyword
    EXPECT_NE(error.message().find("no entry for patch 'inlet'"), std::string::npos) << error.message();
}

TEST(PointVectorFieldErrors, EntryMatchingNoPatchNamesFileLineAndEntry)
{
    const fs::path path = writeField("unmatched", allPatches + "    inlte { type fixedValue; value uniform (0 0 0); }\n");
    const InputError error = readError(path, unitCube());
    EXPECT_EQ(error.file(), path.string());
    EXPECT_EQ(error.line(), 14);
    EXPECT_NE(error.message().find("'inlte' matches no patch"), std::string::npos) << error.message();

    const fs::path pattern = writeField("unmatchedPattern", allPatches + "\n    \"side.*\" { type slip; }\n");
    const InputError patternError = readError(pattern, unitCube());
    EXPECT_EQ(patternError.line(), 15);
    EXPECT_NE(patternError.message().find("'side.*'"), std::string::npos) << patternError.message();
}

TEST(PointVectorFieldErrors, UnusedEmptyAndPatchTypeGroupEntriesAreAccepted)
{
    const fs::path path = writeField("unusedAllowed", allPatches + "    frontAndBack { type empty; }\n"
                                                                   "    symmetryPlane { type symmetry; }\n"
                                                                   "    variable 3;\n");
    const PointVectorField field = rbm::io::readPointVectorField(path, unitCube());
    EXPECT_EQ(field.boundaryField[2].keyword, "wall");
    EXPECT_EQ(field.boundaryField[2].match, PointPatchFieldEntry::Match::Group);
    EXPECT_EQ(field.boundaryField[4].match, PointPatchFieldEntry::Match::ImplicitEmpty);
}

TEST(PointVectorFieldErrors, LaterGroupWinsAndEmptyPatchesCanHaveEntries)
{
    const fs::path path = writeField("groups", "    \"(inlet|outlet)\" { type fixedValue; value uniform (0 0 0); }\n"
                                               "    movingWalls { type fixedValue; value uniform (1 0 0); }\n"
                                               "    wall { type slip; }\n"
                                               "    back { type empty; }\n"
                                               "    \"fr.*\" { type empty; }\n");
    const PointVectorField field = rbm::io::readPointVectorField(path, unitCube());
    EXPECT_EQ(field.boundaryField[2].type, "slip");       // lowerWall: wall only
    EXPECT_EQ(field.boundaryField[3].type, "slip");       // upperWall: wall is later than movingWalls
    EXPECT_EQ(field.boundaryField[4].match, PointPatchFieldEntry::Match::PatchName);
    EXPECT_EQ(field.boundaryField[5].match, PointPatchFieldEntry::Match::ImplicitEmpty);  // empty before expressions
}

TEST(PointVectorFieldErrors, InternalFieldOfTheWrongLength)
{
    const fs::path path = writeField("internalLength", allPatches, "nonuniform List<vector> 2((0 0 0) (1 1 1))");
    const InputError error = readError(path, unitCube());
    EXPECT_EQ(error.file(), path.string());
    EXPECT_EQ(error.line(), 9);
    EXPECT_NE(error.message().find("internalField"), std::string::npos) << error.message();
    EXPECT_NE(error.message().find("has 2 values but 8 are needed"), std::string::npos) << error.message();
}

TEST(PointVectorFieldErrors, PatchValueOfTheWrongLength)
{
    const fs::path path = writeField("patchLength", "    \"(inlet|outlet)\" { type fixedValue; value uniform (0 0 0); }\n"
                                                    "    wall { type slip; }\n"
                                                    "    upperWall\n    {\n        type fixedValue;\n"
                                                    "        value nonuniform List<vector> 3((0 0 0) (1 0 0) (2 0 0));\n    }\n");
    const InputError error = readError(path, unitCube());
    EXPECT_EQ(error.line(), 17);
    EXPECT_NE(error.message().find("patch 'upperWall'"), std::string::npos) << error.message();
    EXPECT_NE(error.message().find("has 3 values but 4 are needed"), std::string::npos) << error.message();
}

TEST(PointVectorFieldErrors, EntryWithoutTypeAndBadDimensionsAndClass)
{
    const InputError noType = readError(writeField("noType", "    \"(inlet|outlet)\" { value uniform (0 0 0); }\n    wall { type slip; }\n"), unitCube());
    EXPECT_EQ(noType.line(), 12);
    EXPECT_NE(noType.message().find("has no 'type'"), std::string::npos) << noType.message();

    const fs::path folder = scratchFolder("badHeader");
    std::ofstream(folder / "dims") << header << "dimensions [0 1 0];\ninternalField uniform (0 0 0);\nboundaryField { }\n";
    const InputError dims = readError(folder / "dims", unitCube());
    EXPECT_EQ(dims.line(), 7);
    EXPECT_NE(dims.message().find("7 exponents"), std::string::npos) << dims.message();

    std::ofstream(folder / "scalar") << "FoamFile { format ascii; class pointScalarField; }\ndimensions [0 1 0 0 0 0 0];\n";
    const InputError wrongClass = readError(folder / "scalar", unitCube());
    EXPECT_EQ(wrongClass.file(), (folder / "scalar").string());
    EXPECT_NE(wrongClass.message().find("pointScalarField"), std::string::npos) << wrongClass.message();

    const InputError internalKind = readError(writeField("kind", allPatches, "(0 0 0)"), unitCube());
    EXPECT_EQ(internalKind.line(), 9);
    EXPECT_NE(internalKind.message().find("'uniform' or 'nonuniform'"), std::string::npos) << internalKind.message();
}

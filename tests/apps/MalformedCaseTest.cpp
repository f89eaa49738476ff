// Every kind of bad input of issue 6, end to end: rbmMoveMesh's run (apps/MoveMeshRun) on a
// copy of the committed valid case tests/data/malformedCases/base with one committed
// malformed file laid over it (tests/data/malformedCases/<name>/, made by
// makeMalformedCases.sh, which says how each was spoilt). Each must exit with status 2
// (bad input) without a crash or a hang, print a message naming the file, the line (or, for
// checks across files, the entry: face, cell, patch) and what was expected, say "Nothing was
// written.", and leave every file of the case folder byte for byte as it was, with nothing
// added. The line numbers are those of the spoilt entries in the committed files (the ascii
// files OpenFOAM writes have a 16-line banner and header, a blank line, then the list size).

#include "ScratchFiles.hpp"
#include "MoveMeshRun.hpp"
#include "PetscTestEnvironment.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace rbm;

const fs::path fixtures = fs::path(RBM_TEST_DATA_DIR) / "malformedCases";

struct Malformed {
    std::string name;                   // folder under malformedCases/ (may not exist: only removals)
    std::string file;                   // the file the message must name, relative to the case
    int line = 0;                       // its line in the message; 0: no line (the entry is named instead)
    std::vector<std::string> expected;  // what the message must say besides
    std::vector<std::string> remove{};  // files of base/ to delete (relative to the case)
};

void PrintTo(const Malformed& malformed, std::ostream* out) { *out << malformed.name; }

// Every file and folder of the case with its bytes.
std::map<std::string, std::string> snapshot(const fs::path& root)
{
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        files[fs::relative(entry.path(), root).string()] = entry.is_directory() ? "<folder>" : rbm::test::readText(entry.path());
    }
    return files;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

class MalformedCase : public ::testing::TestWithParam<Malformed> {};

TEST(MalformedCaseFixture, TheBaseCaseRuns)
{
    // The malformed cases fail because of their one spoilt file, not because of the base.
    const fs::path caseDir = fs::temp_directory_path() / ("rbmMalformedCaseTest_base_" + std::to_string(::getpid()));
    fs::remove_all(caseDir);
    fs::copy(fixtures / "base", caseDir, fs::copy_options::recursive);
    std::ostringstream out;
    std::ostringstream err;
    app::MoveMeshOptions options;
    options.caseDirectory = caseDir;
    EXPECT_EQ(app::runMoveMesh(options, out, err), app::exitSuccess) << out.str() << err.str();
    EXPECT_TRUE(fs::exists(caseDir / "0.1" / "polyMesh" / "points"));
    fs::remove_all(caseDir);
}

TEST_P(MalformedCase, ExitsWithTwoNamingFileLineAndExpectationAndLeavesTheCaseAsItWas)
{
    const Malformed& malformed = GetParam();
    const fs::path caseDir =
        fs::temp_directory_path() / ("rbmMalformedCaseTest_" + malformed.name + "_" + std::to_string(::getpid()));
    fs::remove_all(caseDir);
    fs::copy(fixtures / "base", caseDir, fs::copy_options::recursive);
    if (fs::exists(fixtures / malformed.name)) {
        fs::copy(fixtures / malformed.name, caseDir, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    }
    for (const std::string& file : malformed.remove) ASSERT_TRUE(fs::remove(caseDir / file)) << file;
    const auto before = snapshot(caseDir);

    std::ostringstream out;
    std::ostringstream err;
    app::MoveMeshOptions options;
    options.caseDirectory = caseDir;
    const int status = app::runMoveMesh(options, out, err);
    const std::string message = err.str();

    EXPECT_EQ(status, app::exitBadInput) << out.str() << message;
    const std::string where =
        (caseDir / malformed.file).string() + (malformed.line > 0 ? ":" + std::to_string(malformed.line) : "") + ": ";
    EXPECT_TRUE(contains(message, "rbmMoveMesh: " + where)) << "expected the message to start with '" << where
                                                            << "':\n" << message;
    for (const std::string& part : malformed.expected) EXPECT_TRUE(contains(message, part)) << part << "\n" << message;
    EXPECT_TRUE(contains(message, "Nothing was written.")) << message;
    EXPECT_TRUE(snapshot(caseDir) == before) << "the case folder changed";
    fs::remove_all(caseDir);
}

const std::string polyMesh = "constant/polyMesh/";

INSTANTIATE_TEST_SUITE_P(
    Cases, MalformedCase,
    ::testing::Values(
        // --- polyMesh: truncated files, counts that disagree with the data, huge counts -------
        Malformed{"truncatedPoints", polyMesh + "points", 19, {"list claims 24 points but the file has only 98 bytes left"}},
        Malformed{"pointCountLargerThanData", polyMesh + "points", 45, {"list of 25 points ends after 24 entries"}},
        Malformed{"pointCountSmallerThanData", polyMesh + "points", 44,
                  {"list of 23 points has more entries than its size (expected ')'"}},
        Malformed{"faceCountOf2To31", polyMesh + "faces", 19, {"list of 2147483648 faces", "32-bit labels"}},
        // --- faces, labels, owner/neighbour, upper-triangular order, closedness --------------
        Malformed{"faceWithTwoPoints", polyMesh + "faces", 21, {"face 0 has 2 points; a face needs at least 3"}},
        Malformed{"pointLabelOutOfRange", polyMesh + "faces", 0,
                  {"face 0 refers to point 24 but the points file has 24 points (valid labels 0 to 23)"}},
        Malformed{"faceZoneLabelOutOfRange", polyMesh + "faceZones", 22,
                  {"zone 'middle': label 29 (entry 1) is out of range; the mesh has 29 faces"}},
        Malformed{"ownerShorterThanFaces", polyMesh + "owner", 0,
                  {"owner has 28 entries but the faces file has 29 faces (expected one owner cell per face)"}},
        Malformed{"neighbourLongerThanTheInternalFaces", polyMesh + "boundary", 0,
                  {"patch 'left' starts at face 7 but the internal faces (one per neighbour entry) end at face 8",
                   "expected startFace 8"}},
        Malformed{"notUpperTriangular", "constant/polyMesh", 0,
                  {"face 1 (owner 0, neighbour 1) comes after face 0 (owner 0, neighbour 3)",
                   "sorted by owner, then neighbour (upper-triangular order)"}},
        Malformed{"meshNotClosed", "constant/polyMesh", 0,
                  {"cell 0 is not closed or not consistently oriented: its edge 4-16 has no matching reversed edge"}},
        Malformed{"missingOwner", polyMesh + "owner", 0, {"file not found"}, {polyMesh + "owner"}},
        // --- boundary patches ----------------------------------------------------------------
        Malformed{"patchesOverlap", polyMesh + "boundary", 0,
                  {"patch 'right' starts at face 8 but the previous patch 'left' ends at face 9 (overlap of 1 faces)",
                   "expected startFace 9"}},
        Malformed{"patchesLeaveAGap", polyMesh + "boundary", 0,
                  {"patch 'right' starts at face 10 but the previous patch 'left' ends at face 9 (gap of 1 faces)",
                   "expected startFace 9"}},
        Malformed{"patchRunsPastTheLastFace", polyMesh + "boundary", 0,
                  {"patch 'frontAndBack' (startFace 17, nFaces 13) runs past the last face; the mesh has 29 faces"}},
        // --- coordinates ----------------------------------------------------------------------
        Malformed{"nanCoordinate", polyMesh + "points", 22, {"expected a finite coordinate but found 'nan'"}},
        Malformed{"infiniteCoordinate", polyMesh + "points", 22, {"expected a finite coordinate but found 'inf"}},
        // --- formats: arch, gzip, ascii under a binary header ---------------------------------
        Malformed{"binaryArchMismatch", polyMesh + "points", 21,
                  {"expected ')' after the 288 bytes of a binary list of 24 points", "arch"}},
        Malformed{"corruptGzip", polyMesh + "points.gz", 0, {"corrupt gzip stream"}, {polyMesh + "points"}},
        Malformed{"asciiFileSaysBinary", polyMesh + "points", 19,
                  {"binary list of 24 points needs 576 bytes but the file has only 301 left", "arch"}},
        // --- dictionaries ---------------------------------------------------------------------
        Malformed{"dictionarySyntaxError", "system/controlDict", 13,
                  {"entry 'endTime'", "expected a single number but found '0.1 deltaT 0.1'"}},
        Malformed{"unclosedBrace", "constant/dynamicMeshDict", 12,
                  {"unterminated dictionary 'dynamicMeshDict/rigidBodyMotionSolverCoeffs'", "never closed"}},
        Malformed{"includeLoop", "system/controlDict", 9, {"#include loop"}},
        Malformed{"missingInclude", "system/controlDict", 9, {"cannot find the file \"commonSettings\" included here"}},
        Malformed{"nestedThousandsDeep", "constant/dynamicMeshDict", 1016, {"nested deeper than 1000 levels"}},
        // --- pointDisplacement ----------------------------------------------------------------
        Malformed{"missingPatch", "0/pointDisplacement", 11, {"no entry for patch 'right'"}},
        Malformed{"unknownPatch", "0/pointDisplacement", 23, {"entry 'wing' matches no patch of the mesh"}},
        Malformed{"unknownType", "0/pointDisplacement", 20,
                  {"Unknown patchField type movingWallDisplacement for patch right", "Valid patchField types are: "}},
        Malformed{"nonuniformListOfTheWrongLength", "0/pointDisplacement", 16,
                  {"value of patch 'left' (one value per patch point) has 5 values but 6 are needed"}},
        Malformed{"patchBothMovingAndSliding", "0/pointDisplacement", 25,
                  {"patch top is a symmetryPlane patch", "gives it type fixedValue, a prescribed motion",
                   "a patch cannot both move and slide", "Expected type symmetryPlane"}},
        // --- dynamicMeshDict and controlDict ---------------------------------------------------
        Malformed{"misspeltSolverName", "constant/dynamicMeshDict", 10,
                  {"Unknown motionSolver type rigidBodyMotionSolvr. Valid motionSolver types are: rbmMotionSolver rigidBodyMotionSolver"}},
        Malformed{"misspeltKeyword", "constant/dynamicMeshDict", 13,
                  {"unknown keyword 'formulaton'", "Valid keywords are: coupling formulation"}},
        Malformed{"negativeDeltaT", "system/controlDict", 14, {"entry 'deltaT'", "must be > 0, found -0.1"}},
        Malformed{"endTimeBeforeStartTime", "system/controlDict", 13, {"endTime -1 is before startTime 0"}}),
    [](const ::testing::TestParamInfo<Malformed>& info) { return info.param.name; });

} // namespace

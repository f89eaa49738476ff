// Reading decomposePar's processor folders (DecomposedCase) from the committed fixture
// tests/data/decomposed (tests/data/makeDecomposedFixture.sh: a 6 × 5 × 4 box in 4
// processors, simple (2 2 1)): the folder count, each processor's mesh and its
// pointProcAddressing against the undecomposed mesh, and the errors for broken cases.

#include "DecomposedCase.hpp"
#include "InputError.hpp"
#include "PolyMeshReader.hpp"
#include "ScratchFiles.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

namespace {

using namespace rbm;
namespace fs = std::filesystem;

const fs::path fixture = fs::path(RBM_TEST_DATA_DIR) / "decomposed";

TEST(DecomposedCase, CountsTheProcessorFolders)
{
    EXPECT_EQ(io::countProcessorFolders(fixture), 4);
    EXPECT_EQ(io::countProcessorFolders(fs::path(RBM_TEST_DATA_DIR) / "formats" / "ascii"), 0);
}

TEST(DecomposedCase, EveryPointMapsToTheSamePointOfTheWholeMesh)
{
    const PolyMesh whole = io::readPolyMesh(fixture / "constant" / "polyMesh");
    Label cells = 0;
    std::set<Label> covered;
    for (int processor = 0; processor < 4; ++processor) {
        const io::ProcessorMesh part = io::readProcessorMesh(fixture, processor);
        ASSERT_EQ(part.pointProcAddressing.size(), part.mesh.points.size());
        for (std::size_t p = 0; p < part.mesh.points.size(); ++p) {
            const Label g = part.pointProcAddressing[p];
            ASSERT_LT(g, whole.pointCount());
            EXPECT_EQ(part.mesh.points[p], whole.points[g]) << "processor" << processor << " point " << p;
            covered.insert(g);
        }
        cells += part.mesh.cellCount();
        // The simple (2 2 1) split: each processor meets two others through faces, never the
        // diagonal one, with which it shares only the points of the middle edge.
        std::set<std::string> neighbours;
        for (const Patch& patch : part.mesh.patches)
            if (patch.type == "processor")
                for (const auto& [key, value] : patch.otherEntries)
                    if (key == "neighbProcNo") neighbours.insert(value);
        EXPECT_EQ(neighbours.size(), 2u) << "processor" << processor;
        EXPECT_EQ(neighbours.count(std::to_string(3 - processor)), 0u) << "processor" << processor;
    }
    EXPECT_EQ(cells, whole.cellCount());
    EXPECT_EQ(static_cast<Label>(covered.size()), whole.pointCount());
}

// A copy of the fixture to break (processors 0 and 1 only).
fs::path copyOfFixture(const rbm::test::TempDir& scratch)
{
    const fs::path copy = scratch.path() / "case";
    fs::create_directories(copy);
    for (int processor : {0, 1})
        fs::copy(fixture / ("processor" + std::to_string(processor)), copy / ("processor" + std::to_string(processor)),
                 fs::copy_options::recursive);
    return copy;
}

TEST(DecomposedCase, AGapInTheProcessorNumbersIsAnError)
{
    const rbm::test::TempDir scratch(::testing::UnitTest::GetInstance()->current_test_info()->name());
    const fs::path copy = copyOfFixture(scratch);
    fs::rename(copy / "processor1", copy / "processor2");
    try {
        io::countProcessorFolders(copy);
        FAIL() << "expected an InputError";
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find("without a gap"), std::string::npos) << error.what();
    }
}

TEST(DecomposedCase, AMissingOrShortPointProcAddressingNamesTheFile)
{
    const rbm::test::TempDir scratch(::testing::UnitTest::GetInstance()->current_test_info()->name());
    const fs::path copy = copyOfFixture(scratch);
    const fs::path addressing = copy / "processor1" / "constant" / "polyMesh" / "pointProcAddressing";
    fs::remove(addressing);
    EXPECT_THROW(io::readProcessorMesh(copy, 1), InputError);
    std::ofstream(addressing) << "FoamFile { version 2.0; format ascii; class labelList; object pointProcAddressing; }\n"
                                 "3 ( 0 1 2 )\n";
    try {
        io::readProcessorMesh(copy, 1);
        FAIL() << "expected an InputError";
    } catch (const InputError& error) {
        EXPECT_NE(error.file().find("pointProcAddressing"), std::string::npos) << error.file();
        EXPECT_NE(std::string(error.what()).find("one label per point"), std::string::npos) << error.what();
    }
}

TEST(DecomposedCase, AProcessorPatchOfAnotherProcessorIsAnError)
{
    const rbm::test::TempDir scratch(::testing::UnitTest::GetInstance()->current_test_info()->name());
    const fs::path copy = copyOfFixture(scratch);
    // processor1's folder read as processor 0's: its processor patches say myProcNo 1.
    fs::rename(copy / "processor0", copy / "processorX");
    fs::rename(copy / "processor1", copy / "processor0");
    EXPECT_THROW(io::readProcessorMesh(copy, 0), InputError);
}

} // namespace

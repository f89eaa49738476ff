// Tests of the time folder writer (io/TimeFolderWriter): points and pointDisplacement written
// whole or not at all.

#include "FoamDictionaryWriter.hpp"
#include "MeshGenerators.hpp"
#include "PetscTestEnvironment.hpp"
#include "PointVectorField.hpp"
#include "PolyMeshReader.hpp"
#include "PolyMeshWriter.hpp"
#include "RigidBodyMotionSolver.hpp"
#include "RunLog.hpp"
#include "ScratchFiles.hpp"
#include "TestCases.hpp"
#include "TimeFolderWriter.hpp"
#include "TimeName.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace rbm::test::moveMeshCases;

namespace {

using namespace rbm;

TEST(TimeFolderWriter, CommitTurnsTheStagingFolderIntoTheTimeFolder)
{
    TempDir dir("commitNew");
    fs::path staging;
    {
        io::TimeFolderWriter folder(dir.path(), "0.5");
        staging = folder.staging();
        EXPECT_EQ(staging.parent_path(), dir.path());
        EXPECT_EQ(staging.filename().string().rfind("0.5.tmp-", 0), 0u) << staging;
        writeText(folder.staging() / "polyMesh" / "points", "points");
        writeText(folder.staging() / "pointDisplacement", "displacement");
        // Not visible as a time before commit.
        EXPECT_TRUE(timeFolders(dir.path()).empty());
        EXPECT_FALSE(fs::exists(dir.path() / "0.5"));
        EXPECT_EQ(folder.commit(), dir.path() / "0.5");
    }
    EXPECT_FALSE(fs::exists(staging));
    EXPECT_EQ(readText(dir.path() / "0.5" / "polyMesh" / "points"), "points");
    EXPECT_EQ(readText(dir.path() / "0.5" / "pointDisplacement"), "displacement");
    EXPECT_EQ(timeFolders(dir.path()), std::set<std::string>{"0.5"});
}

TEST(TimeFolderWriter, CommitIntoAnExistingTimeKeepsOtherFilesAndRemovesCompressionTwins)
{
    TempDir dir("commitExisting");
    writeText(dir.path() / "0.5" / "U", "velocity of a flow solver");
    writeText(dir.path() / "0.5" / "polyMesh" / "points", "old points");
    writeText(dir.path() / "0.5" / "pointDisplacement.gz", "old compressed displacement");
    {
        io::TimeFolderWriter folder(dir.path(), "0.5");
        writeText(folder.staging() / "polyMesh" / "points.gz", "new points");
        writeText(folder.staging() / "pointDisplacement", "new displacement");
        folder.commit();
    }
    EXPECT_EQ(readText(dir.path() / "0.5" / "U"), "velocity of a flow solver");
    EXPECT_EQ(readText(dir.path() / "0.5" / "polyMesh" / "points.gz"), "new points");
    EXPECT_FALSE(fs::exists(dir.path() / "0.5" / "polyMesh" / "points"));
    EXPECT_EQ(readText(dir.path() / "0.5" / "pointDisplacement"), "new displacement");
    EXPECT_FALSE(fs::exists(dir.path() / "0.5" / "pointDisplacement.gz"));
    expectNoTemporaryFiles(dir.path());
}

// The identity of a file or folder (device, inode): unchanged by renames, new for a new folder.
std::pair<dev_t, ino_t> identity(const fs::path& path)
{
    struct stat status {};
    EXPECT_EQ(::stat(path.c_str(), &status), 0) << path;
    return {status.st_dev, status.st_ino};
}

TEST(TimeFolderWriter, CommitIntoAnExistingTimeSwapsInAWholeFolderThatHardLinksTheKeptFiles)
{
    // Not the old folder filled file by file (a kill -9 in between would leave a mix), but a
    // new folder holding the staged files and links to the kept ones, swapped in at once.
    TempDir dir("commitExchange");
    writeText(dir.path() / "0.5" / "U", "velocity of a flow solver");
    writeText(dir.path() / "0.5" / "uniform" / "time", "time dictionary");
    writeText(dir.path() / "0.5" / "polyMesh" / "points", "old points");
    writeText(dir.path() / "0.5" / "polyMesh" / "faces", "faces of a topology change");
    const auto oldFolder = identity(dir.path() / "0.5");
    const auto oldU = identity(dir.path() / "0.5" / "U");
    const auto oldFaces = identity(dir.path() / "0.5" / "polyMesh" / "faces");
    {
        io::TimeFolderWriter folder(dir.path(), "0.5");
        writeText(folder.staging() / "polyMesh" / "points.gz", "new points");
        writeText(folder.staging() / "pointDisplacement", "new displacement");
        folder.commit();
    }
    EXPECT_NE(identity(dir.path() / "0.5"), oldFolder) << "the folder was filled in place, not swapped";
    EXPECT_EQ(identity(dir.path() / "0.5" / "U"), oldU) << "U was copied, not linked";
    EXPECT_EQ(identity(dir.path() / "0.5" / "polyMesh" / "faces"), oldFaces);
    EXPECT_EQ(readText(dir.path() / "0.5" / "U"), "velocity of a flow solver");
    EXPECT_EQ(readText(dir.path() / "0.5" / "uniform" / "time"), "time dictionary");
    EXPECT_EQ(readText(dir.path() / "0.5" / "polyMesh" / "points.gz"), "new points");
    EXPECT_EQ(readText(dir.path() / "0.5" / "pointDisplacement"), "new displacement");
    EXPECT_FALSE(fs::exists(dir.path() / "0.5" / "polyMesh" / "points"));
    // The old folder (now under the staging name) is gone too.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
}

TEST(TimeFolderWriter, AWriterThatFailsBeforeCommitLeavesNothingBehind)
{
    TempDir dir("failed");
    try {
        io::TimeFolderWriter folder(dir.path(), "1e-05");
        writeText(folder.staging() / "polyMesh" / "points", "half");
        throw std::runtime_error("disk full");
    } catch (const std::runtime_error&) {
    }
    EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(TimeFolderWriter, RecognisesAndRemovesStaleStagingFolders)
{
    EXPECT_TRUE(io::isTimeFolderStagingName("0.5.tmp-1a2b-3"));
    EXPECT_TRUE(io::isTimeFolderStagingName("1e-05.tmp-ff-0"));
    EXPECT_FALSE(io::isTimeFolderStagingName("0.5"));
    EXPECT_FALSE(io::isTimeFolderStagingName("constant.tmp-12"));
    EXPECT_FALSE(io::isTimeFolderStagingName("0.orig"));
    EXPECT_FALSE(io::isTimeFolderStagingName("0.5.tmp-"));
    EXPECT_FALSE(io::isTimeFolderStagingName("0.5.tmp-xyz"));

    TempDir dir("stale");
    fs::create_directories(dir.path() / "0.1.tmp-ab-0" / "polyMesh");
    fs::create_directories(dir.path() / "0.1");
    fs::create_directories(dir.path() / "notes.tmp-1");
    EXPECT_EQ(io::removeStaleStagingFolders(dir.path()), std::vector<std::string>{"0.1.tmp-ab-0"});
    EXPECT_FALSE(fs::exists(dir.path() / "0.1.tmp-ab-0"));
    EXPECT_TRUE(fs::exists(dir.path() / "0.1"));
    EXPECT_TRUE(fs::exists(dir.path() / "notes.tmp-1"));
}

} // namespace

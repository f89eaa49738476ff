// Every writer of rbm_io names the file and the operating system's reason when it fails,
// and leaves nothing partial (issue 13.4): whole files (WholeFile), plain and gzip files
// (CompressedFile), .vtu and .pvd (VtkWriter), the JSON log (RunLog), time folders
// (TimeFolderWriter), polyMesh folders (PolyMeshWriter). Failures are made with a path
// below a regular file ("Not a directory": works as root, unlike permissions) and with a
// full 1 MB tmpfs ("No space left on device"; skipped with a message where the test cannot
// mount one). VTK's own messages are captured, not printed (VtkMessageCapture).

#include "CompressedFile.hpp"
#include "InputError.hpp"
#include "MeshGenerators.hpp"
#include "MeshTopology.hpp"
#include "PolyMeshWriter.hpp"
#include "RunLog.hpp"
#include "ScratchFiles.hpp"
#include "SmallTmpfs.hpp"
#include "TimeFolderWriter.hpp"
#include "VtkMessageCapture.hpp"
#include "VtkWriter.hpp"
#include "WholeFile.hpp"

#include <gtest/gtest.h>

#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkOutputWindow.h>
#include <vtkPoints.h>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace rbm;
using rbm::test::readText;
using rbm::test::TempDir;
using rbm::test::writeText;

// The message of the exception `write` throws ("" when it throws none).
std::string messageOf(const std::function<void()>& write)
{
    try {
        write();
    } catch (const std::exception& error) {
        return error.what();
    }
    return "";
}

class WriteErrorMessage : public ::testing::Test {
protected:
    WriteErrorMessage()
    {
        writeText(notAFolder_, "a regular file\n");
    }
    TempDir dir_{"writeErrorMessage"};
    const fs::path notAFolder_ = dir_.path() / "file";
    // A path whose parent is a regular file: every create fails with ENOTDIR.
    const fs::path below_ = notAFolder_ / "x";
};

TEST_F(WriteErrorMessage, WholeFilesNameTheFileAndTheReason)
{
    EXPECT_EQ(messageOf([&] { io::writeWholeFile(below_, "text"); }), "cannot create " + below_.string() + ": Not a directory");
    EXPECT_EQ(messageOf([&] { io::replaceFileAtomically(below_, "text"); }),
              "cannot create " + below_.string() + ": Not a directory");
    EXPECT_EQ(messageOf([&] { io::readWholeFile(below_); }),
              below_.string() + ": cannot open file for reading (Not a directory)");
    EXPECT_EQ(messageOf([&] { io::readWholeFile(dir_.path() / "missing"); }),
              (dir_.path() / "missing").string() + ": cannot open file for reading (No such file or directory)");
}

TEST_F(WriteErrorMessage, CompressedAndPlainFilesNameTheFileAndTheReason)
{
    EXPECT_EQ(messageOf([&] { io::writeFileContents(below_, "text", false); }),
              "cannot create " + below_.string() + ": Not a directory");
    // Before: "cannot open file for writing <file>" / "cannot write gzip file <file>", no reason.
    EXPECT_EQ(messageOf([&] { io::writeFileContents(below_, "text", true); }),
              "cannot create " + below_.string() + ".gz: Not a directory");
}

TEST_F(WriteErrorMessage, GzipFilesReadBackAsWritten)
{
    // The gzip stream is now made in memory (deflate) and written with write(): it must read
    // back, empty and large (several deflate blocks) alike.
    std::string large;
    for (int i = 0; i < 200000; ++i) large += std::to_string(i * 7919 % 100003) + (i % 10 == 9 ? "\n" : " ");
    for (const std::string& contents : {std::string(), std::string("(0 0 0)\n"), large}) {
        const fs::path written = io::writeFileContents(dir_.path() / "field", contents, true);
        EXPECT_EQ(written, dir_.path() / "field.gz");
        EXPECT_EQ(io::readFileContents(written), contents);
    }
}

TEST_F(WriteErrorMessage, VtkFilesNameTheFileAndTheReason)
{
    const PolyMesh mesh = makeExtruded2D(2, 2, Vector3{0, 0, 0}, Vector3{1, 1, 0.1});
    const io::VtkCells cells = io::vtkCellsOf(mesh, buildMeshTopology(mesh));
    EXPECT_EQ(messageOf([&] { io::writeVtu(below_, mesh.points, cells, {}, {}); }),
              "cannot create " + below_.string() + ": Not a directory");
    io::PvdCollection pvd(below_);
    pvd.add(0.0, "case_0.vtu");
    EXPECT_EQ(messageOf([&] { pvd.write(); }), "cannot create " + below_.string() + ": Not a directory");
    // A .pvd that exists but cannot be read is an error, not an empty series (which the next
    // write would put in its place).
    io::PvdCollection folderAsPvd(dir_.path());
    EXPECT_NE(messageOf([&] { folderAsPvd.load(); }).find("cannot read file (Is a directory)"), std::string::npos);
}

TEST_F(WriteErrorMessage, LogTimeFolderAndPolyMeshNameTheFileAndTheReason)
{
    EXPECT_EQ(messageOf([&] { io::JsonLinesWriter(below_ / "log.jsonl", true); }),
              "cannot create the folder " + below_.string() + ": Not a directory");
    const std::string timeFolder = messageOf([&] { io::TimeFolderWriter(notAFolder_, "0.5"); });
    EXPECT_EQ(timeFolder.rfind("cannot create the folder " + (notAFolder_ / "0.5.tmp-").string(), 0), 0u) << timeFolder;
    EXPECT_NE(timeFolder.find(": Not a directory"), std::string::npos) << timeFolder;
    const std::string polyMesh = messageOf([&] {
        io::writePolyMesh(below_ / "polyMesh", makeExtruded2D(1, 1, Vector3{0, 0, 0}, Vector3{1, 1, 1}), {});
    });
    EXPECT_NE(polyMesh.find("Not a directory"), std::string::npos) << polyMesh;
    EXPECT_NE(polyMesh.find(below_.string()), std::string::npos) << polyMesh;
}

TEST_F(WriteErrorMessage, FullDiskKeepsTheOldFileAndLeavesNoTemporary)
{
    rbm::test::SmallTmpfs disk(dir_.path() / "disk", "1m");
    if (!disk.mounted()) GTEST_SKIP() << disk.whyNot();
    const fs::path pvdFile = disk.path() / "case.pvd";
    io::PvdCollection pvd(pvdFile);
    pvd.add(0.0, "case_0.vtu");
    pvd.write();
    const std::string before = readText(pvdFile);
    // Fill the disk to the last page.
    std::vector<fs::path> fillers;
    for (std::size_t size = 64 * 1024; size > 0; size /= 2) {
        while (true) {
            const fs::path filler = disk.path() / ("filler" + std::to_string(fillers.size()));
            if (!messageOf([&] { io::writeWholeFile(filler, std::string(size, 'x')); }).empty()) break;
            fillers.push_back(filler);
        }
    }
    ASSERT_FALSE(fillers.empty());
    for (int k = 1; k <= 200; ++k) pvd.add(k, "case_" + std::to_string(k) + ".vtu");
    EXPECT_EQ(messageOf([&] { pvd.write(); }), "cannot write " + pvdFile.string() + ": No space left on device");
    EXPECT_EQ(readText(pvdFile), before);
    EXPECT_FALSE(fs::exists(io::temporaryNameOf(pvdFile)));

    EXPECT_EQ(messageOf([&] { io::writeFileContents(disk.path() / "points", std::string(100000, '1'), true); }),
              "cannot write " + (disk.path() / "points.gz").string() + ": No space left on device");
    EXPECT_FALSE(fs::exists(disk.path() / "points.gz")) << "a partial file was left";

    // The log keeps whole lines only: with one page free, the line that crosses its end is
    // written in part, then cut off.
    fs::remove(fillers.back());
    const fs::path logFile = disk.path() / "log.jsonl";
    std::string message;
    {
        io::JsonLinesWriter log(logFile, true);
        message = messageOf([&] {
            for (int i = 0; i < 10000; ++i) log.append("{\"step\":" + std::to_string(i) + ",\"padding\":\"" + std::string(100, 'p') + "\"}");
        });
    }
    EXPECT_EQ(message, "cannot write " + logFile.string() + ": No space left on device");
    const std::string log = readText(logFile);
    EXPECT_TRUE(log.empty() || log.back() == '\n') << "a partial line";
}

} // namespace

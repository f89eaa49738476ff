// The built rbmMoveMesh when its writes fail (issue 13.4): a disk that fills up partway
// through a run, and a case folder the run may not write or read. Each failure must give
// one rbm message naming the file and the operating system's reason, exit status non-zero,
// and leave nothing partial: no staging folder or temporary file, every time folder whole
// (byte for byte an uninterrupted run's) or absent, the .pvd whole (listing the first times
// of the series) or absent, every .vtu whole, the JSON log in whole lines. VTK prints nothing
// of its own.
//
// The full disk is a tmpfs of 3 MB (SmallTmpfs.hpp; skipped with a message where the test
// cannot mount one). A filler file of a different size in each run moves the failing write
// over the files of a step: points, pointDisplacement, the .vtu, the .pvd, the log.

#include "TestCases.hpp"
#include "MoveMeshProcess.hpp"
#include "ScratchFiles.hpp"
#include "SmallTmpfs.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace rbm::test;

// 6 steps, each written: about 0.45 MB a step (ascii time folder and .vtu) on 3 MB.
constexpr rbm::Label cells = 48;
const std::vector<std::string> times = {"0.1", "0.2", "0.3", "0.4", "0.5", "0.6"};

std::vector<std::string> linesOf(const std::string& text)
{
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

bool contains(const std::string& text, const std::string& part)
{
    return text.find(part) != std::string::npos;
}

// The lines of rbm's messages that are errors (not warnings, not the sentences after one).
std::vector<std::string> errorLines(const std::string& err)
{
    std::vector<std::string> errors;
    for (const std::string& line : linesOf(err)) {
        if (line.rfind("rbmMoveMesh: ", 0) == 0 && !contains(line, "warning")) errors.push_back(line);
    }
    return errors;
}

// A .pvd is whole when it is the reference's (the complete run's) with the DataSets after its
// k-th left out.
bool isPrefixOfSeries(const std::string& pvd, const std::string& referencePvd)
{
    const auto isDataSet = [](const std::string& line) { return contains(line, "<DataSet"); };
    const std::vector<std::string> found = linesOf(pvd);
    const auto k = std::count_if(found.begin(), found.end(), isDataSet);
    std::vector<std::string> expected;
    long dataSets = 0;
    for (const std::string& line : linesOf(referencePvd)) {
        if (isDataSet(line) && ++dataSets > k) continue;
        expected.push_back(line);
    }
    return found == expected && pvd.size() > 0 && pvd.back() == '\n';
}

class WriteFailure : public ::testing::Test {
protected:
    static void SetUpTestSuite()
    {
        reference_ = new Reference;
        writeCompressionCase(reference_->root.path() / "pristine", cells, "0.6", false);
        const fs::path complete = reference_->root.path() / "complete" / "case";   // VTK files are named after it
        fs::create_directories(complete.parent_path());
        fs::copy(reference_->root.path() / "pristine", complete, fs::copy_options::recursive);
        const ProcessRun run = runMoveMesh(complete, reference_->root.path() / "log");
        ASSERT_EQ(run.exitStatus, 0) << run.out << run.err;
        reference_->files = snapshot(complete);
    }
    static void TearDownTestSuite()
    {
        delete reference_;
        reference_ = nullptr;
    }

    struct Reference {
        TempDir root{"writeFailureReference"};
        Snapshot files;   // the case after the complete run
    };
    static Reference* reference_;

    static fs::path pristine() { return reference_->root.path() / "pristine"; }
};

WriteFailure::Reference* WriteFailure::reference_ = nullptr;

TEST_F(WriteFailure, DiskFullPartwayLeavesOneMessageWithTheReasonAndNothingPartial)
{
    ASSERT_NE(reference_, nullptr);
    const Snapshot& reference = reference_->files;
    TempDir dir("diskFull");
    SmallTmpfs disk(dir.path() / "disk", "3m");
    if (!disk.mounted()) GTEST_SKIP() << disk.whyNot();

    std::set<std::string> failedFiles;   // which kind of file each run failed on
    for (int filler = 0; filler < 14; ++filler) {
        const std::size_t fillerBytes = static_cast<std::size_t>(filler) * 36 * 1024;
        SCOPED_TRACE("filler of " + std::to_string(fillerBytes) + " bytes");
        disk.clear();
        const fs::path caseDir = disk.path() / "case";
        fs::copy(pristine(), caseDir, fs::copy_options::recursive);
        writeText(disk.path() / "filler", std::string(fillerBytes, 'x'));
        const ProcessRun run = runMoveMesh(caseDir, dir.path() / "log");

        ASSERT_EQ(run.exitStatus, 1) << "the 3 MB disk should fill up before the end\n" << run.out << run.err;
        // One error, naming a file of the case and the reason; VTK's own dump nowhere.
        const std::vector<std::string> errors = errorLines(run.err);
        ASSERT_EQ(errors.size(), 1u) << run.err;
        EXPECT_TRUE(contains(errors[0], caseDir.string() + "/")) << errors[0];
        EXPECT_TRUE(contains(errors[0], ": No space left on device")) << errors[0];
        for (const char* vtkText : {"ERR|", "vtkExecutive", "ERROR: In", "vtkXMLUnstructuredGridWriter", "Warning: In"}) {
            EXPECT_FALSE(contains(run.err + run.out, vtkText)) << vtkText << " in\n" << run.err;
        }
        for (const char* kind : {"points", "pointDisplacement", ".vtu", ".pvd", "log.jsonl"}) {
            if (contains(errors[0], kind)) failedFiles.insert(kind);
        }

        // Nothing partial: every file is the complete run's, but the .pvd (a shorter series)
        // and the log (fewer lines); no temporary file or staging folder.
        const Snapshot found = snapshot(caseDir);
        for (const auto& [name, bytes] : found) {
            SCOPED_TRACE(name);
            EXPECT_FALSE(contains(name, ".tmp")) << "left over: " << name;
            const auto expected = reference.find(name);
            if (expected == reference.end()) {
                ADD_FAILURE() << "a file the complete run does not write";
            } else if (name == "VTK/case.pvd") {
                EXPECT_TRUE(isPrefixOfSeries(bytes, expected->second)) << "a broken .pvd:\n" << bytes;
            } else if (fs::path(name).filename() == "log.jsonl") {
                // Whole lines of whole objects (the wall times differ from the complete run's).
                EXPECT_TRUE(bytes.empty() || bytes.back() == '\n') << "a partial line in the log";
                const std::vector<std::string> lines = linesOf(bytes);
                EXPECT_LE(lines.size(), linesOf(expected->second).size());
                for (const std::string& line : lines) EXPECT_TRUE(line.front() == '{' && line.back() == '}') << line;
            } else {
                EXPECT_TRUE(bytes == expected->second) << "differs from the complete run's (" << bytes.size()
                                                       << " bytes instead of " << expected->second.size() << ")";
            }
        }
        // Every time folder whole or absent (each of its files was compared above).
        for (const std::string& time : times) {
            if (!found.count(time)) continue;
            for (const auto& [name, bytes] : reference) {
                if (name.rfind(time + "/", 0) == 0) {
                    EXPECT_TRUE(found.count(name)) << "time " << time << " lacks " << name;
                }
            }
        }
        // The .pvd lists only .vtu files that are there.
        if (found.count("VTK/case.pvd")) {
            for (const std::string& time : times) {
                if (contains(found.at("VTK/case.pvd"), "case_" + time + ".vtu")) {
                    EXPECT_TRUE(found.count("VTK/case_" + time + ".vtu")) << "the .pvd lists a missing case_" << time;
                }
            }
        }
    }
    // The sweep moved the failure over the files of a step.
    EXPECT_TRUE(failedFiles.count("points") || failedFiles.count("pointDisplacement")) << failedFiles.size();
    EXPECT_TRUE(failedFiles.count(".vtu"));
    std::string kinds;
    for (const std::string& kind : failedFiles) kinds += " " + kind;
    RecordProperty("failedFiles", kinds);
}

// Tests run as root, for whom file permissions deny nothing: the run is then started as the
// user nobody (65534), for whom the root-owned case (mode 0755, files 0644) is read-only.
int unprivilegedUser()
{
    return ::geteuid() == 0 ? 65534 : -1;
}

TEST_F(WriteFailure, ReadOnlyCaseFolderGivesPermissionDeniedAndChangesNothing)
{
    TempDir dir("permission");
    const fs::path caseDir = dir.path() / "case";
    fs::copy(pristine(), caseDir, fs::copy_options::recursive);
    fs::permissions(caseDir, fs::perms::owner_write, fs::perm_options::remove);   // for a test not run as root
    const Snapshot before = snapshot(caseDir);
    MoveMeshProcessOptions options;
    options.userId = unprivilegedUser();
    const ProcessRun run = runMoveMeshWith(caseDir, dir.path() / "log", options);
    fs::permissions(caseDir, fs::perms::owner_write, fs::perm_options::add);
    if (run.exitStatus == 125) GTEST_SKIP() << "cannot start the program as the user nobody (setuid refused)";

    EXPECT_EQ(run.exitStatus, 1) << run.out << run.err;
    const std::vector<std::string> errors = errorLines(run.err);
    ASSERT_EQ(errors.size(), 1u) << run.err;
    EXPECT_TRUE(contains(errors[0], caseDir.string() + "/")) << errors[0];
    EXPECT_TRUE(contains(errors[0], ": Permission denied")) << errors[0];
    EXPECT_TRUE(snapshot(caseDir) == before) << "the case changed:" << describe(snapshot(caseDir));
}

TEST_F(WriteFailure, UnreadableMeshFileGivesPermissionDeniedAndExitStatus2)
{
    TempDir dir("unreadable");
    const fs::path caseDir = dir.path() / "case";
    fs::copy(pristine(), caseDir, fs::copy_options::recursive);
    const fs::path faces = caseDir / "constant" / "polyMesh" / "faces";
    fs::permissions(faces, fs::perms::owner_read | fs::perms::owner_write);   // 0600: root's alone
    if (::geteuid() != 0) fs::permissions(faces, fs::perms::none);
    const Snapshot before = snapshot(caseDir);
    MoveMeshProcessOptions options;
    options.userId = unprivilegedUser();
    const ProcessRun run = runMoveMeshWith(caseDir, dir.path() / "log", options);
    fs::permissions(faces, fs::perms::owner_read | fs::perms::owner_write);
    if (run.exitStatus == 125) GTEST_SKIP() << "cannot start the program as the user nobody (setuid refused)";

    EXPECT_EQ(run.exitStatus, 2) << run.out << run.err;
    const std::vector<std::string> errors = errorLines(run.err);
    ASSERT_EQ(errors.size(), 1u) << run.err;
    EXPECT_EQ(errors[0], "rbmMoveMesh: " + faces.string() + ": cannot open file for reading (Permission denied)");
    EXPECT_TRUE(snapshot(caseDir) == before) << "the case changed";
}

TEST_F(WriteFailure, TemporaryVtkFilesOfAKilledRunAreRemovedByTheNextRun)
{
    TempDir dir("vtkLeftovers");
    const fs::path caseDir = dir.path() / "case";
    fs::copy(pristine(), caseDir, fs::copy_options::recursive);
    writeText(caseDir / "VTK" / "case_0.3.vtu.tmp", "half a file");
    writeText(caseDir / "VTK" / "case.pvd.tmp", "<?xml");
    writeText(caseDir / "VTK" / "notes.tmp", "not rbm's: stays");
    const ProcessRun run = runMoveMesh(caseDir, dir.path() / "log");
    EXPECT_EQ(run.exitStatus, 0) << run.out << run.err;
    EXPECT_TRUE(contains(run.err, "rbmMoveMesh: removed VTK/case_0.3.vtu.tmp, the unfinished VTK file of an interrupted run\n"))
        << run.err;
    EXPECT_TRUE(contains(run.err, "rbmMoveMesh: removed VTK/case.pvd.tmp, the unfinished VTK file of an interrupted run\n"))
        << run.err;
    EXPECT_FALSE(fs::exists(caseDir / "VTK" / "case_0.3.vtu.tmp"));
    EXPECT_FALSE(fs::exists(caseDir / "VTK" / "case.pvd.tmp"));
    EXPECT_TRUE(fs::exists(caseDir / "VTK" / "notes.tmp"));
    EXPECT_EQ(readText(caseDir / "VTK" / "case_0.3.vtu"), reference_->files.at("VTK/case_0.3.vtu"));
}

} // namespace

// kill -9 of the built rbmMoveMesh (fork/exec) at many moments of a run on a mesh large
// enough that writing a time folder takes a noticeable time (a 2D case of 160 × 160 cells,
// 51 842 points, written as gzip-compressed ascii with 17 digits: 0.3-0.5 s of a 0.6-0.8 s
// step, three write times, 3-4 s a run in the Release build). After every kill the case
// must hold, for every written time, either no folder or the complete folder, byte for byte
// the one of an uninterrupted run (and reading back to the same points), nothing else that
// OpenFOAM would take for a time folder (a name that reads wholly as a number), and
// constant/, system/ and 0/ as they were. Moments:
//  - right before and right after every commit of a time folder (the rename of
//    TimeFolderWriter), exactly, through the LD_PRELOAD shim KillAtRename.cpp;
//  - while a staging folder is being filled (its points.gz or pointDisplacement.gz
//    partly written), then a rerun must clear the leftover and give the uninterrupted result;
//  - at fixed fractions of the uninterrupted run's wall time;
//  - while the folders of an earlier run are being replaced: each must then be the old one
//    or the new one, whole, with the flow solver's file kept.

#include "TestCases.hpp"
#include "MoveMeshProcess.hpp"
#include "ScratchFiles.hpp"
#include "PolyMeshReader.hpp"

#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using rbm::test::controlDict;
using rbm::test::pointDisplacement;
using rbm::test::ProcessRun;
using rbm::test::runMoveMesh;
using rbm::test::TempDir;
using rbm::test::describe;
using rbm::test::readText;
using rbm::test::Snapshot;
using rbm::test::snapshot;
using rbm::test::writeCompressionCase;
using rbm::test::writeText;

namespace fs = std::filesystem;
using namespace rbm;
using Clock = std::chrono::steady_clock;

const std::vector<std::string> writtenTimes = {"0.1", "0.2", "0.3"};




// OpenFOAM's Time::findTimes takes every folder whose whole name reads as a scalar.
bool readsAsTime(const std::string& name)
{
    if (name.empty()) return false;
    char* end = nullptr;
    std::strtod(name.c_str(), &end);
    return end != name.c_str() && *end == '\0';
}

std::set<std::string> timeFolderNames(const fs::path& caseDir)
{
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(caseDir)) {
        const std::string name = entry.path().filename().string();
        if (entry.is_directory() && readsAsTime(name) && name != "0") names.insert(name);
    }
    return names;
}

bool hasStagingFolder(const fs::path& caseDir)
{
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(caseDir, error)) {
        if (entry.path().filename().string().find(".tmp-") != std::string::npos) return true;
    }
    return false;
}

// Size of the largest file named `name` inside a staging folder of the case (0: none yet).
std::uintmax_t stagedFileSize(const fs::path& caseDir, const std::string& name)
{
    std::uintmax_t largest = 0;
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(caseDir, error)) {
        if (entry.path().filename().string().find(".tmp-") == std::string::npos) continue;
        for (const fs::path& file : {entry.path() / "polyMesh" / name, entry.path() / name}) {
            std::error_code sizeError;
            const std::uintmax_t size = fs::file_size(file, sizeError);
            if (!sizeError) largest = std::max(largest, size);
        }
    }
    return largest;
}

void copyCase(const fs::path& from, const fs::path& to)
{
    fs::remove_all(to);
    fs::copy(from, to, fs::copy_options::recursive);
}

// The case, its uninterrupted run and what it wrote.
struct Reference {
    fs::path pristine;                       // the case before any run
    std::map<std::string, Snapshot> times;   // written time folders of the uninterrupted run
    std::map<std::string, std::vector<Vector3>> points;
    Snapshot inputs;                         // constant/, system/, 0/ of the pristine case
    double seconds = 0.0;
    std::vector<std::string> commits;        // the renames of TimeFolderWriter, in order
};

Snapshot inputsOf(const fs::path& caseDir)
{
    Snapshot files;
    for (const char* folder : {"constant", "system", "0"}) {
        for (const auto& [name, bytes] : snapshot(caseDir / folder)) files[std::string(folder) + "/" + name] = bytes;
    }
    return files;
}

Reference makeReference(const fs::path& root)
{
    Reference reference;
    reference.pristine = root / "pristine";
    writeCompressionCase(reference.pristine, 160, "0.3");
    reference.inputs = inputsOf(reference.pristine);
    const fs::path caseDir = root / "uninterrupted";
    copyCase(reference.pristine, caseDir);
    const fs::path renameLog = root / "renames.log";
    const ProcessRun run = runMoveMesh(caseDir, root / "uninterruptedLog",
                                {{"LD_PRELOAD", RBM_KILL_SHIM}, {"RBM_KILL_RENAME_LOG", renameLog.string()}});
    EXPECT_EQ(run.exitStatus, 0) << run.out << run.err;
    reference.seconds = run.seconds;
    EXPECT_EQ(timeFolderNames(caseDir), std::set<std::string>(writtenTimes.begin(), writtenTimes.end()));
    for (const std::string& time : writtenTimes) {
        reference.times[time] = snapshot(caseDir / time);
        reference.points[time] = io::readPolyMeshPoints(caseDir / time);
        EXPECT_TRUE(reference.times[time].count("polyMesh/points.gz")) << describe(reference.times[time]);
        EXPECT_TRUE(reference.times[time].count("pointDisplacement.gz")) << describe(reference.times[time]);
    }
    std::ifstream log(renameLog);
    for (std::string line; std::getline(log, line);) reference.commits.push_back(line);
    return reference;
}

// The checks after a kill. `complete` receives the written times found (each one verified
// whole and identical to the uninterrupted run's).
void expectNoPartialTimeFolder(const fs::path& caseDir, const Reference& reference, std::set<std::string>* complete = nullptr)
{
    EXPECT_EQ(inputsOf(caseDir), reference.inputs) << "constant/, system/ or 0/ changed";
    for (const std::string& name : timeFolderNames(caseDir)) {
        SCOPED_TRACE("time folder " + name);
        const auto expected = reference.times.find(name);
        if (expected == reference.times.end()) {
            ADD_FAILURE() << "a folder OpenFOAM takes for a time, which the uninterrupted run does not write: " << name;
            continue;
        }
        const Snapshot found = snapshot(caseDir / name);
        EXPECT_TRUE(found == expected->second)
            << "incomplete or different time folder: found" << describe(found) << "; expected"
            << describe(expected->second);
        if (found == expected->second) {
            EXPECT_EQ(io::readPolyMeshPoints(caseDir / name), reference.points.at(name));
            if (complete) complete->insert(name);
        }
    }
}

std::set<std::string> firstTimes(std::size_t count)
{
    return std::set<std::string>(writtenTimes.begin(), writtenTimes.begin() + static_cast<std::ptrdiff_t>(count));
}

class KillDuringWrite : public ::testing::Test {
protected:
    static void SetUpTestSuite()
    {
        root_ = new TempDir("reference");
        reference_ = new Reference(makeReference(root_->path()));
    }
    static void TearDownTestSuite()
    {
        delete reference_;
        delete root_;
    }
    static TempDir* root_;
    static Reference* reference_;
};

TempDir* KillDuringWrite::root_ = nullptr;
Reference* KillDuringWrite::reference_ = nullptr;

TEST_F(KillDuringWrite, RightBeforeOrAfterEveryCommitTheCaseHoldsExactlyTheTimesCommittedSoFar)
{
    const Reference& reference = *reference_;
    // One commit (a rename of the staging folder) per written time, and nothing else
    // renamed from a staging folder.
    ASSERT_EQ(reference.commits.size(), writtenTimes.size()) << ::testing::PrintToString(reference.commits);
    for (std::size_t k = 0; k < writtenTimes.size(); ++k) {
        EXPECT_NE(reference.commits[k].find(".tmp-"), std::string::npos);
        EXPECT_NE(reference.commits[k].find("/" + writtenTimes[k]), std::string::npos) << reference.commits[k];
    }
    TempDir dir("commits");
    for (std::size_t k = 1; k <= writtenTimes.size(); ++k) {
        for (const std::string when : {"before", "after"}) {
            SCOPED_TRACE("kill " + when + " commit " + std::to_string(k));
            const fs::path caseDir = dir.path() / "case";
            copyCase(reference.pristine, caseDir);
            const ProcessRun run = runMoveMesh(caseDir, dir.path() / "log",
                                        {{"LD_PRELOAD", RBM_KILL_SHIM},
                                         {"RBM_KILL_AT_RENAME", std::to_string(k)},
                                         {"RBM_KILL_WHEN", when}});
            ASSERT_TRUE(run.killed) << "exit " << run.exitStatus << "\n" << run.out << run.err;
            std::set<std::string> complete;
            expectNoPartialTimeFolder(caseDir, reference, &complete);
            EXPECT_EQ(complete, firstTimes(when == "before" ? k - 1 : k));
            // The staging folder of the interrupted commit is all that is left besides.
            EXPECT_EQ(hasStagingFolder(caseDir), when == "before");
        }
    }
}

TEST_F(KillDuringWrite, WhileAFileIsHalfWrittenNothingShowsAndARerunCompletesTheRun)
{
    const Reference& reference = *reference_;
    TempDir dir("halfWritten");
    // Killed at the second piece written to a staged file (the .gz files go to the disk in
    // 128 KiB pieces): the file holds its first piece only.
    for (const std::string file : {"points.gz", "pointDisplacement.gz"}) {
        SCOPED_TRACE(file);
        const fs::path caseDir = dir.path() / "case";
        copyCase(reference.pristine, caseDir);
        const ProcessRun run =
            runMoveMesh(caseDir, dir.path() / "log", {{"LD_PRELOAD", RBM_KILL_SHIM}, {"RBM_KILL_WRITE_MATCH", "/" + file}});
        ASSERT_TRUE(run.killed) << "the run ended before " << file << " was being written: " << run.out << run.err;
        const std::uintmax_t sizeAtKill = stagedFileSize(caseDir, file);
        EXPECT_GT(sizeAtKill, 0u);
        // It really was mid-write: the staged file is shorter than the finished one.
        EXPECT_LT(sizeAtKill, reference.times.at("0.1").at(file == "points.gz" ? "polyMesh/points.gz" : file).size());
        EXPECT_TRUE(hasStagingFolder(caseDir));
        std::set<std::string> complete;
        expectNoPartialTimeFolder(caseDir, reference, &complete);
        EXPECT_TRUE(complete.empty()) << "killed while writing the first time, yet " << complete.size() << " written";

        // A rerun removes the staging folder and writes what the uninterrupted run wrote.
        const ProcessRun rerun = runMoveMesh(caseDir, dir.path() / "rerunLog");
        EXPECT_EQ(rerun.exitStatus, 0) << rerun.out << rerun.err;
        EXPECT_NE(rerun.err.find("the unfinished time folder of an interrupted run"), std::string::npos) << rerun.err;
        EXPECT_FALSE(hasStagingFolder(caseDir));
        complete.clear();
        expectNoPartialTimeFolder(caseDir, reference, &complete);
        EXPECT_EQ(complete, firstTimes(writtenTimes.size()));
    }
}

TEST_F(KillDuringWrite, AtAnyMomentOfTheRunEveryTimeFolderIsWholeOrAbsent)
{
    const Reference& reference = *reference_;
    TempDir dir("timed");
    int killed = 0;
    int killedWithStagingFolder = 0;
    // The run's length as measured: the reference run's, then the shortest run that finished
    // before its kill (under ctest -j2 the reference may have shared the cores with another
    // test, and the late moments would all fall after a faster run's end).
    double runSeconds = reference.seconds;
    int finishedBeforeTheirKill = 0;
    for (const double fraction : {0.1, 0.3, 0.5, 0.65, 0.8, 0.95}) {
        for (int attempt = 0; attempt < 3; ++attempt) {
            SCOPED_TRACE("kill at " + std::to_string(fraction) + " of " + std::to_string(runSeconds) + " s");
            const fs::path caseDir = dir.path() / "case";
            copyCase(reference.pristine, caseDir);
            bool stagingAtKill = false;
            const double killAt = fraction * runSeconds;
            const ProcessRun run = runMoveMesh(caseDir, dir.path() / "log", {}, [&](double elapsed, pid_t) {
                if (elapsed < killAt) return false;
                stagingAtKill = hasStagingFolder(caseDir);
                return true;
            });
            expectNoPartialTimeFolder(caseDir, reference);
            if (run.killed) {
                ++killed;
                killedWithStagingFolder += stagingAtKill;
                break;
            }
            EXPECT_EQ(run.exitStatus, 0) << run.out << run.err;   // finished before the kill: fine
            ++finishedBeforeTheirKill;
            runSeconds = std::min(runSeconds, run.seconds);         // and aim again at its length
        }
    }
    // Most moments fall inside the run (a moment after a faster run's end is aimed again).
    EXPECT_GE(killed, 4);
    RecordProperty("killed", killed);
    RecordProperty("killedWithStagingFolder", killedWithStagingFolder);
    RecordProperty("finishedBeforeTheirKill", finishedBeforeTheirKill);
}

TEST_F(KillDuringWrite, WhileReplacingAnEarlierRunsFoldersEachIsTheOldOrTheNewOneWhole)
{
    const Reference& reference = *reference_;
    TempDir dir("replacing");
    // An earlier run with another motion, uncompressed; a flow solver then added U to every
    // time folder. The new run writes compressed files over them: points.gz must replace
    // points (no stale twin), U must stay.
    const fs::path earlier = dir.path() / "earlier";
    copyCase(reference.pristine, earlier);
    writeText(earlier / "system" / "controlDict", controlDict(false));
    writeText(earlier / "0" / "pointDisplacement", pointDisplacement("0.1"));
    const ProcessRun earlierRun = runMoveMesh(earlier, dir.path() / "earlierLog");
    ASSERT_EQ(earlierRun.exitStatus, 0) << earlierRun.out << earlierRun.err;
    for (const std::string& time : writtenTimes) writeText(earlier / time / "U", "velocity of time " + time + "\n");
    fs::copy_file(reference.pristine / "system" / "controlDict", earlier / "system" / "controlDict",
                  fs::copy_options::overwrite_existing);
    fs::copy_file(reference.pristine / "0" / "pointDisplacement", earlier / "0" / "pointDisplacement",
                  fs::copy_options::overwrite_existing);
    std::map<std::string, Snapshot> oldTimes;
    std::map<std::string, Snapshot> newTimes;
    for (const std::string& time : writtenTimes) {
        oldTimes[time] = snapshot(earlier / time);
        ASSERT_TRUE(oldTimes[time].count("polyMesh/points")) << describe(oldTimes[time]);
        newTimes[time] = reference.times.at(time);
        newTimes[time]["U"] = "velocity of time " + time + "\n";
        ASSERT_NE(oldTimes[time], newTimes[time]);
    }

    for (std::size_t k = 1; k <= writtenTimes.size(); ++k) {
        for (const std::string when : {"before", "after"}) {
            SCOPED_TRACE("kill " + when + " commit " + std::to_string(k));
            const fs::path caseDir = dir.path() / "case";
            copyCase(earlier, caseDir);
            const ProcessRun run = runMoveMesh(caseDir, dir.path() / "log",
                                        {{"LD_PRELOAD", RBM_KILL_SHIM},
                                         {"RBM_KILL_AT_RENAME", std::to_string(k)},
                                         {"RBM_KILL_WHEN", when}});
            ASSERT_TRUE(run.killed) << "exit " << run.exitStatus << "\n" << run.out << run.err;
            EXPECT_EQ(inputsOf(caseDir), reference.inputs);
            EXPECT_EQ(timeFolderNames(caseDir), std::set<std::string>(writtenTimes.begin(), writtenTimes.end()));
            const std::size_t replaced = when == "before" ? k - 1 : k;
            for (std::size_t t = 0; t < writtenTimes.size(); ++t) {
                const std::string& time = writtenTimes[t];
                const Snapshot found = snapshot(caseDir / time);
                const Snapshot& expected = t < replaced ? newTimes.at(time) : oldTimes.at(time);
                EXPECT_TRUE(found == expected) << "time " << time << " (" << (t < replaced ? "new" : "old")
                                               << " expected): found" << describe(found) << "; expected"
                                               << describe(expected);
            }
        }
    }
}

} // namespace

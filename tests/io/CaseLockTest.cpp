// One rbmMoveMesh per case (io/CaseLock.hpp, issue 13.4): the lock itself, and two runs of
// the built program on one case at once. The first run is held (SIGSTOP) once it holds the
// lock, the second must exit with status 2 and "another rbmMoveMesh (pid N) is moving the
// case" with the first run's pid, and change nothing; the first then finishes as if alone.
// A run killed with SIGKILL leaves no lock behind.

#include "CaseLock.hpp"
#include "TestCases.hpp"
#include "MoveMeshProcess.hpp"
#include "ScratchFiles.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace {

namespace fs = std::filesystem;
using namespace rbm;
using namespace rbm::test;

// The pid /proc/locks gives for the flock on `folder`, 0 when none.
long lockHolder(const fs::path& folder)
{
    struct stat status {};
    if (::stat(folder.c_str(), &status) != 0) return 0;
    return io::flockHolderPid(status.st_dev, status.st_ino);
}

TEST(CaseLock, SecondLockOfTheSameCaseIsRefusedWithTheHoldersPid)
{
    TempDir dir("caseLock");
    {
        io::CaseLock first = io::CaseLock::acquire(dir.path());
        ASSERT_EQ(first.state(), io::CaseLock::State::Held) << first.message();
        EXPECT_EQ(lockHolder(dir.path()), ::getpid());
        // A second open file description conflicts even in the same process.
        const io::CaseLock second = io::CaseLock::acquire(dir.path());
        EXPECT_EQ(second.state(), io::CaseLock::State::HeldByAnother);
        EXPECT_EQ(second.holderPid(), ::getpid());
        EXPECT_EQ(second.message().rfind("another rbmMoveMesh (pid " + std::to_string(::getpid()) +
                                             ") is moving the case " + dir.path().string() + ": ",
                                         0),
                  0u)
            << second.message();
    }
    // Released with the object: the next one gets it.
    EXPECT_EQ(lockHolder(dir.path()), 0);
    EXPECT_EQ(io::CaseLock::acquire(dir.path()).state(), io::CaseLock::State::Held);
    // Nothing written: the lock is on the folder itself.
    EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(CaseLock, MissingFolderIsLeftToTheCaseReader)
{
    TempDir dir("caseLockMissing");
    const io::CaseLock lock = io::CaseLock::acquire(dir.path() / "noSuchCase");
    EXPECT_EQ(lock.state(), io::CaseLock::State::Unavailable);
    EXPECT_EQ(lock.message(), "");
}

// 60 × 60 cells, 3 steps: long enough to hold, short enough to finish.
void writeCase(const fs::path& caseDir)
{
    writeCompressionCase(caseDir, 60, "0.3");
}

TEST(CaseLock, SecondRunOnACaseBeingMovedExitsWithStatus2AndChangesNothing)
{
    TempDir dir("concurrentRuns");
    const fs::path caseDir = dir.path() / "case";
    writeCase(caseDir);
    bool checked = false;
    const ProcessRun first = runMoveMesh(caseDir, dir.path() / "firstLog", {}, [&](double, pid_t pid) {
        if (checked || lockHolder(caseDir) != pid) return false;
        // The first run holds the case: stop it there, start the second.
        ::kill(pid, SIGSTOP);
        const Snapshot before = snapshot(caseDir);
        const ProcessRun second = runMoveMesh(caseDir, dir.path() / "secondLog");
        EXPECT_EQ(second.exitStatus, 2) << second.out << second.err;
        EXPECT_EQ(second.err.rfind("rbmMoveMesh: another rbmMoveMesh (pid " + std::to_string(pid) +
                                       ") is moving the case " + caseDir.string() + ": ",
                                   0),
                  0u)
            << second.err;
        EXPECT_NE(second.err.find("\nNothing was written.\n"), std::string::npos) << second.err;
        EXPECT_EQ(second.out, "");
        EXPECT_TRUE(snapshot(caseDir) == before) << "the refused run changed the case";
        ::kill(pid, SIGCONT);
        checked = true;
        return false;
    });
    ASSERT_TRUE(checked) << "the first run ended before it was seen holding the lock\n" << first.out << first.err;
    EXPECT_EQ(first.exitStatus, 0) << first.out << first.err;
    for (const char* time : {"0.1", "0.2", "0.3"}) EXPECT_TRUE(fs::exists(caseDir / time / "polyMesh" / "points.gz"));
}

TEST(CaseLock, RunKilledWithSigkillLeavesNoLock)
{
    TempDir dir("killedRun");
    const fs::path caseDir = dir.path() / "case";
    writeCase(caseDir);
    const ProcessRun killed =
        runMoveMesh(caseDir, dir.path() / "killedLog", {}, [&](double, pid_t pid) { return lockHolder(caseDir) == pid; });
    ASSERT_TRUE(killed.killed) << killed.out << killed.err;
    EXPECT_EQ(lockHolder(caseDir), 0);
    const ProcessRun next = runMoveMesh(caseDir, dir.path() / "nextLog");
    EXPECT_EQ(next.exitStatus, 0) << next.out << next.err;
    EXPECT_EQ(next.err.find("another rbmMoveMesh"), std::string::npos) << next.err;
}

} // namespace

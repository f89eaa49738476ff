// Tests of LoadAdaptiveThreads: other processes' load takes rbm's threads down to the cores
// left; OMP_NUM_THREADS or a single-thread policy switch the adaptation off.
#include "LoadAdaptiveThreads.hpp"
#include "SavedThreadSettings.hpp"
#include "ThreadCount.hpp"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace rbm;
using rbm::test::SavedThreadSettings;

TEST(LoadAdaptiveThreads, OtherProcessesBusyOnEveryCoreLeaveOneThread)
{
    const SavedThreadSettings saved;
    unsetenv("OMP_NUM_THREADS");
    const int cores = static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN));
    LoadAdaptiveThreads threads(cores + 1);
    ASSERT_TRUE(threads.active()) << "no /proc/stat?";
    // One busy process per core, for the measured interval.
    std::vector<pid_t> children;
    for (int k = 0; k < cores; ++k) {
        const pid_t child = fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
            volatile double x = 0.0;
            while (std::chrono::steady_clock::now() < end) x = x + 1.0;
            _exit(0);
        }
        children.push_back(child);
    }
    threads.update();   // starts the interval with the children running
    std::this_thread::sleep_for(std::chrono::milliseconds(400));
    const int count = threads.update();
    for (pid_t child : children) {
        kill(child, SIGKILL);
        waitpid(child, nullptr, 0);
    }
    EXPECT_GE(threads.otherLoad(), 0.5 * cores) << "the children kept every core busy";
    EXPECT_LE(count, (cores + 1) / 2) << "other load " << threads.otherLoad();
    EXPECT_EQ(threadCount(), count);
}

TEST(LoadAdaptiveThreads, OmpNumThreadsOrOneThreadSwitchTheAdaptationOff)
{
    const SavedThreadSettings saved;
    setenv("OMP_NUM_THREADS", "2", 1);
    EXPECT_FALSE(LoadAdaptiveThreads(2).active());
    unsetenv("OMP_NUM_THREADS");
    LoadAdaptiveThreads one(1);
    EXPECT_FALSE(one.active());
    EXPECT_EQ(one.update(), 1);
}

} // namespace

// Tests of the thread count (src/ThreadCount): OMP_NUM_THREADS and rbm's own setting.

#include "CoupledNewtonSolver.hpp"
#include "DecoupledSolver.hpp"
#include "LocalGlobalSolver.hpp"
#include "MeshGenerators.hpp"
#include "MeshTopology.hpp"
#include "PetscTestEnvironment.hpp"
#include "PolyMeshReader.hpp"
#include "PseudoTwoDExtraction.hpp"
#include "QualityReport.hpp"
#include "RbmEnergy.hpp"
#include "RbmProblem.hpp"
#include "TestCases.hpp"
#include "ReducedNewtonSolver.hpp"
#include "SavedThreadSettings.hpp"
#include "ThreadCount.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace rbm::test::threadCases;

using namespace rbm;
using namespace rbm::motion;

namespace {

// Threads OpenMP starts in a region that asks for 4 with a num_threads clause, as CHOLMOD's
// factorisation does (1 without OpenMP).
int threadsAskingForFour()
{
    int seen = 1;
#ifdef _OPENMP
#pragma omp parallel num_threads(4)
    {
#pragma omp single
        seen = omp_get_num_threads();
    }
#endif
    return seen;
}

} // namespace

TEST(ThreadCount, PolicyIsOmpNumThreadsElseTheCoresElseOnePerRank)
{
#ifndef _OPENMP
    GTEST_SKIP() << "built without OpenMP";
#else
    const test::SavedThreadSettings saved;
    const int adaptsBefore = omp_get_dynamic();
    const char* savedDynamic = std::getenv("OMP_DYNAMIC");
    const std::string savedDynamicValue = savedDynamic ? savedDynamic : "";
    // No load adaptation unless asked for (OMP_DYNAMIC): OpenMP's own default.
    if (!savedDynamic) {
        EXPECT_FALSE(adaptsBefore);
    }
    unsetenv("OMP_DYNAMIC");
    unsetenv("OMP_NUM_THREADS");
    EXPECT_EQ(policyThreadCount(1), omp_get_num_procs());
    EXPECT_EQ(policyThreadCount(4), 1);   // several MPI ranks: one thread each
    EXPECT_EQ(applyThreadCountPolicy(1), omp_get_num_procs());
    EXPECT_EQ(threadCount(), omp_get_num_procs());
    EXPECT_FALSE(omp_get_dynamic());   // every core, whatever the load
    EXPECT_EQ(applyThreadCountPolicy(4), 1);
    EXPECT_EQ(threadCount(), 1);
    setenv("OMP_NUM_THREADS", "3", 1);
    setThreadCount(3);   // what OpenMP would have read from OMP_NUM_THREADS=3 at start-up
    EXPECT_EQ(policyThreadCount(1), 3);
    EXPECT_EQ(policyThreadCount(4), 3);   // set explicitly: used even with several ranks
    EXPECT_EQ(applyThreadCountPolicy(4), 3);
    EXPECT_FALSE(omp_get_dynamic());   // exactly what was asked for
    EXPECT_EQ(threadsInAParallelRegion(), 3);
    EXPECT_NE(describeThreadCount().find("OMP_NUM_THREADS"), std::string::npos);
    if (savedDynamic) setenv("OMP_DYNAMIC", savedDynamicValue.c_str(), 1);
    omp_set_dynamic(adaptsBefore);
#endif
}

// Inside OpenFOAM (the plugin): one core per process, OpenFOAM's convention, unless
// OMP_NUM_THREADS asks for more; a machine with several cores changes nothing.
TEST(ThreadCount, InsideAHostOneThreadUnlessOmpNumThreadsSaysOtherwise)
{
#ifndef _OPENMP
    GTEST_SKIP() << "built without OpenMP";
#else
    const test::SavedThreadSettings saved;
    unsetenv("OMP_NUM_THREADS");
    setThreadCount(omp_get_num_procs() + 1);   // as if OpenMP had chosen every core and more
    EXPECT_EQ(applyHostThreadCountPolicy(), 1);
    EXPECT_EQ(threadCount(), 1);
    EXPECT_EQ(threadsInAParallelRegion(), 1);
    setenv("OMP_NUM_THREADS", "3", 1);
    setThreadCount(3);   // what OpenMP would have read from OMP_NUM_THREADS=3 at start-up
    EXPECT_EQ(applyHostThreadCountPolicy(), 3);
    EXPECT_EQ(threadsInAParallelRegion(), 3);
#endif
}

// CHOLMOD's numeric factorisation asks for num_threads(4) whatever OMP_NUM_THREADS says:
// with one thread, such a region must run on one thread too (src/ThreadCount.cpp).
TEST(ThreadCount, OneThreadHoldsForRegionsThatAskForMore)
{
#ifndef _OPENMP
    GTEST_SKIP() << "built without OpenMP";
#else
    const int before = threadCount();
    const int adaptsBefore = omp_get_dynamic();
    setThreadCount(1);
    EXPECT_EQ(threadsInAParallelRegion(), 1);
    EXPECT_EQ(threadsAskingForFour(), 1);
    setThreadCount(2);
    EXPECT_EQ(threadsInAParallelRegion(), 2);
    EXPECT_EQ(threadsAskingForFour(), 4);   // more than one: the libraries' own counts again
    setThreadCount(1);
    EXPECT_EQ(applyThreadCountPolicy(4), 1);   // one per MPI rank
    EXPECT_EQ(threadsAskingForFour(), 1);
    setThreadCount(before);
    omp_set_dynamic(adaptsBefore);
    EXPECT_EQ(threadsInAParallelRegion(), before);
#endif
}

// A library region asking for a team larger than rbm's thread count runs on one thread inside
// LibraryTeamsWithinThreadCount (CHOLMOD's factorisation), and gets its team again outside.
TEST(ThreadCount, LibraryTeamsLargerThanTheThreadCountRunOnOneThreadInsideTheGuard)
{
#ifndef _OPENMP
    GTEST_SKIP() << "built without OpenMP";
#else
    const int before = threadCount();
    for (const int threads : {1, 2, 3}) {
        setThreadCount(threads);
        {
            const LibraryTeamsWithinThreadCount withinThreadCount(4);
            EXPECT_EQ(threadsAskingForFour(), 1) << threads << " thread(s)";
        }
        EXPECT_EQ(threadsAskingForFour(), threads == 1 ? 1 : 4) << "after the guard, " << threads << " thread(s)";
        EXPECT_EQ(threadsInAParallelRegion(), threads);
    }
    setThreadCount(4);
    {
        const LibraryTeamsWithinThreadCount withinThreadCount(4);
        EXPECT_EQ(threadsAskingForFour(), 4);   // within the count: the library's own team
    }
    setThreadCount(before);
#endif
}

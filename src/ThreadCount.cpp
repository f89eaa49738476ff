#include "ThreadCount.hpp"

#include <algorithm>
#include <cstdlib>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace rbm {

namespace {

bool isSet(const char* variable)
{
    const char* value = std::getenv(variable);
    return value != nullptr && *value != '\0';
}

#ifdef _OPENMP
// One thread means one thread in the libraries too. Debian's CHOLMOD (SuiteSparse 5.12) asks
// for num_threads(CHOLMOD_OMP_NUM_THREADS), compiled as 4, in every large supernode of its
// numeric factorisation, whatever OMP_NUM_THREADS says: a run told to use one thread would
// still start extra threads and pay for their context switches, for work a team does not
// speed up (docs/rbmMoveMesh.md, "Threads"). OpenMP's max-active-levels of 0 makes every
// parallel region, num_threads clause or not, run on the thread that meets it (OpenMP 5.0;
// GCC's libgomp honours it).
// With more than one thread the level is OpenMP's own default again.
void limitParallelRegions(int threads)
{
    static const int defaultActiveLevels = omp_get_max_active_levels();
    omp_set_max_active_levels(threads == 1 ? 0 : defaultActiveLevels);
}
#endif

} // namespace

bool worthThreading(std::size_t work) { return work >= minimumThreadedWork; }

int policyThreadCount(int mpiRanks)
{
#ifdef _OPENMP
    // OpenMP has read OMP_NUM_THREADS at start-up (and ignored it if malformed); without it,
    // omp_get_num_procs() is the number of cores in this process' affinity mask, which under
    // mpirun's default binding is already the rank's own core(s).
    if (isSet("OMP_NUM_THREADS")) return std::max(1, omp_get_max_threads());
    if (mpiRanks > 1) return 1;
    return std::max(1, omp_get_num_procs());
#else
    (void)mpiRanks;
    return 1;
#endif
}

int applyThreadCountPolicy(int mpiRanks)
{
    const int threads = policyThreadCount(mpiRanks);
#ifdef _OPENMP
    omp_set_num_threads(threads);
    limitParallelRegions(threads);
#endif
    return threads;
}

int applyHostThreadCountPolicy()
{
#ifdef _OPENMP
    const int threads = isSet("OMP_NUM_THREADS") ? std::max(1, omp_get_max_threads()) : 1;
    setThreadCount(threads);
    return threads;
#else
    return 1;
#endif
}

void setThreadCount(int threads)
{
#ifdef _OPENMP
    omp_set_dynamic(0);
    omp_set_num_threads(std::max(1, threads));
    limitParallelRegions(std::max(1, threads));
#else
    (void)threads;
#endif
}

int threadCount()
{
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

LibraryTeamsWithinThreadCount::LibraryTeamsWithinThreadCount(int teamSize)
{
#ifdef _OPENMP
    if (threadCount() >= teamSize || omp_in_parallel()) return;
    activeLevelsBefore_ = omp_get_max_active_levels();
    omp_set_max_active_levels(0);
#else
    (void)teamSize;
#endif
}

LibraryTeamsWithinThreadCount::~LibraryTeamsWithinThreadCount()
{
#ifdef _OPENMP
    if (activeLevelsBefore_ >= 0) omp_set_max_active_levels(activeLevelsBefore_);
#endif
}

int threadsAvailable()
{
    int threads = 1;
#ifdef _OPENMP
    if (threadCount() == 1) return 1;
#pragma omp parallel
    {
#pragma omp single
        threads = omp_get_num_threads();
    }
#endif
    return threads;
}

std::string describeThreadCount()
{
#ifdef _OPENMP
    const std::string count = std::to_string(threadCount());
    const std::string source = isSet("OMP_NUM_THREADS") ? "OMP_NUM_THREADS" : "OMP_NUM_THREADS unset";
    if (omp_get_dynamic() && threadCount() > 1)
        return "up to " + count + " (OpenMP, " + source + ", OMP_DYNAMIC: fewer when the machine is loaded; results do not depend on it)";
    return count + " (OpenMP, " + source + "; results do not depend on it)";
#else
    return "1 (built without OpenMP)";
#endif
}

} // namespace rbm

#pragma once
// How many threads rbm's own loops use (OpenMP): the cell-neighbour graph, the energy's
// gradient and Hessian blocks, the local rotation fits, the decoupled assembly and the
// stiffening factors. PETSc, MUMPS and hypre are not affected (OpenBLAS, under MUMPS, has
// its own OPENBLAS_NUM_THREADS). Every threaded loop gives bitwise the same result for any
// thread count: each thread writes only its own slots and every sum is formed in a fixed
// order (docs/rbmMoveMesh.md, "Threads"; tests/system/ThreadDeterminismTest.cpp).
//
// The policy, in one place:
//   OMP_NUM_THREADS set       → exactly that many (OpenMP's own reading of it);
//   otherwise, one MPI rank   → the number of cores this process may run on (its affinity
//                               mask: under a batch system, the cores it was given);
//   otherwise (several ranks) → 1 per rank, so that N ranks on N cores do not oversubscribe.
// On a machine shared with other jobs, threads that wait for a core at every barrier cost
// more than they save: rbmMoveMesh applies the policy with its MPI rank count and then, step by
// step, leaves the cores other processes keep busy to them (LoadAdaptiveThreads.hpp).
// Inside a host program (the OpenFOAM plugin) rbm follows the host's convention instead: one
// core per process, unless OMP_NUM_THREADS says otherwise (applyHostThreadCountPolicy): a
// flow solver's ranks already fill the cores, and threads that wait for a busy core at every
// barrier make a motion step several times slower. Other programs get OpenMP's default
// (OMP_NUM_THREADS, else every core). Without OpenMP (a compiler without it) everything runs
// on 1 thread.

#include <cstddef>
#include <string>

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace rbm {

// Loops with less work than this (edges, faces or cells visited) run on one thread: a
// parallel region costs microseconds on an idle machine but up to a scheduler time slice
// (milliseconds) on a busy one, which would make the many small evaluations of a small
// problem slower. Use as `#pragma omp parallel for schedule(static) if (worthThreading(work))`.
// (Defined out of line: every threaded file then links ThreadCount.cpp and its start-up default.)
constexpr std::size_t minimumThreadedWork = 20000;
bool worthThreading(std::size_t work);

// The thread count the policy above gives for a process that is one of mpiRanks ranks
// (the most it uses when it adapts to the load).
int policyThreadCount(int mpiRanks);

// Applies the policy for mpiRanks ranks; returns policyThreadCount(mpiRanks). A count of 1
// holds for the libraries' OpenMP regions too, even those with a num_threads clause
// (CHOLMOD's factorisation asks for 4): OpenMP's max-active-levels is then 0.
int applyThreadCountPolicy(int mpiRanks);

// Inside a host program (OpenFOAM): OMP_NUM_THREADS when set, otherwise 1. Returns the count.
int applyHostThreadCountPolicy();

// Exactly this many threads (≥ 1) for the following threaded loops, whatever the load
// (ignored without OpenMP); 1 holds for the libraries' regions too, as above.
void setThreadCount(int threads);

// The most threads the next threaded loop will use (1 without OpenMP).
int threadCount();

// Within its scope, a library's OpenMP region that asks for a team of teamSize threads (a
// num_threads clause, which overrides OMP_NUM_THREADS) runs on the calling thread whenever
// rbm may use fewer than teamSize threads: the library then stays within rbm's thread count
// instead of oversubscribing the cores. For CHOLMOD's factorisation (teamSize 4,
// SparseCholesky.cpp), whose regions only copy and clear supernodes, a team per large
// supernode on fewer cores than the team costs more in start-up and waiting than it saves,
// at one thread and at two (docs/rbmMoveMesh.md, "Threads"; rbmBenchmark's quad2D case
// times K's set-up).
// Restores OpenMP's max-active-levels on leaving. Nothing without OpenMP.
class LibraryTeamsWithinThreadCount {
public:
    explicit LibraryTeamsWithinThreadCount(int teamSize);
    ~LibraryTeamsWithinThreadCount();
    LibraryTeamsWithinThreadCount(const LibraryTeamsWithinThreadCount&) = delete;
    LibraryTeamsWithinThreadCount& operator=(const LibraryTeamsWithinThreadCount&) = delete;

private:
    int activeLevelsBefore_ = -1;   // -1: left as it was
};

// The threads the next threaded loop will really get: threadCount(), or fewer when OpenMP
// adapts to the load (asks OpenMP with an empty parallel region, a few microseconds). For
// loops whose threaded form costs more arithmetic than their serial one.
int threadsAvailable();

// Calls pass(begin, end) on [0, count) split into contiguous ranges, one per thread (one call
// on the whole range when threads is false). For kernels that must see their rows in order
// (the AVX2 variants of ReducedHessian3D and ThreeVectorMultigrid); every item's result is its
// own, so the result is the same for any thread count.
template <typename Pass>
void forEachThreadRange(int count, bool threads, Pass pass)
{
#pragma omp parallel if (threads)
    {
        int begin = 0, end = count;
#if defined(_OPENMP)
        const int teamSize = omp_get_num_threads(), thread = omp_get_thread_num();
        begin = static_cast<int>(static_cast<long long>(count) * thread / teamSize);
        end = static_cast<int>(static_cast<long long>(count) * (thread + 1) / teamSize);
#endif
        pass(begin, end);
    }
}

// For the start-up log, e.g. "up to 2 (OpenMP, fewer when the machine is loaded; ...)".
std::string describeThreadCount();

} // namespace rbm

#pragma once
// A program run under mpirun, measured rank by rank.
//
// Each rank's peak resident memory is measured the way the serial runs measure theirs: by the
// process that waits for it. mpirun starts `rbmBenchmark --run-one rankUsage FILE PROGRAM ...`
// on every rank; that wrapper forks and execs the program (which inherits Open MPI's
// environment and so joins the job as the rank), waits for it with wait4 and writes the
// kernel's account of it to FILE.<rank>: ru_maxrss (the high-water mark of the resident set,
// VmHWM at exit), user and system time. Unlike polling /proc/<pid>/status of mpirun's
// children, nothing is sampled, so a peak just before exit is not missed, and it does not
// depend on how mpirun parents its processes. The wrapper itself idles in wait4 and is not
// counted.

#include "Record.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace rbm::benchmark {

namespace fs = std::filesystem;

// The wrapper: args = {FILE, PROGRAM, ARGS...}; the rank is OMPI_COMM_WORLD_RANK (or PMIX_RANK).
// Returns the program's exit status.
int runRankUsage(const std::vector<std::string>& args);

struct MpiRunResult {
    int exitCode = -1;
    double wallSeconds = 0.0;        // mpirun, start to end
    std::vector<Record> ranks;       // per rank: peakMemoryMiB, cpuSeconds, exitCode
    double maxRankPeakMiB() const;
    double sumRankPeakMiB() const;
    double cpuSeconds() const;       // summed over the ranks
};

// mpirun -np `ranks` (--oversubscribe; --allow-run-as-root as root) of argv through the wrapper,
// standard output to `stdoutFile`, standard error to `stderrFile`; the environment given (or
// the parent's). The per-rank files are written beside stdoutFile.
MpiRunResult runMpi(int ranks, const std::vector<std::string>& argv, const fs::path& stdoutFile,
                    const fs::path& stderrFile, const std::vector<std::string>* environment = nullptr);

// The record's fields of a decomposed run, keys prefixed by `prefix`: wallSeconds, cpuSeconds,
// rankPeakMaxMiB, rankPeakSumMiB, rankPeaksMiB (the list), exitCode.
void addMpiRun(Record& record, const std::string& prefix, const MpiRunResult& run);

} // namespace rbm::benchmark

#include "MpiRun.hpp"

#include "CaseFiles.hpp"
#include "Format.hpp"
#include "Process.hpp"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>

namespace rbm::benchmark {

namespace {

std::string rankText()
{
    for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
        if (const char* value = std::getenv(name)) return value;
    return "0";
}

} // namespace

int runRankUsage(const std::vector<std::string>& args)
{
    if (args.size() < 2) return 2;
    std::vector<char*> argv;
    for (std::size_t k = 1; k < args.size(); ++k) argv.push_back(const_cast<char*>(args[k].c_str()));
    argv.push_back(nullptr);
    const auto started = Clock::now();
    const pid_t pid = fork();
    if (pid < 0) return 2;
    if (pid == 0) {
        execv(argv[0], argv.data());
        _exit(127);
    }
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    const int exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    Record record;
    record.set("rank", std::stod(rankText()));
    record.set("wallSeconds", secondsSince(started));
    record.set("peakMemoryMiB", static_cast<double>(usage.ru_maxrss) / 1024.0);
    record.set("cpuSeconds", static_cast<double>(usage.ru_utime.tv_sec) + 1e-6 * static_cast<double>(usage.ru_utime.tv_usec) +
                                 static_cast<double>(usage.ru_stime.tv_sec) + 1e-6 * static_cast<double>(usage.ru_stime.tv_usec));
    record.set("exitCode", exitCode);
    writeText(args[0] + "." + rankText(), record.toLines());
    return exitCode;
}

double MpiRunResult::maxRankPeakMiB() const
{
    double peak = ranks.empty() ? nan : 0.0;
    for (const Record& rank : ranks) peak = std::max(peak, rank.number("peakMemoryMiB"));
    return peak;
}

double MpiRunResult::sumRankPeakMiB() const
{
    double sum = ranks.empty() ? nan : 0.0;
    for (const Record& rank : ranks) sum += rank.number("peakMemoryMiB");
    return sum;
}

double MpiRunResult::cpuSeconds() const
{
    double sum = ranks.empty() ? nan : 0.0;
    for (const Record& rank : ranks) sum += rank.number("cpuSeconds");
    return sum;
}

MpiRunResult runMpi(int ranks, const std::vector<std::string>& argv, const fs::path& stdoutFile,
                    const fs::path& stderrFile, const std::vector<std::string>* environment)
{
    const fs::path usageFile = stdoutFile.string() + ".rankUsage";
    for (int rank = 0; rank < ranks; ++rank) fs::remove(usageFile.string() + "." + std::to_string(rank));
    std::vector<std::string> command{"/usr/bin/mpirun"};
    if (geteuid() == 0) command.push_back("--allow-run-as-root");
    command.insert(command.end(), {"--oversubscribe", "-np", std::to_string(ranks), selfExecutable().string(),
                                   "--run-one", "rankUsage", usageFile.string()});
    command.insert(command.end(), argv.begin(), argv.end());
    const ProcessResult process = runProcess(command, stderrFile, environment, stdoutFile);
    MpiRunResult result;
    result.exitCode = process.exitCode;
    result.wallSeconds = process.wallSeconds;
    for (int rank = 0; rank < ranks; ++rank) {
        std::ifstream in(usageFile.string() + "." + std::to_string(rank));
        if (!in) {
            result.ranks.clear();
            break;
        }
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        result.ranks.push_back(Record::fromLines(text));
    }
    return result;
}

void addMpiRun(Record& record, const std::string& prefix, const MpiRunResult& run)
{
    std::string peaks;
    for (const Record& rank : run.ranks) peaks += (peaks.empty() ? "" : ", ") + count(rank.number("peakMemoryMiB"));
    record.set(prefix + "WallSeconds", run.wallSeconds);
    record.set(prefix + "CpuSeconds", run.cpuSeconds());
    record.set(prefix + "RankPeakMaxMiB", run.maxRankPeakMiB());
    record.set(prefix + "RankPeakSumMiB", run.sumRankPeakMiB());
    record.set(prefix + "RankPeaksMiB", peaks);
    record.set(prefix + "ExitCode", run.exitCode);
}

} // namespace rbm::benchmark

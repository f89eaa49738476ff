#include "ChildTask.hpp"

#include "DecomposedCheckTask.hpp"
#include "MeshIoTask.hpp"
#include "MpiRun.hpp"
#include "PitchingTask.hpp"
#include "Process.hpp"
#include "VariantTask.hpp"

#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <iostream>
#include <optional>

namespace rbm::benchmark {

int runOne(const std::vector<std::string>& args)
{
    // One rank's wrapper under mpirun (MpiRun.hpp): it only waits for the program.
    if (!args.empty() && args[0] == "rankUsage") return runRankUsage(std::vector<std::string>(args.begin() + 1, args.end()));
    // The parent's --run-timeout: SIGALRM ends a run that takes longer.
    if (const char* timeout = std::getenv("RBM_BENCHMARK_RUN_TIMEOUT"))
        if (std::atoi(timeout) > 0) alarm(static_cast<unsigned>(std::atoi(timeout)));
    try {
        Record record;
        if (args.size() >= 5 && args[0] == "meshio") {
            record = runMeshIoTask(args[1], std::stod(args[2]), args[3], args[4]);
        } else if (args.size() >= 5 && args[0] == "variant") {
            record = runVariantTask(args[1], args[2], args[3], std::stod(args[4]));
        } else if (args.size() >= 5 && args[0] == "pitching") {
            record = runPitchingTask(args[1], std::stoi(args[2]), args[3], args[4]);
        } else if (args.size() >= 6 && args[0] == "decomposedCheck") {
            record = runDecomposedCheckTask(args[1], args[2], std::stoi(args[3]), args[4], args[5]);
        } else {
            std::cerr << "rbmBenchmark --run-one: unknown task\n";
            return 2;
        }
        std::cout << "RBM_BENCHMARK_RECORD_BEGIN\n" << record.toLines() << "RBM_BENCHMARK_RECORD_END\n";
        return 0;
    } catch (const std::exception& error) {
        std::cerr << "rbmBenchmark --run-one " << (args.empty() ? "" : args[0]) << ": " << error.what() << '\n';
        return 1;
    }
}

Record runChild(const std::vector<std::string>& taskArgs, const fs::path& logDir, const std::string& logName,
                const Record& identity)
{
    std::vector<std::string> argv{selfExecutable().string(), "--run-one"};
    argv.insert(argv.end(), taskArgs.begin(), taskArgs.end());
    const fs::path stderrFile = logDir / (logName + ".stderr");
    const ProcessResult result = runProcess(argv, stderrFile);
    std::optional<Record> record = recordFromOutput(result.output);
    Record out = identity;
    if (result.exitCode != 0 || !record) {
        out.setFlag("failed", true);
        out.set("exitCode", result.exitCode);
        out.set("error", result.exitCode == 128 + SIGALRM
                             ? "timed out after " + std::string(std::getenv("RBM_BENCHMARK_RUN_TIMEOUT")) + " s"
                             : readTail(stderrFile, 300));
        out.set("peakMemoryMiB", result.maxRssMiB);
        return out;
    }
    out.merge(*record);
    out.set("processWallSeconds", result.wallSeconds);
    out.set("processMaxRssMiB", result.maxRssMiB);
    return out;
}

} // namespace rbm::benchmark

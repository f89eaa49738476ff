#pragma once
// Runs the built rbmMoveMesh (RBM_MOVE_MESH) as a separate process (fork + execve), for the
// tests that need a real process: kill -9 at chosen moments (KillDuringWriteTest), two runs
// at once (CaseLockTest), a full disk or a folder the run may not write (WriteFailureTest).

#include "ScratchFiles.hpp"

#include <gtest/gtest.h>
#include <fcntl.h>
#include <grp.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <thread>
#include <utility>
#include <vector>

extern char** environ;

namespace rbm::test {

struct ProcessRun {
    bool killed = false;     // by our SIGKILL (or the shim's)
    int exitStatus = -1;     // when it exited by itself
    double seconds = 0.0;
    std::string out;
    std::string err;
};

struct MoveMeshProcessOptions {
    std::vector<std::pair<std::string, std::string>> environment;   // added to the test's own
    std::vector<std::string> arguments;                             // after -case DIR
    // Polled every 0.2 ms with the seconds since the start and the process id; the first
    // time it returns true the process gets SIGKILL.
    std::function<bool(double, pid_t)> killWhen;
    // Run as this user and group instead of the test's (a test running as root, for which
    // file permissions deny nothing); -1: the test's.
    int userId = -1;
};

// Runs rbmMoveMesh -case `caseDir` with its standard output and error in `logDir`.
inline ProcessRun runMoveMeshWith(const std::filesystem::path& caseDir, const std::filesystem::path& logDir,
                                  const MoveMeshProcessOptions& options)
{
    using Clock = std::chrono::steady_clock;
    std::filesystem::create_directories(logDir);
    // The environment is built before fork: the child only calls async-signal-safe functions.
    std::map<std::string, std::string> variables;
    for (char** variable = environ; *variable; ++variable) {
        const std::string text = *variable;
        const std::size_t equals = text.find('=');
        if (equals != std::string::npos) variables[text.substr(0, equals)] = text.substr(equals + 1);
    }
    variables["OPENBLAS_NUM_THREADS"] = "1";
    variables["OMP_NUM_THREADS"] = "1";
    for (const auto& [name, value] : options.environment) variables[name] = value;
    if (variables.count("LD_PRELOAD")) {
        // In the sanitizer build the shim comes before the ASan runtime; tell ASan that is fine.
        std::string& asan = variables["ASAN_OPTIONS"];
        asan += (asan.empty() ? "" : ":") + std::string("verify_asan_link_order=0");
    }
    std::vector<std::string> storage;
    for (const auto& [name, value] : variables) storage.push_back(name + "=" + value);
    std::vector<char*> environment;
    for (std::string& entry : storage) environment.push_back(entry.data());
    environment.push_back(nullptr);
    std::vector<std::string> argumentStorage = {RBM_MOVE_MESH, "-case", caseDir.string()};
    argumentStorage.insert(argumentStorage.end(), options.arguments.begin(), options.arguments.end());
    std::vector<char*> arguments;
    for (std::string& argument : argumentStorage) arguments.push_back(argument.data());
    arguments.push_back(nullptr);
    const std::string outFile = (logDir / "stdout").string();
    const std::string errFile = (logDir / "stderr").string();

    ProcessRun run;
    const Clock::time_point start = Clock::now();
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int out = ::open(outFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
        const int err = ::open(errFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
        if (out < 0 || err < 0) ::_exit(126);
        ::dup2(out, 1);
        ::dup2(err, 2);
        if (options.userId >= 0 && (::setgroups(0, nullptr) != 0 || ::setgid(static_cast<gid_t>(options.userId)) != 0 ||
                                    ::setuid(static_cast<uid_t>(options.userId)) != 0)) {
            ::_exit(125);
        }
        ::execve(arguments[0], arguments.data(), environment.data());
        ::_exit(127);
    }
    EXPECT_GT(pid, 0) << "fork failed";
    int status = 0;
    while (true) {
        const pid_t done = ::waitpid(pid, &status, WNOHANG);
        if (done == pid) break;
        const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
        if (options.killWhen && options.killWhen(elapsed, pid)) {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, &status, 0);
            break;
        }
        if (elapsed > 600) {   // a hang: stop it, the test fails below
            ::kill(pid, SIGKILL);
            ::waitpid(pid, &status, 0);
            ADD_FAILURE() << "rbmMoveMesh ran for more than 600 s";
            break;
        }
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    run.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    run.killed = WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
    if (WIFEXITED(status)) run.exitStatus = WEXITSTATUS(status);
    run.out = readText(logDir / "stdout");
    run.err = readText(logDir / "stderr");
    return run;
}

// The same with extra environment variables and a kill condition only.
inline ProcessRun runMoveMesh(const std::filesystem::path& caseDir, const std::filesystem::path& logDir,
                              const std::vector<std::pair<std::string, std::string>>& extraEnvironment = {},
                              const std::function<bool(double, pid_t)>& killWhen = {})
{
    MoveMeshProcessOptions options;
    options.environment = extraEnvironment;
    options.killWhen = killWhen;
    return runMoveMeshWith(caseDir, logDir, options);
}

} // namespace rbm::test

#include "Process.hpp"

#include "Record.hpp"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <ctime>
#include <fstream>
#include <iostream>
#include <iterator>
#include <stdexcept>

namespace rbm::benchmark {

double secondsSince(Clock::time_point start)
{
    return std::chrono::duration<double>(Clock::now() - start).count();
}

double processCpuSeconds()
{
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

double procStatusMiB(const std::string& name)
{
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind(name + ":", 0) != 0) continue;
        return std::strtod(line.c_str() + name.size() + 1, nullptr) / 1024.0;
    }
    return nan;
}

std::string firstLineWith(const std::string& file, const std::string& prefix)
{
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line))
        if (line.rfind(prefix, 0) == 0) return line;
    return {};
}

std::string afterColon(const std::string& line)
{
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) return line;
    std::size_t start = line.find_first_not_of(" \t", colon + 1);
    return start == std::string::npos ? std::string() : line.substr(start);
}

std::uintmax_t directoryBytes(const fs::path& directory)
{
    std::uintmax_t bytes = 0;
    std::error_code error;
    for (const auto& entry : fs::recursive_directory_iterator(directory, error))
        if (entry.is_regular_file(error)) bytes += entry.file_size(error);
    return bytes;
}

fs::path selfExecutable()
{
    return fs::read_symlink("/proc/self/exe");
}

ProcessResult runProcess(const std::vector<std::string>& argv, const fs::path& stderrFile,
                         const std::vector<std::string>* environment, const fs::path& stdoutFile,
                         const fs::path& workingDirectory)
{
    int pipeEnds[2] = {-1, -1};
    if (stdoutFile.empty() && pipe(pipeEnds) != 0) throw std::runtime_error("pipe failed");
    std::vector<char*> args;
    for (const std::string& arg : argv) args.push_back(const_cast<char*>(arg.c_str()));
    args.push_back(nullptr);
    std::vector<char*> env;
    if (environment) {
        for (const std::string& entry : *environment) env.push_back(const_cast<char*>(entry.c_str()));
        env.push_back(nullptr);
    }
    std::cout.flush();
    std::cerr.flush();
    const auto started = Clock::now();
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
        if (stdoutFile.empty()) {
            dup2(pipeEnds[1], STDOUT_FILENO);
            close(pipeEnds[0]);
            close(pipeEnds[1]);
        } else {
            const int out = open(stdoutFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            if (out >= 0) dup2(out, STDOUT_FILENO);
        }
        const int err = open(stderrFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (err >= 0) dup2(err, STDERR_FILENO);
        if (!workingDirectory.empty() && chdir(workingDirectory.c_str()) != 0) _exit(126);
        if (environment) execve(args[0], args.data(), env.data());
        else execv(args[0], args.data());
        _exit(127);
    }
    ProcessResult result;
    if (stdoutFile.empty()) {
        close(pipeEnds[1]);
        char buffer[4096];
        ssize_t count = 0;
        while ((count = read(pipeEnds[0], buffer, sizeof buffer)) > 0) result.output.append(buffer, count);
        close(pipeEnds[0]);
    }
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    result.wallSeconds = secondsSince(started);
    result.maxRssMiB = static_cast<double>(usage.ru_maxrss) / 1024.0;
    result.userSeconds = static_cast<double>(usage.ru_utime.tv_sec) + 1e-6 * static_cast<double>(usage.ru_utime.tv_usec);
    result.systemSeconds = static_cast<double>(usage.ru_stime.tv_sec) + 1e-6 * static_cast<double>(usage.ru_stime.tv_usec);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    return result;
}

std::string trim(const std::string& text)
{
    const std::size_t first = text.find_first_not_of(" \t\n");
    if (first == std::string::npos) return {};
    return text.substr(first, text.find_last_not_of(" \t\n") - first + 1);
}

std::string readTail(const fs::path& file, std::size_t bytes)
{
    std::ifstream in(file);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.size() > bytes) text = "..." + text.substr(text.size() - bytes);
    return trim(text);
}

std::vector<std::string> environmentWith(const std::vector<std::string>& additions)
{
    std::vector<std::string> environment;
    for (char** entry = environ; *entry; ++entry) environment.emplace_back(*entry);
    environment.insert(environment.end(), additions.begin(), additions.end());
    return environment;
}

} // namespace rbm::benchmark

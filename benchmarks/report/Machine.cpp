#include "Machine.hpp"

#include "Process.hpp"

#include <petscversion.h>

#include <sys/utsname.h>
#include <unistd.h>

#include <cstdlib>
#include <ctime>
#include <fstream>

#ifndef RBM_SOURCE_DIR
#define RBM_SOURCE_DIR "."
#endif

namespace rbm::benchmark {

std::string todayIso()
{
    const std::time_t now = std::time(nullptr);
    char buffer[32];
    std::strftime(buffer, sizeof buffer, "%Y-%m-%d", std::localtime(&now));
    return buffer;
}

std::string nowIso()
{
    const std::time_t now = std::time(nullptr);
    char buffer[40];
    std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%S%z", std::localtime(&now));
    return buffer;
}

Record machineRecord(const fs::path& logDir)
{
    Record machine;
    machine.set("nproc", static_cast<double>(sysconf(_SC_NPROCESSORS_ONLN)));
    machine.set("cpuModel", afterColon(firstLineWith("/proc/cpuinfo", "model name")));
    const std::string memTotal = afterColon(firstLineWith("/proc/meminfo", "MemTotal"));
    machine.set("memoryGiB", std::strtod(memTotal.c_str(), nullptr) / 1048576.0);
    utsname name{};
    if (uname(&name) == 0) machine.set("kernel", std::string(name.sysname) + " " + name.release);
    std::ifstream load("/proc/loadavg");
    std::string loadText;
    std::getline(load, loadText);
    machine.set("loadAverageAtStart", loadText);
    machine.set("compiler", std::string("GCC/Clang ") + __VERSION__);
#ifdef NDEBUG
    machine.set("assertions", "off (NDEBUG)");
#else
    machine.set("assertions", "on");
#endif
    machine.set("petsc", std::to_string(PETSC_VERSION_MAJOR) + "." + std::to_string(PETSC_VERSION_MINOR) + "." +
                             std::to_string(PETSC_VERSION_SUBMINOR));
    if (fs::exists("/usr/bin/git")) {
        const ProcessResult git = runProcess({"/usr/bin/git", "-C", RBM_SOURCE_DIR, "rev-parse", "--short", "HEAD"},
                                             logDir / "git.stderr");
        machine.set("gitCommit", trim(git.output));
        const ProcessResult status = runProcess(
            {"/usr/bin/git", "-C", RBM_SOURCE_DIR, "status", "--porcelain", "--untracked-files=no"}, logDir / "git.stderr");
        machine.setFlag("gitDirty", !trim(status.output).empty());
    }
    return machine;
}

std::string loadAverage()
{
    std::ifstream load("/proc/loadavg");
    std::string text;
    std::getline(load, text);
    return text;
}

} // namespace rbm::benchmark

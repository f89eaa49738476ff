// LD_PRELOAD shim for KillDuringWriteTest: kills the process with SIGKILL right before or
// right after the N-th rename whose source path contains a given text, so the test can stop
// rbmMoveMesh at exactly the moments a time folder is committed (TimeFolderWriter), which no
// timer hits reliably. Environment:
//   RBM_KILL_RENAME_MATCH   text the source path must contain to count (default ".tmp-",
//                           the staging-folder marker of TimeFolderWriter)
//   RBM_KILL_AT_RENAME      N (1-based); unset or 0: never kill
//   RBM_KILL_WHEN           "before" (default) or "after" the rename
//   RBM_KILL_RENAME_LOG     file to which every counted rename appends "N source -> target"
// rename, renameat and renameat2 are intercepted (std::filesystem::rename calls rename;
// TimeFolderWriter calls renameat2 for RENAME_EXCHANGE).
//
// And, to stop it while a file is half written:
//   RBM_KILL_WRITE_MATCH    kill at the second write() to a file in a staging folder (path
//                           contains ".tmp-") whose path ends with this text, before it writes:
//                           the file then holds its first piece only. Unset: write() passes.

#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <cstring>

namespace {

std::atomic<int> counted{0};

const char* environment(const char* name, const char* fallback)
{
    const char* value = std::getenv(name);
    return value && *value ? value : fallback;
}

void logRename(int number, const char* from, const char* to)
{
    const char* log = std::getenv("RBM_KILL_RENAME_LOG");
    if (!log || !*log) return;
    if (FILE* out = std::fopen(log, "a")) {
        std::fprintf(out, "%d %s -> %s\n", number, from, to);
        std::fclose(out);
    }
}

// The number of this rename when it counts, 0 otherwise.
int countRename(const char* from, const char* to)
{
    if (!from || !std::strstr(from, environment("RBM_KILL_RENAME_MATCH", ".tmp-"))) return 0;
    const int number = ++counted;
    logRename(number, from, to);
    return number;
}

void killIf(int number, const char* when)
{
    if (number == 0) return;
    const int target = std::atoi(environment("RBM_KILL_AT_RENAME", "0"));
    if (number == target && std::strcmp(environment("RBM_KILL_WHEN", "before"), when) == 0) {
        ::kill(::getpid(), SIGKILL);
        ::pause();
    }
}

template <typename Function>
Function next(const char* name)
{
    return reinterpret_cast<Function>(::dlsym(RTLD_NEXT, name));
}

// Whether this write() is the second to a staged file matching RBM_KILL_WRITE_MATCH.
bool secondWriteToMatchingFile(int fd)
{
    static const char* match = std::getenv("RBM_KILL_WRITE_MATCH");
    if (!match || !*match) return false;
    static std::atomic<int> lastFd{-1};
    char link[64];
    char path[4096];
    std::snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    const ssize_t length = ::readlink(link, path, sizeof path - 1);
    if (length <= 0) return false;
    path[length] = '\0';
    const std::size_t matchLength = std::strlen(match);
    if (!std::strstr(path, ".tmp-") || static_cast<std::size_t>(length) < matchLength ||
        std::strcmp(path + length - matchLength, match) != 0)
        return false;
    return lastFd.exchange(fd) == fd;   // the same file written before
}

} // namespace

extern "C" {

ssize_t write(int fd, const void* data, size_t size)
{
    using Write = ssize_t (*)(int, const void*, size_t);
    static const Write real = next<Write>("write");
    if (secondWriteToMatchingFile(fd)) {
        ::kill(::getpid(), SIGKILL);
        ::pause();
    }
    return real(fd, data, size);
}

int rename(const char* from, const char* to) noexcept   // glibc declares them __THROW
{
    using Rename = int (*)(const char*, const char*);
    static const Rename real = next<Rename>("rename");
    const int number = countRename(from, to);
    killIf(number, "before");
    const int result = real(from, to);
    killIf(number, "after");
    return result;
}

int renameat(int fromDirectory, const char* from, int toDirectory, const char* to) noexcept
{
    using RenameAt = int (*)(int, const char*, int, const char*);
    static const RenameAt real = next<RenameAt>("renameat");
    const int number = countRename(from, to);
    killIf(number, "before");
    const int result = real(fromDirectory, from, toDirectory, to);
    killIf(number, "after");
    return result;
}

int renameat2(int fromDirectory, const char* from, int toDirectory, const char* to, unsigned int flags) noexcept
{
    using RenameAt2 = int (*)(int, const char*, int, const char*, unsigned int);
    static const RenameAt2 real = next<RenameAt2>("renameat2");
    const int number = countRename(from, to);
    killIf(number, "before");
    const int result = real(fromDirectory, from, toDirectory, to, flags);
    killIf(number, "after");
    return result;
}

} // extern "C"

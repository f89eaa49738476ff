#include "CaseLock.hpp"

#include "WholeFile.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <utility>

namespace rbm::io {

CaseLock CaseLock::acquire(const std::filesystem::path& caseDirectory)
{
    CaseLock lock;
    const int fd = ::open(caseDirectory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) {
        const int error = errno;
        // A missing case is not the lock's business: reading the case reports it.
        if (error == ENOENT || error == ENOTDIR) return lock;
        lock.message_ = "cannot lock the case " + caseDirectory.string() + " (" + systemErrorText(error) + ")";
        return lock;
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) {
        lock.fd_ = fd;
        lock.state_ = State::Held;
        return lock;
    }
    const int error = errno;
    if (error == EWOULDBLOCK) {
        struct stat status {};
        if (::fstat(fd, &status) == 0) lock.holderPid_ = flockHolderPid(status.st_dev, status.st_ino);
        lock.state_ = State::HeldByAnother;
        lock.message_ = "another rbmMoveMesh" +
                        (lock.holderPid_ > 0 ? " (pid " + std::to_string(lock.holderPid_) + ")" : std::string()) +
                        " is moving the case " + caseDirectory.string() +
                        ": two runs on one case would write the same files. Wait for it to end (or stop it), "
                        "or run on a copy of the case.";
    } else {
        lock.message_ = "cannot lock the case " + caseDirectory.string() + " (" + systemErrorText(error) +
                        "): a second rbmMoveMesh on this case would not be noticed";
    }
    ::close(fd);
    return lock;
}

CaseLock::CaseLock(CaseLock&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), state_(other.state_), holderPid_(other.holderPid_),
      message_(std::move(other.message_))
{}

CaseLock& CaseLock::operator=(CaseLock&& other) noexcept
{
    if (this != &other) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = std::exchange(other.fd_, -1);
        state_ = other.state_;
        holderPid_ = other.holderPid_;
        message_ = std::move(other.message_);
    }
    return *this;
}

CaseLock::~CaseLock()
{
    if (fd_ >= 0) ::close(fd_);   // closing the only descriptor releases the flock
}

long flockHolderPid(unsigned long long device, unsigned long long inode)
{
    // Lines like "1: FLOCK  ADVISORY  WRITE 12345 08:01:1234567 0 EOF" (device in hex); a
    // waiting request is marked "->" and is not the holder.
    std::ifstream locks("/proc/locks");
    for (std::string line; std::getline(locks, line);) {
        std::istringstream fields(line);
        std::string number, kind, mode, access, file;
        long pid = 0;
        if (!(fields >> number >> kind)) continue;
        if (kind == "->") continue;
        if (!(fields >> mode >> access >> pid >> file) || kind != "FLOCK") continue;
        unsigned int major = 0, minor = 0;
        unsigned long long lockedInode = 0;
        if (std::sscanf(file.c_str(), "%x:%x:%llu", &major, &minor, &lockedInode) != 3) continue;
        if (lockedInode == inode && ::makedev(major, minor) == device && pid > 0) return pid;
    }
    return 0;
}

} // namespace rbm::io

#pragma once
// An advisory lock on an OpenFOAM case folder for the length of a run that writes into it,
// so that a second rbmMoveMesh on the same case is refused before it reads or writes
// anything, instead of both writing the same files (where one of them can die with
// "filesystem error: cannot rename: No such file or directory [./VTK/...vtu.tmp]").
//
// The lock is flock(LOCK_EX) on the case folder itself (an O_RDONLY descriptor of the folder):
//  - nothing is written: no lock file to leave behind or to clean up;
//  - the kernel releases it when the process ends in any way, kill -9 included, so there is
//    never a stale lock; the descriptor is close-on-exec, so a program started by the run
//    does not keep it;
//  - the holder's process id is read from /proc/locks (flock has no query) for the message.
// File systems without flock on folders (some NFS set-ups) give no lock: acquire() then
// says why, and the run may go on unlocked.
//
//   CaseLock lock = CaseLock::acquire(caseDir);
//   if (lock.heldByAnother()) { std::cerr << lock.message(); return 2; }

#include <filesystem>
#include <string>

namespace rbm::io {

class CaseLock {
public:
    enum class State {
        Held,           // this process holds the lock until the object is destroyed
        HeldByAnother,  // another process holds it (holderPid() when known)
        Unavailable,    // the folder cannot be opened or locked (message() says why)
    };

    // Tries once, without waiting.
    static CaseLock acquire(const std::filesystem::path& caseDirectory);

    CaseLock(CaseLock&& other) noexcept;
    CaseLock& operator=(CaseLock&& other) noexcept;
    CaseLock(const CaseLock&) = delete;
    CaseLock& operator=(const CaseLock&) = delete;
    ~CaseLock();   // releases the lock

    State state() const { return state_; }
    bool heldByAnother() const { return state_ == State::HeldByAnother; }
    // The process that holds the lock (HeldByAnother), 0 when /proc/locks does not say.
    long holderPid() const { return holderPid_; }
    // HeldByAnother: "another rbmMoveMesh (pid N) is moving the case DIR: ..."; Unavailable:
    // "cannot lock the case DIR (REASON): ...", or empty when the folder does not exist (reading
    // the case reports that); Held: empty.
    const std::string& message() const { return message_; }

private:
    CaseLock() = default;

    int fd_ = -1;
    State state_ = State::Unavailable;
    long holderPid_ = 0;
    std::string message_;
};

// The process id /proc/locks gives for an flock lock on the file or folder with this device
// and inode, 0 when there is none or it cannot be read.
long flockHolderPid(unsigned long long device, unsigned long long inode);

} // namespace rbm::io

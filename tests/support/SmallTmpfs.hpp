#pragma once
// A small tmpfs mounted for one test: a disk that fills up after a few megabytes, to test
// what rbm does when a write fails with "No space left on device". Mounting needs root (or
// CAP_SYS_ADMIN), as the tests run in CI; elsewhere mounted() is false and whyNot() says
// why, for a visible GTEST_SKIP.
//
//   TempDir dir("diskFull");                        // declared first: removed after the unmount
//   SmallTmpfs disk(dir.path() / "disk", "3m");
//   if (!disk.mounted()) GTEST_SKIP() << disk.whyNot();

#include <sys/mount.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

namespace rbm::test {

class SmallTmpfs {
public:
    SmallTmpfs(std::filesystem::path mountPoint, const std::string& size) : mountPoint_(std::move(mountPoint))
    {
        std::filesystem::create_directories(mountPoint_);
        const std::string options = "size=" + size + ",mode=0755";
        if (::mount("tmpfs", mountPoint_.c_str(), "tmpfs", 0, options.c_str()) == 0) {
            mounted_ = true;
        } else {
            const int error = errno;
            whyNot_ = "cannot mount a tmpfs of " + size + " on " + mountPoint_.string() + " (" + std::strerror(error) +
                      "): the test needs root or CAP_SYS_ADMIN to make a small disk that fills up";
        }
    }
    ~SmallTmpfs()
    {
        if (mounted_) ::umount2(mountPoint_.c_str(), MNT_DETACH);
    }
    SmallTmpfs(const SmallTmpfs&) = delete;
    SmallTmpfs& operator=(const SmallTmpfs&) = delete;

    bool mounted() const { return mounted_; }
    const std::string& whyNot() const { return whyNot_; }
    const std::filesystem::path& path() const { return mountPoint_; }

    // Removes everything on the disk (between the runs of a test).
    void clear() const
    {
        for (const auto& entry : std::filesystem::directory_iterator(mountPoint_)) std::filesystem::remove_all(entry.path());
    }

private:
    std::filesystem::path mountPoint_;
    bool mounted_ = false;
    std::string whyNot_;
};

} // namespace rbm::test

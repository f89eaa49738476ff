#include "WholeFile.hpp"

#include "InputError.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <system_error>

namespace rbm::io {

namespace fs = std::filesystem;

namespace {

// Closes a file descriptor on every way out of readWholeFile.
class ReadDescriptor {
public:
    explicit ReadDescriptor(int fd) : fd_(fd) {}
    ~ReadDescriptor()
    {
        if (fd_ >= 0) ::close(fd_);
    }
    ReadDescriptor(const ReadDescriptor&) = delete;
    ReadDescriptor& operator=(const ReadDescriptor&) = delete;
    int get() const { return fd_; }

private:
    int fd_;
};

} // namespace

std::string systemErrorText(int error)
{
    return std::generic_category().message(error);
}

OutputFile::OutputFile(fs::path file, fs::path shownAs)
    : file_(std::move(file)), shownAs_(shownAs.empty() ? file_ : std::move(shownAs))
{
    fd_ = ::open(file_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd_ < 0) {
        const int error = errno;
        throw std::runtime_error("cannot create " + shownAs_.string() + ": " + systemErrorText(error));
    }
}

OutputFile::~OutputFile()
{
    if (fd_ < 0) return;
    ::close(fd_);
    std::error_code ignored;
    fs::remove(file_, ignored);
}

void OutputFile::fail(const char* what, int error)
{
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    std::error_code ignored;
    fs::remove(file_, ignored);   // nothing partial stays behind
    throw std::runtime_error(std::string(what) + " " + shownAs_.string() + ": " + systemErrorText(error));
}

void OutputFile::write(std::string_view bytes)
{
    std::size_t written = 0;
    while (written < bytes.size()) {
        const ssize_t result = ::write(fd_, bytes.data() + written, bytes.size() - written);
        if (result < 0 && errno == EINTR) continue;
        if (result < 0) fail("cannot write", errno);
        written += static_cast<std::size_t>(result);
    }
}

void OutputFile::close()
{
    // close() reports late write errors (NFS, quotas): checked, not dropped.
    const int result = ::close(fd_);
    const int error = errno;
    fd_ = -1;
    if (result != 0) fail("cannot close", error);
}

void writeWholeFile(const fs::path& file, std::string_view bytes)
{
    OutputFile out(file);
    out.write(bytes);
    out.close();
}

fs::path temporaryNameOf(const fs::path& file)
{
    return fs::path(file.string() + ".tmp");
}

void replaceFileAtomically(const fs::path& file, std::string_view bytes)
{
    const fs::path temporary = temporaryNameOf(file);
    {
        OutputFile out(temporary, file);
        out.write(bytes);
        out.close();
    }
    if (std::rename(temporary.c_str(), file.c_str()) != 0) {
        const int error = errno;
        std::error_code ignored;
        fs::remove(temporary, ignored);
        throw std::runtime_error("cannot rename " + temporary.string() + " to " + file.string() + ": " +
                                 systemErrorText(error));
    }
}

std::vector<std::string> removeStaleTemporaries(const fs::path& folder, const std::vector<std::string>& suffixes)
{
    const auto isTemporary = [&](const std::string& name) {
        return std::any_of(suffixes.begin(), suffixes.end(), [&](const std::string& suffix) {
            const std::string ending = suffix + ".tmp";
            return name.size() > ending.size() && name.compare(name.size() - ending.size(), ending.size(), ending) == 0;
        });
    };
    std::vector<std::string> removed;
    std::error_code error;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
        const std::string name = entry.path().filename().string();
        std::error_code ignored;
        if (isTemporary(name) && entry.is_regular_file(ignored) && fs::remove(entry.path(), ignored)) removed.push_back(name);
    }
    return removed;
}

std::string readWholeFile(const fs::path& file)
{
    ReadDescriptor fd(::open(file.c_str(), O_RDONLY | O_CLOEXEC));
    if (fd.get() < 0) {
        const int error = errno;
        throw InputError(file.string(), 0, "cannot open file for reading (" + systemErrorText(error) + ")");
    }
    struct stat status {};
    if (::fstat(fd.get(), &status) != 0) {
        const int error = errno;
        throw InputError(file.string(), 0, "cannot read file (" + systemErrorText(error) + ")");
    }
    // One read into a buffer of the file's size (no stream-buffer copy of large meshes), one
    // byte more to see the end at once; the loop also takes a file that grew since fstat.
    std::string bytes(static_cast<std::size_t>(std::max<off_t>(status.st_size, 0)) + 1, '\0');
    std::size_t done = 0;
    while (true) {
        if (done == bytes.size()) bytes.resize(2 * bytes.size());
        const ssize_t result = ::read(fd.get(), bytes.data() + done, bytes.size() - done);
        if (result < 0) {
            if (errno == EINTR) continue;
            const int error = errno;
            throw InputError(file.string(), 0, "cannot read file (" + systemErrorText(error) + ")");
        }
        if (result == 0) break;
        done += static_cast<std::size_t>(result);
    }
    bytes.resize(done);
    return bytes;
}

} // namespace rbm::io

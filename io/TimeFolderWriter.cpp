#include "TimeFolderWriter.hpp"

#include "TimeName.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>    // AT_FDCWD
#include <stdio.h>    // renameat2, RENAME_EXCHANGE (glibc 2.28)
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cstdio>
#include <stdexcept>
#include <string_view>
#include <system_error>

namespace rbm::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* stagingMarker = ".tmp-";

std::string stagingSuffix(unsigned attempt)
{
    // The process id keeps two programs apart, the counter two folders of one program.
    static std::atomic<unsigned> counter{0};
    char buffer[48];
    std::snprintf(buffer, sizeof buffer, "%s%x-%x", stagingMarker, static_cast<unsigned>(::getpid()),
                  counter.fetch_add(1) + attempt);
    return buffer;
}

// "points.gz" <-> "points".
fs::path compressionTwin(const fs::path& file)
{
    const std::string name = file.filename().string();
    constexpr std::string_view gz = ".gz";
    if (name.size() > gz.size() && name.compare(name.size() - gz.size(), gz.size(), gz) == 0) {
        return file.parent_path() / name.substr(0, name.size() - gz.size());
    }
    return file.parent_path() / (name + ".gz");
}

// Moves every file under `from` to the same relative place under `to`, replacing files
// there and removing their compression twins (the fallback without RENAME_EXCHANGE).
void mergeInto(const fs::path& from, const fs::path& to)
{
    for (const fs::directory_entry& entry : fs::directory_iterator(from)) {
        const fs::path destination = to / entry.path().filename();
        if (entry.is_directory()) {
            if (!fs::exists(destination)) {
                fs::rename(entry.path(), destination);   // a whole new sub-folder at once
            } else {
                mergeInto(entry.path(), destination);
            }
            continue;
        }
        std::error_code ignored;
        if (fs::equivalent(entry.path(), destination, ignored)) continue;   // a kept file, linked by linkKeptFiles
        fs::rename(entry.path(), destination);   // atomic replacement of one file
        fs::remove(compressionTwin(destination), ignored);
    }
}

// Gives `staging` every file of the existing time folder `existing` that it does not
// replace: hard links (the same file, no copy), or copies where the file system has none.
// A file whose name or compression twin is staged is left out; sub-folders recurse.
void linkKeptFiles(const fs::path& existing, const fs::path& staging)
{
    for (const fs::directory_entry& entry : fs::directory_iterator(existing)) {
        const fs::path name = entry.path().filename();
        const fs::path destination = staging / name;
        if (entry.is_directory() && !entry.is_symlink()) {
            if (fs::exists(destination) && !fs::is_directory(destination)) continue;   // replaced by a file
            fs::create_directories(destination);
            linkKeptFiles(entry.path(), destination);
            continue;
        }
        std::error_code error;
        if (fs::exists(fs::symlink_status(destination, error)) ||
            fs::exists(fs::symlink_status(compressionTwin(destination), error))) {
            continue;   // replaced by the staged file
        }
        if (entry.is_symlink()) {
            fs::copy_symlink(entry.path(), destination);
            continue;
        }
        fs::create_hard_link(entry.path(), destination, error);
        if (error) fs::copy_file(entry.path(), destination);
    }
}

// Swaps two folders in one step. False when the file system cannot (the caller falls back).
bool exchangeFolders(const fs::path& a, const fs::path& b)
{
    if (::renameat2(AT_FDCWD, a.c_str(), AT_FDCWD, b.c_str(), RENAME_EXCHANGE) == 0) return true;
    const int error = errno;
    if (error == EINVAL || error == ENOSYS || error == ENOTSUP) return false;
    throw fs::filesystem_error("cannot exchange the folders", a, b, std::error_code(error, std::generic_category()));
}

} // namespace

TimeFolderWriter::TimeFolderWriter(fs::path caseDirectory, std::string timeName)
    : caseDirectory_(std::move(caseDirectory)), timeName_(std::move(timeName))
{
    for (unsigned attempt = 0; attempt < 1000; ++attempt) {
        fs::path candidate = caseDirectory_ / (timeName_ + stagingSuffix(attempt));
        std::error_code error;
        if (fs::create_directory(candidate, error)) {
            staging_ = std::move(candidate);
            return;
        }
        if (error) {
            throw std::runtime_error("cannot create the folder " + candidate.string() + ": " + error.message());
        }
    }
    throw std::runtime_error("cannot find a free name for a staging folder of time " + timeName_ + " in " +
                             caseDirectory_.string());
}

TimeFolderWriter::~TimeFolderWriter()
{
    if (committed_ || staging_.empty()) return;
    std::error_code ignored;
    fs::remove_all(staging_, ignored);
}

fs::path TimeFolderWriter::commit()
{
    const fs::path folder = target();
    try {
        std::error_code error;
        if (!fs::exists(folder, error)) {
            fs::rename(staging_, folder);
        } else {
            if (!fs::is_directory(folder)) {
                throw std::runtime_error(folder.string() + " exists and is not a folder");
            }
            linkKeptFiles(folder, staging_);
            if (exchangeFolders(staging_, folder)) {
                // The old folder now has the staging name: a kill before it is gone leaves a
                // staging folder, which the next run removes (removeStaleStagingFolders).
                fs::remove_all(staging_);
            } else {
                mergeInto(staging_, folder);
                fs::remove_all(staging_);
            }
        }
    } catch (const fs::filesystem_error& error) {
        throw std::runtime_error("cannot move the files of time " + timeName_ + " into " + folder.string() + ": " +
                                 error.what());
    }
    committed_ = true;
    return folder;
}

bool isTimeFolderStagingName(const std::string& name)
{
    const std::size_t marker = name.rfind(stagingMarker);
    if (marker == std::string::npos || marker == 0) return false;
    double value = 0.0;
    if (!parseTimeName(std::string_view(name).substr(0, marker), value)) return false;
    const std::string id = name.substr(marker + std::char_traits<char>::length(stagingMarker));
    if (id.empty()) return false;
    for (const char c : id) {
        if (!(std::isxdigit(static_cast<unsigned char>(c)) || c == '-')) return false;
    }
    return true;
}

std::vector<std::string> removeStaleStagingFolders(const fs::path& caseDirectory)
{
    std::vector<std::string> removed;
    std::error_code error;
    for (const fs::directory_entry& entry : fs::directory_iterator(caseDirectory, error)) {
        if (!entry.is_directory()) continue;
        const std::string name = entry.path().filename().string();
        if (!isTimeFolderStagingName(name)) continue;
        std::error_code ignored;
        fs::remove_all(entry.path(), ignored);
        removed.push_back(name);
    }
    return removed;
}

} // namespace rbm::io

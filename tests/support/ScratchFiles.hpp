#pragma once
// Scratch folders and whole-file text helpers shared by the test programs.

#include <errno.h>  // program_invocation_short_name (GNU)
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

namespace rbm::test {

// A fresh folder $TMPDIR/<program>_<name>_<pid>, removed with its contents on destruction.
// The program name and the process id keep tests that CTest runs in parallel apart.
class TempDir {
public:
    explicit TempDir(const std::string& name)
        : path_(std::filesystem::temp_directory_path() /
                (std::string(program_invocation_short_name) + "_" + name + "_" + std::to_string(::getpid())))
    {
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() { std::filesystem::remove_all(path_); }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

// Writes `text` as the whole file, creating its folder.
inline void writeText(const std::filesystem::path& file, const std::string& text)
{
    if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << text;
}

// The whole file, byte for byte (empty when it cannot be read).
inline std::string readText(const std::filesystem::path& file)
{
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

// Every file and folder under `folder` with its bytes ("<folder>" for folders), by relative path:
// two snapshots are equal when the tree is byte for byte the same.
using Snapshot = std::map<std::string, std::string>;

inline Snapshot snapshot(const std::filesystem::path& folder)
{
    Snapshot files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
        const std::string name = std::filesystem::relative(entry.path(), folder).string();
        files[name] = entry.is_directory() ? std::string("<folder>") : readText(entry.path());
    }
    return files;
}

// " name (N bytes)" for every entry, for failure messages.
inline std::string describe(const Snapshot& files)
{
    std::string text;
    for (const auto& [name, bytes] : files) text += " " + name + " (" + std::to_string(bytes.size()) + " bytes)";
    return text;
}

} // namespace rbm::test

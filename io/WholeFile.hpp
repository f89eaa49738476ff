#pragma once
// Reading and writing whole files with the POSIX calls themselves (open, read, write, close,
// rename), so that every failure is reported with the file and the operating system's reason
// ("No space left on device", "Permission denied"): C++ streams and zlib's gzFile lose errno,
// and an std::ofstream checked before it is closed reports a write that its close then loses
// (a full disk left .pvd files of 0 bytes that way).
//
//   writeWholeFile(folder / "points", text);          // folder/points, or an exception
//   replaceFileAtomically(vtk / "case.pvd", xml);    // readers see the old file or the new one

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace rbm::io {

// The operating system's text for an errno value ("No space left on device").
std::string systemErrorText(int error);

// A file being written piece by piece: created (or truncated) by the constructor, filled by
// write(), finished by close(). Each throws std::runtime_error "cannot create|write|close
// FILE: REASON" and removes the partial file; destroyed without close() (an exception
// elsewhere), it removes the file too. `shownAs` is the name in messages (the final name
// of a temporary file); empty: `file`.
class OutputFile {
public:
    explicit OutputFile(std::filesystem::path file, std::filesystem::path shownAs = {});
    ~OutputFile();
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    void write(std::string_view bytes);
    void close();

private:
    [[noreturn]] void fail(const char* what, int error);

    std::filesystem::path file_;
    std::filesystem::path shownAs_;
    int fd_ = -1;
};

// Writes `bytes` as the whole content of `file` (created, or truncated). On failure the
// partial file is removed and std::runtime_error is thrown: "cannot write FILE: REASON"
// (or "cannot create", "cannot close").
void writeWholeFile(const std::filesystem::path& file, std::string_view bytes);

// Writes `bytes` to temporaryNameOf(file), then renames it over `file` (an atomic
// replacement on POSIX file systems): a reader, or a run killed at any moment, sees the old
// file or the new one, never a part. On failure the temporary file is removed, `file` is
// left as it was and std::runtime_error names the file and the reason.
void replaceFileAtomically(const std::filesystem::path& file, std::string_view bytes);

// "<file>.tmp": the name replaceFileAtomically writes to before the rename. Without a
// process id: the case lock (CaseLock.hpp) keeps a second writer away, and a leftover of a
// killed run is overwritten by the next write or removed by removeStaleTemporaries.
std::filesystem::path temporaryNameOf(const std::filesystem::path& file);

// Removes the files of `folder` whose names end in "<suffix>.tmp" for one of `suffixes`
// (leftovers of replaceFileAtomically in a killed run) and returns their names; a missing
// folder has none.
std::vector<std::string> removeStaleTemporaries(const std::filesystem::path& folder,
                                                const std::vector<std::string>& suffixes);

// The whole content of a regular file. Throws rbm::InputError naming the file and the
// reason: "cannot open file for reading (Permission denied)", "cannot read file (...)".
std::string readWholeFile(const std::filesystem::path& file);

} // namespace rbm::io

#pragma once
// Atomic writing of a time folder (<case>/<time>): a reader (ParaView, OpenFOAM, a user
// listing the case, a restart with startFrom latestTime) never sees a half-written time.
//
// The files are first written into a staging folder next to it, `<case>/<time>.tmp-<id>`
// (not a time folder: OpenFOAM and listTimeDirectories only take names that read wholly as
// numbers), then committed:
//  - when <case>/<time> does not exist, the staging folder is renamed to it: one atomic
//    rename, the folder appears complete or not at all;
//  - when it exists (a run repeated over earlier results, or files of a flow solver), the
//    files of the existing folder that the staged ones do not replace are hard-linked (or
//    copied) into the staging folder, leaving out the compression twin of each staged file
//    (`points` for `points.gz` and the other way round) so a stale file never shadows the
//    new one, as OpenFOAM does; then the two folders are swapped in one atomic
//    renameat2(RENAME_EXCHANGE) and the old one, now under the staging name, is removed.
//    A kill -9 at any moment leaves the old folder or the new one, whole; at worst a staging
//    folder, which removeStaleStagingFolders() clears at the next run. File systems without
//    RENAME_EXCHANGE (it needs Linux 3.15 and, e.g., no NFS) fall back to renaming every
//    staged file over its namesake: each file is replaced atomically, the folder as a whole
//    is not.
// When writing fails (an exception before commit) the staging folder is removed: nothing
// partial is left behind.
//
//   TimeFolderWriter folder(caseDir, "0.5");
//   writePointsFile(folder.staging() / "polyMesh" / "points", points, "0.5/polyMesh", options);
//   folder.commit();

#include <filesystem>
#include <string>
#include <vector>

namespace rbm::io {

class TimeFolderWriter {
public:
    // Creates the staging folder <caseDirectory>/<timeName>.tmp-<id>. Throws
    // std::runtime_error when it cannot be created.
    TimeFolderWriter(std::filesystem::path caseDirectory, std::string timeName);
    // Removes the staging folder unless commit() succeeded.
    ~TimeFolderWriter();
    TimeFolderWriter(const TimeFolderWriter&) = delete;
    TimeFolderWriter& operator=(const TimeFolderWriter&) = delete;

    // Where to write the files, with the same layout as the time folder.
    const std::filesystem::path& staging() const { return staging_; }
    // The time folder the files will land in.
    std::filesystem::path target() const { return caseDirectory_ / timeName_; }

    // Moves the staged files into <case>/<time> (see the top of this file) and returns that
    // folder. Throws std::runtime_error (the staging folder is then removed) on failure.
    std::filesystem::path commit();

private:
    std::filesystem::path caseDirectory_;
    std::string timeName_;
    std::filesystem::path staging_;
    bool committed_ = false;
};

// True for names of staging folders: "<number>.tmp-<id>".
bool isTimeFolderStagingName(const std::string& name);

// Removes the staging folders an interrupted run may have left in `caseDirectory` and
// returns their names.
std::vector<std::string> removeStaleStagingFolders(const std::filesystem::path& caseDirectory);

} // namespace rbm::io

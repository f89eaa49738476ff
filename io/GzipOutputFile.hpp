#pragma once
// A gzip file compressed as it is written: bytes go through one zlib deflate stream (level 1)
// into a 128 KiB buffer that goes to the file whenever it is full, so memory stays bounded
// whatever the size of the file. The result is one standard gzip member (what gzopen/gzwrite
// and OpenFOAM's gzstream write and read back).
//
//   GzipOutputFile out(folder / "points.gz");
//   out.write(piece1); out.write(piece2); ...
//   out.close();                                 // the trailer, then the file is closed
//
// Level 1, not OpenFOAM's default 6: any level reads back the same, and level 6 takes several
// times as long for files at most about a tenth smaller (writing's share of a run:
// docs/rbmMoveMesh.md, "Where a one-step run's time goes"). Errors are OutputFile's (the OS
// reason, the partial file removed); destroyed without close(), the partial file is removed.

#include "WholeFile.hpp"

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace rbm::io {

class GzipOutputFile {
public:
    explicit GzipOutputFile(std::filesystem::path file);
    ~GzipOutputFile();
    GzipOutputFile(const GzipOutputFile&) = delete;
    GzipOutputFile& operator=(const GzipOutputFile&) = delete;

    // Compresses `bytes` (any size; zlib's 32-bit counts are handled here).
    void write(std::string_view bytes);
    // Ends the deflate stream (gzip trailer: CRC-32 and size) and closes the file.
    void close();

private:
    struct Stream;   // zlib's z_stream, kept out of this header
    void deflateAll(std::string_view bytes, bool finish);

    std::filesystem::path file_;
    OutputFile out_;
    std::unique_ptr<Stream> stream_;
    std::string buffer_;   // compressed bytes on their way to the file
};

} // namespace rbm::io

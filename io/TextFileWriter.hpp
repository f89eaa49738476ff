#pragma once
// A file (plain, or gzip-compressed with ".gz" appended) whose text is produced in pieces:
// the writer formats into text(), calls pieceDone() now and then, and the text goes to the
// file whenever it reaches the piece size, so a write holds one piece (about 4 MiB) instead
// of the whole file. On a mesh of 10^6 points the whole ascii pointDisplacement is ~55 MB of
// text: built in one std::string (grown by doubling) and compressed in one shot it was the
// process's memory peak.
//
//   TextFileWriter out(timeDir / "pointDisplacement", compressed);
//   out.text() += header;
//   for (...) { appendLine(out.text(), ...); out.pieceDone(); }
//   out.append(rawBytes);                      // large binary data: straight through
//   const fs::path written = out.finish();     // "pointDisplacement" or "pointDisplacement.gz"
//
// The bytes are exactly those of writeFileContents(path, wholeText, compressed): a file
// that fits in one piece is written by writeFileContents itself (libdeflate in one shot for
// gzip: fast, and its buffer is at most a piece); a larger one goes piece by piece to an
// OutputFile or through one zlib stream (GzipOutputFile), one gzip member either way.
// Why zlib for several pieces: libdeflate (1.14) has no streaming interface; it compresses a
// whole buffer into a complete deflate stream whose last block is marked final, so pieces
// compressed apart would make a file of several gzip members, which is not the one standard
// member OpenFOAM's files are. zlib's level 1 is the price: on 1 030 301 vectors (the
// 10^6-cell mesh) writing took 0.475 s instead of 0.386 s for ascii pointDisplacement.gz and
// 0.28 s instead of 0.18 s for binary points.gz, for +73 MB -> +5 MB of peak memory.
// Nothing is created before the first piece is full or finish() is called; destroyed without
// finish() (an exception), the writer removes the partial file. Errors: std::runtime_error
// naming the file and the OS reason, as OutputFile's.

#include "GzipOutputFile.hpp"
#include "WholeFile.hpp"

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace rbm::io {

class TextFileWriter {
public:
    static constexpr std::size_t defaultPieceSize = std::size_t{4} << 20;

    // `pieceSize`: bytes of text held before they go to the file (tests use small ones to
    // write a small file in many pieces).
    explicit TextFileWriter(std::filesystem::path path, bool compress, std::size_t pieceSize = defaultPieceSize);
    ~TextFileWriter();
    TextFileWriter(const TextFileWriter&) = delete;
    TextFileWriter& operator=(const TextFileWriter&) = delete;

    // The text not yet written: append to it, then call pieceDone(). The same string for the
    // writer's whole life (emptied, with its capacity kept, whenever a piece is written).
    std::string& text() { return text_; }
    // Writes the text held when it has reached the piece size. Cheap otherwise: call it after
    // every line of a long list.
    void pieceDone()
    {
        if (text_.size() >= pieceSize_) writePiece();
    }
    // Appends `bytes`; a large block (binary list data) goes to the file without a copy.
    void append(std::string_view bytes);
    // Writes what is left and closes the file. Returns the path written (with ".gz" when
    // compressed).
    std::filesystem::path finish();

private:
    void writePiece();
    void writeToFile(std::string_view bytes);

    std::filesystem::path path_;     // as given (without ".gz")
    std::filesystem::path target_;   // the file written
    bool compress_;
    std::size_t pieceSize_;
    std::string text_;
    // Opened at the first piece written (only one of them, depending on compress_).
    std::unique_ptr<OutputFile> plain_;
    std::unique_ptr<GzipOutputFile> gzip_;
    bool finished_ = false;
};

} // namespace rbm::io

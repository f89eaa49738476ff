#include "TextFileWriter.hpp"

#include "CompressedFile.hpp"

#include <algorithm>
#include <stdexcept>

namespace rbm::io {

namespace fs = std::filesystem;

TextFileWriter::TextFileWriter(fs::path path, bool compress, std::size_t pieceSize)
    : path_(std::move(path)), target_(compress ? fs::path(path_.string() + ".gz") : path_), compress_(compress),
      pieceSize_(std::max<std::size_t>(pieceSize, 1))
{
    // A line appended after the piece is full overshoots it a little: no reallocation then.
    text_.reserve(pieceSize_ + 4096);
}

// The partial file, if any, is removed by OutputFile's / GzipOutputFile's destructors.
TextFileWriter::~TextFileWriter() = default;

void TextFileWriter::writeToFile(std::string_view bytes)
{
    if (!plain_ && !gzip_) {
        if (compress_) {
            gzip_ = std::make_unique<GzipOutputFile>(target_);
        } else {
            plain_ = std::make_unique<OutputFile>(target_);
        }
    }
    if (gzip_) {
        gzip_->write(bytes);
    } else {
        plain_->write(bytes);
    }
}

void TextFileWriter::writePiece()
{
    writeToFile(text_);
    text_.clear();
}

void TextFileWriter::append(std::string_view bytes)
{
    if (text_.size() + bytes.size() < pieceSize_) {
        text_.append(bytes);
        return;
    }
    // The text held first, to keep the order; then the block itself, in place.
    writePiece();
    writeToFile(bytes);
}

fs::path TextFileWriter::finish()
{
    if (finished_) throw std::logic_error("TextFileWriter::finish called twice for " + target_.string());
    finished_ = true;
    if (!plain_ && !gzip_) {
        // Everything fits in one piece: exactly the whole-text write (libdeflate for gzip).
        const fs::path written = writeFileContents(path_, text_, compress_);
        text_ = std::string();
        return written;
    }
    if (!text_.empty()) writePiece();
    if (gzip_) {
        gzip_->close();
    } else {
        plain_->close();
    }
    text_ = std::string();
    return target_;
}

} // namespace rbm::io

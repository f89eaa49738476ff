#include "GzipOutputFile.hpp"

#include <zlib.h>

#include <algorithm>
#include <stdexcept>

namespace rbm::io {

namespace fs = std::filesystem;

struct GzipOutputFile::Stream {
    z_stream z{};
    bool open = false;
};

GzipOutputFile::GzipOutputFile(fs::path file)
    : file_(std::move(file)), out_(file_), stream_(std::make_unique<Stream>()), buffer_(std::size_t{1} << 17, '\0')
{
    // 16 + MAX_WBITS: a gzip header and trailer around the deflate stream, as gzopen writes.
    if (deflateInit2(&stream_->z, 1, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
        throw std::runtime_error("cannot initialise zlib to write " + file_.string());
    }
    stream_->open = true;
}

GzipOutputFile::~GzipOutputFile()
{
    if (stream_->open) deflateEnd(&stream_->z);
}

void GzipOutputFile::deflateAll(std::string_view bytes, bool finish)
{
    z_stream& z = stream_->z;
    std::size_t consumed = 0;
    for (;;) {
        // zlib counts in 32 bits: at most 1 GiB of input per call.
        if (z.avail_in == 0 && consumed < bytes.size()) {
            const std::size_t chunk = std::min<std::size_t>(bytes.size() - consumed, std::size_t{1} << 30);
            z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data() + consumed));
            z.avail_in = static_cast<uInt>(chunk);
            consumed += chunk;
        }
        const bool lastInput = consumed == bytes.size();
        z.next_out = reinterpret_cast<Bytef*>(buffer_.data());
        z.avail_out = static_cast<uInt>(buffer_.size());
        const int status = deflate(&z, finish && lastInput ? Z_FINISH : Z_NO_FLUSH);
        if (status != Z_OK && status != Z_STREAM_END && status != Z_BUF_ERROR) {
            throw std::runtime_error("zlib failed to compress " + file_.string());
        }
        out_.write(std::string_view(buffer_.data(), buffer_.size() - z.avail_out));
        if (finish) {
            if (status == Z_STREAM_END) return;
        } else if (lastInput && z.avail_in == 0 && z.avail_out != 0) {
            // All input taken and the output buffer not filled: nothing pending for now
            // (zlib keeps what it has not emitted yet until more input or Z_FINISH).
            return;
        }
    }
}

void GzipOutputFile::write(std::string_view bytes)
{
    if (!bytes.empty()) deflateAll(bytes, false);
}

void GzipOutputFile::close()
{
    deflateAll({}, true);
    deflateEnd(&stream_->z);
    stream_->open = false;
    out_.close();
}

} // namespace rbm::io

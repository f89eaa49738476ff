#include "CompressedFile.hpp"

#include "InputError.hpp"
#include "WholeFile.hpp"

#include <zlib.h>

#include <algorithm>
#include <stdexcept>

namespace rbm::io {

namespace fs = std::filesystem;

namespace {

fs::path withGzSuffix(const fs::path& path)
{
    return fs::path(path.string() + ".gz");
}

bool looksGzipped(const std::string& bytes)
{
    return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f && static_cast<unsigned char>(bytes[1]) == 0x8b;
}

std::string gunzip(const std::string& compressed, const fs::path& path)
{
    z_stream stream{};
    // 16 + MAX_WBITS: expect a gzip header (not raw zlib).
    if (inflateInit2(&stream, 16 + MAX_WBITS) != Z_OK) throw InputError(path.string(), 0, "cannot initialise zlib");
    stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
    stream.avail_in = static_cast<uInt>(compressed.size());

    std::string out;
    out.resize(std::max<std::size_t>(compressed.size() * 4, 1 << 16));
    int status = Z_OK;
    while (status != Z_STREAM_END) {
        if (stream.total_out >= out.size()) out.resize(out.size() * 2);
        stream.next_out = reinterpret_cast<Bytef*>(out.data() + stream.total_out);
        stream.avail_out = static_cast<uInt>(out.size() - stream.total_out);
        status = inflate(&stream, Z_NO_FLUSH);
        if (status == Z_STREAM_END) break;
        if (status != Z_OK && !(status == Z_BUF_ERROR && stream.avail_out == 0)) {
            std::string reason = stream.msg ? stream.msg : "unexpected end of data";
            inflateEnd(&stream);
            throw InputError(path.string(), 0, "corrupt gzip stream (" + reason + ")");
        }
        if (status == Z_OK && stream.avail_in == 0 && stream.avail_out != 0) {
            inflateEnd(&stream);
            throw InputError(path.string(), 0, "corrupt gzip stream (truncated)");
        }
    }
    out.resize(stream.total_out);
    inflateEnd(&stream);
    return out;
}

// Writes `contents` to `target` as a gzip stream, compressed piece by piece into a buffer that
// goes to the file whenever it is full: the file grows as gzwrite's did, without a second copy
// of the data in memory, and every write is reported with the OS reason by OutputFile
// (gzwrite does not keep errno).
// Level 1 (zlib's fastest), not OpenFOAM's default 6: any level reads back the same.
// On the 40k-node airfoil (81 280 points) level 6 took 0.19 s for the ascii
// pointDisplacement and 0.075 s for the binary points of every written time, half of an
// rbmMoveMesh step; level 1 takes 0.026 s and 0.040 s, for files 10 % (ascii) and 0.7 %
// (binary: doubles hardly compress) larger.
void writeGzip(const fs::path& target, std::string_view contents)
{
    OutputFile out(target);
    z_stream stream{};
    // 16 + MAX_WBITS: a gzip header and trailer around the deflate stream, as gzopen writes.
    if (deflateInit2(&stream, 1, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
        throw std::runtime_error("cannot initialise zlib to write " + target.string());
    }
    std::string buffer(1 << 17, '\0');
    std::size_t consumed = 0;
    int status = Z_OK;
    try {
        while (status != Z_STREAM_END) {
            // zlib counts in 32 bits: at most 1 GiB of input per call.
            if (stream.avail_in == 0 && consumed < contents.size()) {
                const std::size_t chunk = std::min<std::size_t>(contents.size() - consumed, 1u << 30);
                stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(contents.data() + consumed));
                stream.avail_in = static_cast<uInt>(chunk);
                consumed += chunk;
            }
            stream.next_out = reinterpret_cast<Bytef*>(buffer.data());
            stream.avail_out = static_cast<uInt>(buffer.size());
            status = deflate(&stream, consumed == contents.size() ? Z_FINISH : Z_NO_FLUSH);
            if (status != Z_OK && status != Z_STREAM_END && status != Z_BUF_ERROR) {
                throw std::runtime_error("zlib failed to compress " + target.string());
            }
            out.write(std::string_view(buffer.data(), buffer.size() - stream.avail_out));
        }
    } catch (...) {
        deflateEnd(&stream);
        throw;
    }
    deflateEnd(&stream);
    out.close();
}

// fs::exists without the error_code throws std::filesystem_error for names the system
// refuses ("File name too long", a component that is not a folder): found by fuzzing, through
// `#include` of such a name. Any such name is treated as absent.
bool existsQuietly(const fs::path& path)
{
    std::error_code error;
    return fs::exists(path, error) && !error;
}

} // namespace

fs::path resolveMaybeCompressed(const fs::path& path)
{
    if (existsQuietly(path)) return path;
    if (existsQuietly(withGzSuffix(path))) return withGzSuffix(path);
    throw InputError(path.string(), 0, "file not found (looked for " + path.string() + " and " + withGzSuffix(path).string() + ")");
}

bool existsMaybeCompressed(const fs::path& path)
{
    return existsQuietly(path) || existsQuietly(withGzSuffix(path));
}

std::string readFileContents(const fs::path& path)
{
    // Regular files only (found by fuzzing, through `#include "/"` and `#include "/dev/zero"`):
    // a folder reports a huge size and made the read below allocate it (std::bad_alloc);
    // devices read as empty or never end, FIFOs block.
    std::error_code statusError;
    const fs::file_status status = fs::status(path, statusError);
    if (!statusError && fs::exists(status) && !fs::is_regular_file(status)) {
        throw InputError(path.string(), 0,
                         std::string("cannot read ") + (fs::is_directory(status) ? "a folder" : "a device, FIFO or socket") +
                             " as a file (expected a regular file)");
    }
    const std::string bytes = readWholeFile(path);
    if (looksGzipped(bytes)) return gunzip(bytes, path);
    if (path.extension() == ".gz") throw InputError(path.string(), 0, "file name ends in .gz but the content is not a gzip stream");
    return bytes;
}

fs::path writeFileContents(const fs::path& path, std::string_view contents, bool compress)
{
    if (!compress) {
        writeWholeFile(path, contents);
        return path;
    }
    const fs::path target = withGzSuffix(path);
    writeGzip(target, contents);
    return target;
}

} // namespace rbm::io

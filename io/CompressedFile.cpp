#include "CompressedFile.hpp"

#include "GzipOutputFile.hpp"
#include "InputError.hpp"
#include "WholeFile.hpp"

#include <libdeflate.h>
#include <zlib.h>

#include <algorithm>
#include <limits>
#include <optional>
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

// libdeflate (about twice zlib's speed) for the common case: one gzip member whose trailer
// gives the size (the size modulo 2^32, so files of 4 GiB and more fail here). Anything
// else — several members, a corrupt or truncated stream — returns nullopt and goes to zlib
// below, which reads it or says what is wrong.
std::optional<std::string> gunzipOneMember(const std::string& compressed)
{
    if (compressed.size() < 18) return std::nullopt;
    const auto* trailer = reinterpret_cast<const unsigned char*>(compressed.data() + compressed.size() - 4);
    const std::size_t size = static_cast<std::size_t>(trailer[0]) | static_cast<std::size_t>(trailer[1]) << 8 |
                             static_cast<std::size_t>(trailer[2]) << 16 | static_cast<std::size_t>(trailer[3]) << 24;
    // A deflate stream expands at most 1032 times: a larger claimed size is not this member's.
    if (size / 1032 > compressed.size()) return std::nullopt;
    libdeflate_decompressor* decompressor = libdeflate_alloc_decompressor();
    if (!decompressor) return std::nullopt;
    std::string out(size, '\0');
    std::size_t consumed = 0;
    std::size_t produced = 0;
    const libdeflate_result result = libdeflate_gzip_decompress_ex(decompressor, compressed.data(), compressed.size(),
                                                                   out.data(), out.size(), &consumed, &produced);
    libdeflate_free_decompressor(decompressor);
    if (result != LIBDEFLATE_SUCCESS || consumed != compressed.size() || produced != size) return std::nullopt;
    return out;
}

std::string gunzip(const std::string& compressed, const fs::path& path)
{
    if (std::optional<std::string> whole = gunzipOneMember(compressed)) return std::move(*whole);

    z_stream stream{};
    // 16 + MAX_WBITS: expect a gzip header (not raw zlib).
    if (inflateInit2(&stream, 16 + MAX_WBITS) != Z_OK) throw InputError(path.string(), 0, "cannot initialise zlib");
    stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
    stream.avail_in = static_cast<uInt>(compressed.size());

    std::string out;
    out.resize(std::max<std::size_t>(compressed.size() * 4, 1 << 16));
    // Concatenated gzip members (`gzip a >> f; gzip b >> f`) are one file, as gzread reads
    // them: after a member, another gzip header starts the next (anything else after the
    // last member is ignored, as gzread does).
    std::size_t earlierMembers = 0;   // bytes out of the members before the current one
    int status = Z_OK;
    while (status != Z_STREAM_END) {
        if (earlierMembers + stream.total_out >= out.size()) out.resize(out.size() * 2);
        stream.next_out = reinterpret_cast<Bytef*>(out.data() + earlierMembers + stream.total_out);
        stream.avail_out = static_cast<uInt>(std::min<std::size_t>(out.size() - earlierMembers - stream.total_out,
                                                                   std::numeric_limits<uInt>::max()));
        status = inflate(&stream, Z_NO_FLUSH);
        if (status == Z_STREAM_END) {
            if (stream.avail_in >= 2 && stream.next_in[0] == 0x1f && stream.next_in[1] == 0x8b) {
                earlierMembers += stream.total_out;
                inflateReset(&stream);
                status = Z_OK;
                continue;
            }
            break;
        }
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
    out.resize(earlierMembers + stream.total_out);
    inflateEnd(&stream);
    return out;
}

// Writes `contents` to `target` as one gzip member (what gzopen/gzwrite and OpenFOAM's
// gzstream write, and read back). Every write is reported with the OS reason by OutputFile
// (gzwrite does not keep errno).
//
// Up to `oneShotLimit` bytes: libdeflate at level 1, the whole file compressed at once into
// one buffer (contents + 0.1 %) and written. libdeflate compresses a whole buffer in about
// half of zlib's time at the same level, for files of about the same size; the price is the
// buffer, a second copy of the file in memory (callers that produce a large file piece by
// piece use TextFileWriter instead, which comes here for files of one piece only).
// Beyond it (meshes of 10^7 points and more): zlib level 1 through GzipOutputFile, 128 KiB of
// buffer, without a second copy of the data in memory.
void writeGzip(const fs::path& target, std::string_view contents, std::size_t oneShotLimit)
{
    if (contents.size() > oneShotLimit) {
        GzipOutputFile out(target);
        out.write(contents);
        out.close();
        return;
    }
    libdeflate_compressor* compressor = libdeflate_alloc_compressor(1);
    if (!compressor) throw std::runtime_error("cannot initialise libdeflate to write " + target.string());
    std::string buffer(libdeflate_gzip_compress_bound(compressor, contents.size()), '\0');
    const std::size_t size =
        libdeflate_gzip_compress(compressor, contents.data(), contents.size(), buffer.data(), buffer.size());
    libdeflate_free_compressor(compressor);
    if (size == 0) throw std::runtime_error("libdeflate failed to compress " + target.string());
    // To the file in pieces, as GzipOutputFile does (and as gzwrite did).
    OutputFile out(target);
    constexpr std::size_t piece = std::size_t{1} << 17;
    for (std::size_t offset = 0; offset < size; offset += piece)
        out.write(std::string_view(buffer.data() + offset, std::min(piece, size - offset)));
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
    return writeFileContents(path, contents, compress, oneShotGzipLimit);
}

fs::path writeFileContents(const fs::path& path, std::string_view contents, bool compress, std::size_t oneShotLimit)
{
    if (!compress) {
        writeWholeFile(path, contents);
        return path;
    }
    const fs::path target = withGzSuffix(path);
    writeGzip(target, contents, oneShotLimit);
    return target;
}

} // namespace rbm::io

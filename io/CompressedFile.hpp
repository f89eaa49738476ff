#pragma once
// Whole-file reading and writing with transparent gzip, as OpenFOAM does:
// a file "points" may be stored as "points.gz".

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace rbm::io {

// The file to read for `path`: `path` itself if it exists, else `path.gz` if that exists.
// Throws rbm::InputError naming both when neither exists.
std::filesystem::path resolveMaybeCompressed(const std::filesystem::path& path);

// True when a file of that name exists, plain or as .gz.
bool existsMaybeCompressed(const std::filesystem::path& path);

// Reads the whole file (decompressing when its name ends in .gz or its content starts with
// the gzip magic bytes). Throws rbm::InputError naming the file for a missing file or a
// corrupt gzip stream.
std::string readFileContents(const std::filesystem::path& path);

// Writes `contents` to `path`, gzip-compressed when `compress` is true (then ".gz" is
// appended to the name). Returns the path written. Throws std::runtime_error on failure.
// For the text of a large file produced piece by piece, TextFileWriter.hpp writes the same
// bytes without holding the whole text (or its compressed copy) in memory.
std::filesystem::path writeFileContents(const std::filesystem::path& path, std::string_view contents, bool compress);

// Up to this many bytes a gzip file is compressed in one piece (libdeflate, fast; a buffer of
// the compressed size), beyond it as a stream (zlib through GzipOutputFile, 128 KiB of
// buffer): the same format.
inline constexpr std::size_t oneShotGzipLimit = std::size_t{256} << 20;
// As above with another limit (tests: the streaming path on small files).
std::filesystem::path writeFileContents(const std::filesystem::path& path, std::string_view contents, bool compress,
                                        std::size_t oneShotLimit);

} // namespace rbm::io

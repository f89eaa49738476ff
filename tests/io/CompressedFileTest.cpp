#include "CompressedFile.hpp"
#include "InputError.hpp"

#include <gtest/gtest.h>

#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace fs = std::filesystem;

TEST(CompressedFile, GzipRoundTripGivesTheSameBytes)
{
    const fs::path dir = fs::temp_directory_path() / "rbmCompressedFileTest";
    fs::create_directories(dir);
    std::string text;
    for (int i = 0; i < 100000; ++i) text += std::to_string(i) + "\n";
    const fs::path written = rbm::io::writeFileContents(dir / "points", text, true);
    EXPECT_EQ(written.filename(), "points.gz");
    EXPECT_LT(fs::file_size(written), text.size() / 2);
    EXPECT_EQ(rbm::io::resolveMaybeCompressed(dir / "points"), written);
    EXPECT_EQ(rbm::io::readFileContents(written), text);
    fs::remove_all(dir);
}

TEST(CompressedFile, CorruptGzipStreamNamesTheFile)
{
    const fs::path dir = fs::temp_directory_path() / "rbmCompressedFileTestCorrupt";
    fs::create_directories(dir);
    std::string text(5000, 'a');
    const fs::path written = rbm::io::writeFileContents(dir / "faces", text, true);
    std::string bytes;
    {
        std::ifstream in(written, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    bytes.resize(bytes.size() / 2);   // truncated stream
    {
        std::ofstream out(written, std::ios::binary | std::ios::trunc);
        out << bytes;
    }
    try {
        rbm::io::readFileContents(written);
        FAIL() << "expected an InputError";
    } catch (const rbm::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("faces.gz"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("gzip"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

namespace {

std::string readBytes(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

// What zlib's own gzip reader (gzopen/gzread, as OpenFOAM's gzstream reads) makes of a file.
std::string gzreadAll(const fs::path& path)
{
    gzFile file = gzopen(path.c_str(), "rb");
    if (!file) return "<cannot open>";
    std::string out;
    char buffer[1 << 14];
    int n = 0;
    while ((n = gzread(file, buffer, sizeof buffer)) > 0) out.append(buffer, static_cast<std::size_t>(n));
    gzclose(file);
    return out;
}

// Binary doubles and ascii numbers, as points and pointDisplacement files hold them.
std::string sampleContents()
{
    std::string text = "FoamFile { format binary; }\n8000\n(";
    for (int i = 0; i < 8000; ++i) {
        const double value = std::sin(0.001 * i) * 1e3 + i;
        text.append(reinterpret_cast<const char*>(&value), sizeof value);
    }
    text += ")\n";
    for (int i = 0; i < 20000; ++i) text += "(" + std::to_string(0.25 * i) + " 0 " + std::to_string(-i) + ")\n";
    return text;
}

} // namespace

TEST(CompressedFile, OneShotAndStreamingWritesAreGzipFilesZlibReads)
{
    // Below the one-shot limit (libdeflate) and above it (zlib, streaming): both are single
    // gzip members that zlib's gzread and rbm's reader return byte for byte, compressed.
    const fs::path dir = fs::temp_directory_path() / "rbmCompressedFileTestPaths";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string contents = sampleContents();
    const fs::path oneShot = rbm::io::writeFileContents(dir / "oneShot", contents, true);
    const fs::path streamed = rbm::io::writeFileContents(dir / "streamed", contents, true, 1000);
    for (const fs::path& written : {oneShot, streamed}) {
        const std::string bytes = readBytes(written);
        ASSERT_GE(bytes.size(), 18u);
        EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0x1f) << written;
        EXPECT_EQ(static_cast<unsigned char>(bytes[1]), 0x8b) << written;
        EXPECT_EQ(static_cast<unsigned char>(bytes[2]), 8) << written << ": deflate";
        EXPECT_LT(bytes.size(), contents.size() / 2) << written;
        EXPECT_EQ(gzreadAll(written), contents) << written;
        EXPECT_EQ(rbm::io::readFileContents(written), contents) << written;
    }
    // An empty file too.
    const fs::path empty = rbm::io::writeFileContents(dir / "empty", "", true);
    EXPECT_EQ(gzreadAll(empty), "");
    EXPECT_EQ(rbm::io::readFileContents(empty), "");
    fs::remove_all(dir);
}

TEST(CompressedFile, TwoGzipMembersReadAsOneFile)
{
    // A file of two concatenated gzip members (gzip a >> f; gzip b >> f): gzread returns both
    // parts, so must rbm (the fast single-member path gives way to zlib).
    const fs::path dir = fs::temp_directory_path() / "rbmCompressedFileTestMembers";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string first = sampleContents();
    const std::string second = "second member\n";
    const std::string joined = readBytes(rbm::io::writeFileContents(dir / "a", first, true)) +
                               readBytes(rbm::io::writeFileContents(dir / "b", second, true));
    {
        std::ofstream out(dir / "both.gz", std::ios::binary);
        out << joined;
    }
    EXPECT_EQ(gzreadAll(dir / "both.gz"), first + second);
    EXPECT_EQ(rbm::io::readFileContents(dir / "both.gz"), first + second);
    fs::remove_all(dir);
}

TEST(CompressedFile, MissingFileNamesBothCandidates)
{
    try {
        rbm::io::resolveMaybeCompressed("/nonexistent/rbm/points");
        FAIL() << "expected an InputError";
    } catch (const rbm::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("points.gz"), std::string::npos);
    }
}

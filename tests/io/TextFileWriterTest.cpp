#include "CompressedFile.hpp"
#include "ScratchFiles.hpp"
#include "TextFileWriter.hpp"

#include <gtest/gtest.h>

#include <zlib.h>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace fs = std::filesystem;
using rbm::io::TextFileWriter;
using rbm::test::readText;
using rbm::test::TempDir;

namespace {

// About 150 kB of lines and one 20 kB block of bytes of every value (as binary list data).
std::string lineOf(int i)
{
    return "(" + std::to_string(i * 0.001) + " " + std::to_string(-i) + " 1e-07)\n";
}

std::string rawBlock()
{
    std::string block;
    for (int i = 0; i < 20000; ++i) block += static_cast<char>(i * 7 % 256);
    return block;
}

// Writes the text above through a writer with pieces of `pieceSize` bytes, lines one at a
// time and the block through append(); returns the expected whole text in `whole`.
fs::path writeInPieces(const fs::path& path, bool compress, std::size_t pieceSize, std::string& whole)
{
    TextFileWriter writer(path, compress, pieceSize);
    whole.clear();
    for (int i = 0; i < 6000; ++i) {
        const std::string line = lineOf(i);
        writer.text() += line;
        whole += line;
        writer.pieceDone();
        if (i == 3000) {
            const std::string block = rawBlock();
            writer.append(block);
            whole += block;
        }
    }
    writer.text() += "end\n";
    whole += "end\n";
    return writer.finish();
}

// One gzip member exactly: zlib's inflate (gzip wrapper) reaches the end of its stream and
// leaves no input behind (a second member would be left over).
bool isOneGzipMember(const std::string& bytes, std::string& out)
{
    z_stream stream{};
    if (inflateInit2(&stream, 16 + MAX_WBITS) != Z_OK) return false;
    out.assign(bytes.size() * 20 + 1024, '\0');
    stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
    stream.avail_in = static_cast<uInt>(bytes.size());
    stream.next_out = reinterpret_cast<Bytef*>(out.data());
    stream.avail_out = static_cast<uInt>(out.size());
    const int status = inflate(&stream, Z_FINISH);
    out.resize(stream.total_out);
    const bool one = status == Z_STREAM_END && stream.avail_in == 0;
    inflateEnd(&stream);
    return one;
}

} // namespace

TEST(TextFileWriter, TextWrittenInManyPiecesIsTheWholeTextWrite)
{
    // The same text through pieces of 1000 bytes (hundreds of them, the block larger than a
    // piece) and through writeFileContents in one go: the same bytes, plain and decompressed.
    TempDir dir("pieces");
    for (const bool compress : {false, true}) {
        SCOPED_TRACE(compress ? "gzip" : "plain");
        std::string whole;
        const fs::path streamed = writeInPieces(dir.path() / "streamed", compress, 1000, whole);
        const fs::path oneGo = rbm::io::writeFileContents(dir.path() / "oneGo", whole, compress);
        EXPECT_EQ(streamed.filename(), compress ? "streamed.gz" : "streamed");
        EXPECT_GT(whole.size(), 100u * 1000);
        EXPECT_EQ(rbm::io::readFileContents(streamed), rbm::io::readFileContents(oneGo));
        EXPECT_EQ(rbm::io::readFileContents(streamed), whole);
        if (!compress) {
            EXPECT_EQ(readText(streamed), whole);
        }
    }
}

TEST(TextFileWriter, GzipWrittenInPiecesIsOneStandardGzipMember)
{
    // What OpenFOAM's gzstream and gunzip expect: gzip magic, deflate, one member.
    TempDir dir("member");
    std::string whole;
    const fs::path written = writeInPieces(dir.path() / "points", true, 1000, whole);
    const std::string bytes = readText(written);
    ASSERT_GE(bytes.size(), 18u);
    EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0x1f);
    EXPECT_EQ(static_cast<unsigned char>(bytes[1]), 0x8b);
    EXPECT_EQ(static_cast<unsigned char>(bytes[2]), 8);
    EXPECT_LT(bytes.size(), whole.size() / 2);
    std::string inflated;
    EXPECT_TRUE(isOneGzipMember(bytes, inflated));
    EXPECT_EQ(inflated, whole);
}

TEST(TextFileWriter, TextOfOnePieceIsExactlyTheWholeTextWrite)
{
    // Below the piece size the writer is writeFileContents itself: the same compressed bytes.
    TempDir dir("onePiece");
    std::string whole;
    const fs::path streamed = writeInPieces(dir.path() / "streamed", true, TextFileWriter::defaultPieceSize, whole);
    const fs::path oneGo = rbm::io::writeFileContents(dir.path() / "oneGo", whole, true);
    EXPECT_EQ(readText(streamed), readText(oneGo));
}

TEST(TextFileWriter, EmptyTextGivesAnEmptyFile)
{
    TempDir dir("empty");
    for (const bool compress : {false, true}) {
        TextFileWriter writer(dir.path() / "empty", compress, 1);
        const fs::path written = writer.finish();
        EXPECT_EQ(rbm::io::readFileContents(written), "");
    }
}

TEST(TextFileWriter, WriterAbandonedByAnExceptionLeavesNoFile)
{
    TempDir dir("abandoned");
    for (const bool compress : {false, true}) {
        try {
            TextFileWriter writer(dir.path() / "field", compress, 100);
            for (int i = 0; i < 1000; ++i) {
                writer.text() += lineOf(i);
                writer.pieceDone();
            }
            throw std::runtime_error("solver failed");
        } catch (const std::runtime_error&) {
        }
        EXPECT_FALSE(fs::exists(dir.path() / "field"));
        EXPECT_FALSE(fs::exists(dir.path() / "field.gz"));
    }
}

TEST(TextFileWriter, UnwritableFolderNamesTheFile)
{
    TempDir dir("unwritable");
    TextFileWriter writer(dir.path() / "missing" / "field", true, 10);
    writer.text() += std::string(100, 'x');
    try {
        writer.pieceDone();
        FAIL() << "no error";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find("cannot create " + (dir.path() / "missing" / "field.gz").string()),
                  std::string::npos)
            << error.what();
    }
}

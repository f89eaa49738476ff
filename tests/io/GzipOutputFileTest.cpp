#include "CompressedFile.hpp"
#include "GzipOutputFile.hpp"
#include "ScratchFiles.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace fs = std::filesystem;
using rbm::io::GzipOutputFile;
using rbm::test::readText;
using rbm::test::TempDir;

TEST(GzipOutputFile, WritesInPiecesReadBackAsTheirConcatenation)
{
    // Pieces of every size (empty, one byte, several output buffers' worth of incompressible
    // bytes): one gzip member holding their concatenation.
    TempDir dir("pieces");
    std::string whole;
    {
        GzipOutputFile out(dir.path() / "file.gz");
        std::string noise;
        unsigned state = 12345;
        for (int i = 0; i < 600000; ++i) {
            state = state * 1103515245u + 12345u;
            noise += static_cast<char>(state >> 24);
        }
        for (const std::string& piece : {std::string(), std::string("x"), noise, std::string(300000, 'a'), noise}) {
            out.write(piece);
            whole += piece;
        }
        out.close();
    }
    const std::string bytes = readText(dir.path() / "file.gz");
    ASSERT_GE(bytes.size(), 18u);
    EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0x1f);
    EXPECT_EQ(static_cast<unsigned char>(bytes[1]), 0x8b);
    EXPECT_EQ(rbm::io::readFileContents(dir.path() / "file.gz"), whole);
}

TEST(GzipOutputFile, DestroyedWithoutCloseRemovesTheFile)
{
    TempDir dir("abandoned");
    try {
        GzipOutputFile out(dir.path() / "file.gz");
        out.write(std::string(1 << 20, 'z'));
        throw std::runtime_error("stop");
    } catch (const std::runtime_error&) {
    }
    EXPECT_FALSE(fs::exists(dir.path() / "file.gz"));
}

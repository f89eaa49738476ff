#include "CompressedFile.hpp"
#include "InputError.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

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

TEST(CompressedFile, MissingFileNamesBothCandidates)
{
    try {
        rbm::io::resolveMaybeCompressed("/nonexistent/rbm/points");
        FAIL() << "expected an InputError";
    } catch (const rbm::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("points.gz"), std::string::npos);
    }
}

// Replays every committed fuzz input -- the seed corpora fuzz/corpus/<target>/ and the inputs
// that once crashed, hung or leaked, fuzz/regressions/<target>/ -- through the entry function
// of its fuzz target (fuzz/FuzzEntryPoints.hpp), in the normal build: each input must either
// be read or raise rbm::InputError, quickly. Then one test per bug fuzzing found, checking the
// error the reader now gives (fuzz/README.md lists the findings).

#include "ScratchFiles.hpp"
#include "../fuzz/FuzzEntryPoints.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <functional>
#include <sstream>

namespace fs = std::filesystem;
using rbm::InputError;

namespace {


// Every file of fuzz/corpus/<target> and fuzz/regressions/<target>, sorted.
std::vector<fs::path> inputsOf(const std::string& target)
{
    std::vector<fs::path> inputs;
    for (const char* kind : {"corpus", "regressions"}) {
        const fs::path folder = fs::path(RBM_FUZZ_DIR) / kind / target;
        if (!fs::is_directory(folder)) continue;
        for (const auto& file : fs::recursive_directory_iterator(folder)) {
            if (file.is_regular_file()) inputs.push_back(file.path());
        }
    }
    std::sort(inputs.begin(), inputs.end());
    return inputs;
}

// Runs every input of `target` through `entry`; returns how many were read without error.
std::size_t replay(const std::string& target, const std::function<void(std::string_view)>& entry)
{
    const std::vector<fs::path> inputs = inputsOf(target);
    EXPECT_GE(inputs.size(), 3u) << "no fuzz inputs found for " << target << " under " << RBM_FUZZ_DIR;
    std::size_t accepted = 0;
    for (const fs::path& input : inputs) {
        const std::string bytes = rbm::test::readText(input);
        const auto start = std::chrono::steady_clock::now();
        try {
            entry(bytes);
            ++accepted;
        } catch (const InputError&) {
            // bad input, reported as it should be
        } catch (const std::exception& error) {
            ADD_FAILURE() << input << ": an exception other than rbm::InputError escaped: " << error.what();
        }
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        // libFuzzer's -timeout; ordinary inputs take milliseconds, the worst committed ones ~3 s under ASan.
        EXPECT_LT(seconds, 10.0) << input << " took " << seconds << " s (a hang fuzzing found?)";
    }
    return accepted;
}

// The InputError `action` raises (a failure when it raises none or another exception).
template <class Action>
std::string inputErrorOf(Action action)
{
    try {
        action();
    } catch (const InputError& error) {
        return error.what();
    } catch (const std::exception& error) {
        ADD_FAILURE() << "expected rbm::InputError, got another exception: " << error.what();
        return {};
    }
    ADD_FAILURE() << "expected rbm::InputError, but the input was accepted";
    return {};
}

} // namespace

// The valid seeds (files OpenFOAM wrote) must be read; every input must be read or rejected.
TEST(FuzzRegression, DictionaryInputsAreReadOrRaiseInputError)
{
    EXPECT_GE(replay("dictionaryFuzzer", rbm::fuzz::parseDictionary), 10u);
}

TEST(FuzzRegression, AsciiListInputsAreReadOrRaiseInputError)
{
    EXPECT_GE(replay("asciiListFuzzer", rbm::fuzz::readListFile), 6u);
}

TEST(FuzzRegression, BinaryListInputsAreReadOrRaiseInputError)
{
    EXPECT_GE(replay("binaryListFuzzer", rbm::fuzz::readBinaryListFile), 8u);
}

TEST(FuzzRegression, PointFieldInputsAreReadOrRaiseInputError)
{
    EXPECT_GE(replay("pointFieldFuzzer", rbm::fuzz::readPointField), 3u);
}

TEST(FuzzRegression, PolyMeshInputsAreReadOrRaiseInputError)
{
    EXPECT_GE(replay("polyMeshFuzzer", rbm::fuzz::readPolyMeshFolder), 6u);
}

// ---- One test per bug fuzzing found ------------------------------------------------------

// Finding 1: a bare-word keyword with expression characters that is no valid expression
// (`?a$`) was written in quotes, and the quoted keyword was then rejected as an invalid
// expression. Keywords that would read back as something else were written bare.
TEST(FuzzFindings, WriterQuotesKeywordsOnlyWhenTheyMustBeQuoted)
{
    using rbm::io::keywordNeedsQuotes;
    EXPECT_FALSE(keywordNeedsQuotes("inlet"));
    EXPECT_FALSE(keywordNeedsQuotes("div(phi,U)"));      // a literal OpenFOAM keyword stays bare
    EXPECT_FALSE(keywordNeedsQuotes("?a$"));             // no valid expression: bare, as it was read
    EXPECT_FALSE(keywordNeedsQuotes("*a"));
    EXPECT_TRUE(keywordNeedsQuotes(".*Wall"));           // an expression: quoted, as OpenFOAM needs
    EXPECT_TRUE(keywordNeedsQuotes("(inlet|outlet)"));
    EXPECT_TRUE(keywordNeedsQuotes(""));
    EXPECT_TRUE(keywordNeedsQuotes("two words"));
    EXPECT_TRUE(keywordNeedsQuotes("12"));               // bare, a number
    EXPECT_TRUE(keywordNeedsQuotes("#remove"));          // bare, a directive
    EXPECT_TRUE(keywordNeedsQuotes("$x"));               // bare, a variable
    EXPECT_TRUE(keywordNeedsQuotes("a//b"));             // bare, a comment after "a"
    EXPECT_TRUE(keywordNeedsQuotes("FoamFile"));         // bare and first, a header
    EXPECT_TRUE(keywordNeedsQuotes("it's"));             // OpenFOAM words hold no quotes
    EXPECT_FALSE(keywordNeedsQuotes("it's(?"));          // ... but quoted it would be an invalid expression

    const rbm::io::Dictionary parsed = rbm::io::Dictionary::parseText("?a$ 1;\n\"12\" 2;\n\"#x\" 3;\n\"a//b\" 4;\n", "keywords");
    std::string written;
    rbm::io::appendDictionaryEntries(written, parsed, 0, 6);
    const rbm::io::Dictionary reparsed = rbm::io::Dictionary::parseText(written, "written");
    EXPECT_EQ(reparsed.keywords(), (std::vector<std::string>{"?a$", "12", "#x", "a//b"})) << written;
    EXPECT_EQ(reparsed.get<rbm::Label>("a//b"), 4);
}

// Finding 11: the writer puts no space before ')'; after a word with an unclosed '(' ("b("
// from `(b( )`) the word swallowed the ')' when read again, leaving the list unclosed.
TEST(FuzzFindings, WriterKeepsTheClosingParenthesisApartFromAWordThatOpensOne)
{
    const rbm::io::Dictionary parsed = rbm::io::Dictionary::parseText("a (b( );\nc (div(phi,U) x);\n", "words");
    std::string written;
    rbm::io::appendDictionaryEntries(written, parsed, 0, 6);
    EXPECT_NE(written.find("(b( )"), std::string::npos) << written;
    EXPECT_NE(written.find("(div(phi,U) x)"), std::string::npos) << written;   // balanced words keep the compact form
    const rbm::io::Dictionary reparsed = rbm::io::Dictionary::parseText(written, "written");
    EXPECT_EQ(reparsed.lookup("a").valueText(), parsed.lookup("a").valueText());
    EXPECT_EQ(reparsed.lookup("c").valueText(), parsed.lookup("c").valueText());
}

namespace {

// A dictionary file `name` with `text` in a fresh scratch folder.
fs::path scratchFile(const std::string& name, const std::string& text)
{
    const fs::path folder = fs::path(testing::TempDir()) / "rbmFuzzRegressionTest";
    fs::create_directories(folder);
    const fs::path file = folder / name;
    std::ofstream(file, std::ios::binary) << text;
    return file;
}

// The fixture mesh of the point-field fuzz target (30 points, 5 patches).
const rbm::PolyMesh& pointFieldMesh()
{
    static const rbm::PolyMesh mesh =
        rbm::io::readPolyMesh(fs::path(RBM_TEST_DATA_DIR) / "dictionaries" / "pointField" / "ascii" / "constant" / "polyMesh");
    return mesh;
}

// The polyMesh of the point-field fixture copied to a scratch folder, with `file` replaced.
fs::path pointFieldMeshWith(const std::string& file, const std::string& text)
{
    const fs::path source = fs::path(RBM_TEST_DATA_DIR) / "dictionaries" / "pointField" / "ascii" / "constant" / "polyMesh";
    // One folder per test and process: ctest runs the tests of this file in parallel.
    const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
    const fs::path folder = fs::path(testing::TempDir()) /
                            ("rbmFuzzRegressionTestMesh-" + std::string(test ? test->name() : "none") + "-" +
                             std::to_string(::getpid()));
    fs::remove_all(folder);
    fs::create_directories(folder);
    for (const auto& entry : fs::directory_iterator(source)) fs::copy_file(entry.path(), folder / entry.path().filename());
    std::ofstream(folder / file, std::ios::binary | std::ios::trunc) << text;
    return folder;
}

std::string fixtureText(const std::string& file)
{
    return rbm::test::readText(fs::path(RBM_TEST_DATA_DIR) / "dictionaries" / "pointField" / "ascii" / "constant" / "polyMesh" / file);
}

} // namespace

// Finding 2: `#include` of a folder allocated the folder's nonsensical size (std::bad_alloc);
// of /dev/zero read nothing (a FIFO would block). Only regular files are read now.
TEST(FuzzFindings, IncludeOfAFolderOrADeviceIsAnInputError)
{
    const fs::path file = scratchFile("includesFolder", "#include \"/\"\n");
    EXPECT_NE(inputErrorOf([&] { rbm::io::Dictionary::readFile(file); }).find("cannot read a folder as a file"), std::string::npos);
    const fs::path device = scratchFile("includesDevice", "#include \"/dev/zero\"\n");
    const std::string message = inputErrorOf([&] { rbm::io::Dictionary::readFile(device); });
    EXPECT_NE(message.find("/dev/zero"), std::string::npos) << message;
    EXPECT_NE(message.find("a device, FIFO or socket"), std::string::npos) << message;
    EXPECT_NE(inputErrorOf([&] { rbm::io::readFileContents(file.parent_path()); }).find("folder"), std::string::npos);
}

// Finding 3: a name the system refuses ("File name too long") escaped as
// std::filesystem::filesystem_error from #include, and from the polyMesh readers.
TEST(FuzzFindings, IncludeOfATooLongNameIsAFileNotFound)
{
    const std::string name(5000, 'a');
    EXPECT_NE(inputErrorOf([&] { rbm::io::Dictionary::parseText("#include \"" + name + "\"\n", "/tmp/longName"); })
                  .find("cannot find the file"),
              std::string::npos);
    const rbm::io::Dictionary optional = rbm::io::Dictionary::parseText("#includeIfPresent \"" + name + "\"\nx 1;\n", "/tmp/x");
    EXPECT_EQ(optional.get<rbm::Label>("x"), 1);
    EXPECT_FALSE(rbm::io::existsMaybeCompressed(name));
    EXPECT_NE(inputErrorOf([&] { rbm::io::readPolyMesh(name); }).find("polyMesh folder not found"), std::string::npos);
    EXPECT_NE(inputErrorOf([&] { rbm::io::readPolyMeshPoints(name); }).find("not found"), std::string::npos);
}

// Finding 4: std::regex backtracked exponentially ("(a|a)*b" against 40 a's never returned),
// recursed per character of the name and per group of the pattern (stack overflows), built
// automata of 100 000 states for `(a{300}){300}` (seconds), and overflowed a long reading the
// count of `a{2222222222222222222}` (undefined behaviour inside libstdc++).
TEST(FuzzFindings, ExpressionKeywordsMatchWithoutBacktrackingOrDeepRecursion)
{
    // Expressions are tried last defined first: "(a|a)*b" fails on the name before ".*" matches.
    const rbm::io::Dictionary d = rbm::io::Dictionary::parseText("\".*\" 2;\n\"(a|a)*b\" 1;\n", "patterns");
    const auto start = std::chrono::steady_clock::now();
    const rbm::io::Entry* found = d.find(std::string(40, 'a'));
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
    ASSERT_NE(found, nullptr);
    EXPECT_EQ(found->keyword(), ".*");                     // the last matching expression
    const rbm::io::Entry* long100k = d.find(std::string(100000, 'a'));
    ASSERT_NE(long100k, nullptr);
    EXPECT_EQ(long100k->keyword(), ".*");
    EXPECT_EQ(rbm::io::Dictionary::parseText("\"(a|a)*b\" 1;\n", "p").find("aab")->keyword(), "(a|a)*b");

    // Counted repetitions that std::regex would copy into more than 10 000 states, and numbers
    // its compiler reads without an overflow check, are refused before compiling.
    const auto patternError = [](const std::string& pattern) {
        return inputErrorOf([&] { rbm::io::Dictionary::parseText("\"" + pattern + "\" 1;\n", "counts"); });
    };
    EXPECT_NE(patternError("a{2222222222222222222}").find("too large (more than 10000 states)"), std::string::npos);
    EXPECT_NE(patternError("(a{300}){300}").find("too large (more than 10000 states)"), std::string::npos);
    EXPECT_NE(patternError("(a)\\2222222222222222222").find("back-references"), std::string::npos);
    const rbm::io::Dictionary counted = rbm::io::Dictionary::parseText("\"wall[0-9]{1,3}\" 1;\n", "counted");
    EXPECT_NE(counted.find("wall123"), nullptr);
    EXPECT_EQ(counted.find("wall1234"), nullptr);

    const std::string deep = std::string(20000, '(') + std::string(20000, ')');
    EXPECT_NE(inputErrorOf([&] { rbm::io::Dictionary::parseText("\"" + deep + "\" 1;\n", "deep"); }).find("longer than 1024"),
              std::string::npos);
}

// Finding 5: variables that repeat variables doubled the text at every line ("billion
// laughs"): 40 lines asked for terabytes, for tokens and for dictionaries alike.
TEST(FuzzFindings, SubstitutionsThatDoubleAtEveryStepAreAnInputError)
{
    // a_i ($a_(i-1) $a_(i-1)); and d_i { a $d_(i-1); b $d_(i-1); } for i = 1 .. count-1.
    const auto chains = [](int count) {
        std::ostringstream tokens;
        std::ostringstream dictionaries;
        tokens << "a0 (x x);\n";
        dictionaries << "d0 { x 1; }\n";
        for (int i = 1; i < count; ++i) {
            tokens << 'a' << i << " ($a" << i - 1 << " $a" << i - 1 << ");\n";
            dictionaries << 'd' << i << " { a $d" << i - 1 << "; b $d" << i - 1 << "; }\n";
        }
        return std::pair{tokens.str(), dictionaries.str()};
    };
    const auto [tokens, dictionaries] = chains(40);
    EXPECT_NE(inputErrorOf([&] { rbm::io::Dictionary::parseText(tokens, "tokens"); }).find("substitutions copy more than 64 MB"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([&] { rbm::io::Dictionary::parseText(dictionaries, "dicts"); }).find("substitutions copy more than 64 MB"),
              std::string::npos);
    // Ordinary substitution is untouched: a_i holds 2 a_(i-1) and its parentheses, 6 * 2^i - 2 tokens.
    const rbm::io::Dictionary small = rbm::io::Dictionary::parseText(chains(11).first, "small");
    EXPECT_EQ(small.lookup("a10").tokens().size(), 6u * 1024u - 2u);
}

// Finding 6: the size of a uniform list `N{value}` is not bounded by the text: a
// pointDisplacement with `2000000000{(0 0 0)}` asked for 48 GB before its size was checked.
TEST(FuzzFindings, UniformListLargerThanExpectedIsAnInputErrorBeforeAllocation)
{
    const rbm::io::Dictionary d = rbm::io::Dictionary::parseText("v 2000000000{(0 0 0)};\nw 3{(1 2 3)};\n", "uniform");
    auto stream = d.lookup("v").stream();
    EXPECT_NE(inputErrorOf([&] { stream.readVectorList(30); }).find("the size 2000000000 of a vector list is larger than the 30"),
              std::string::npos);
    EXPECT_EQ(d.lookup("w").stream().readVectorList(3).size(), 3u);
    EXPECT_NE(inputErrorOf([&] { d.lookup("w").stream().readVectorList(2); }).find("larger than the 2"), std::string::npos);
    const rbm::io::Dictionary counted = rbm::io::Dictionary::parseText("v 99999999999{0};\n", "count");
    auto hugeCount = counted.lookup("v").stream();
    EXPECT_NE(inputErrorOf([&] { hugeCount.readScalarList(); }).find("larger than the 2147483647"), std::string::npos);

    const fs::path field = scratchFile("pointDisplacement", R"(FoamFile { format ascii; class pointVectorField; }
dimensions [0 1 0 0 0 0 0];
internalField nonuniform List<vector> 2000000000{(0 0 0)};
boundaryField { ".*" { type fixedValue; value uniform (0 0 0); } }
)");
    const std::string message = inputErrorOf([&] { rbm::io::readPointVectorField(field, pointFieldMesh()); });
    EXPECT_NE(message.find("pointDisplacement:3: the size 2000000000 of a vector list is larger than the 30"), std::string::npos)
        << message;
}

// Finding 7: list sizes the tokenizer reads as doubles: 3e125 (spelled as an integer) was
// converted to long long (undefined), and an ascii List<scalar> of 2000000000 was allocated
// before its elements were read.
TEST(FuzzFindings, ListSizesTheTextCannotHoldAreAnInputError)
{
    const std::string huge(130, '3');
    EXPECT_NE(inputErrorOf([&] { rbm::io::Dictionary::parseText("a List<scalar> " + huge + "(1);\n", "huge"); })
                  .find("is larger than 32-bit labels can count"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([&] { rbm::io::Dictionary::parseText("a List<scalar> 2000000000(1 2 3);\n", "packed"); })
                  .find("the size 2000000000 of a List<scalar> is larger than the rest of the file can hold"),
              std::string::npos);
    // A list of 100 or more scalars in 2 bytes each still packs.
    std::string ok = "a List<scalar> 150(";
    for (int i = 0; i < 150; ++i) ok += "1 ";
    const rbm::io::Dictionary packed = rbm::io::Dictionary::parseText(ok + ");\n", "ok");
    EXPECT_EQ(packed.lookup("a").stream().readScalarList().size(), 150u);
}

// Finding 8: an owner label of 2147483647 overflowed cellCount() and asked for an 8 GB
// count of faces per cell.
TEST(FuzzFindings, CellLabelBeyondWhatTheFacesCanMakeIsAnInputError)
{
    std::string owner = fixtureText("owner");
    const std::size_t close = owner.rfind("\n)");
    const std::size_t lastEntry = owner.rfind('\n', close - 1) + 1;
    owner.replace(lastEntry, close - lastEntry, "2147483647");
    const fs::path mesh = pointFieldMeshWith("owner", owner);
    const std::string message = inputErrorOf([&] { rbm::io::readPolyMesh(mesh); });
    EXPECT_NE(message.find("owner cell label 2147483647 is too large: the 48 owner and neighbour entries make at most 12 cells"),
              std::string::npos)
        << message;
}

// Finding 9: `inGroups 2000000000;` (a size without a list) passed the binary size check of
// word lists (0 bytes a word) and reserved room for 2e9 strings.
TEST(FuzzFindings, WordListSizeWithoutItsListIsAnInputError)
{
    std::string boundary = fixtureText("boundary");
    const std::size_t groups = boundary.find("2(movingWalls wall)");
    ASSERT_NE(groups, std::string::npos);
    boundary.replace(groups, std::string("2(movingWalls wall)").size(), "2000000000");
    const fs::path mesh = pointFieldMeshWith("boundary", boundary);
    const std::string message = inputErrorOf([&] { rbm::io::readPolyMesh(mesh); });
    EXPECT_NE(message.find("entry 'inGroups': expected '(' after the size 2000000000 of the list of group names"), std::string::npos)
        << message;
}

// Tests of the OpenFOAM dictionary parser (io/FoamDictionary.hpp): valid syntax with values
// asserted, binary lists, and malformed inputs whose errors must name the file and the line.

#include "CompressedFile.hpp"
#include "FoamDictionary.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using rbm::InputError;
using rbm::Label;
using rbm::Vector3;
using rbm::io::Dictionary;
using rbm::io::Entry;
using rbm::io::FoamFileHeader;

namespace {

fs::path dataPath(const std::string& name)
{
    return fs::path(RBM_TEST_DATA_DIR) / "dictionaries" / name;
}

// A fresh folder under the test temporary directory.
fs::path scratchFolder(const std::string& name)
{
    fs::path folder = fs::path(testing::TempDir()) / ("rbmFoamDictionaryTest_" + name);
    fs::remove_all(folder);
    fs::create_directories(folder);
    return folder;
}

void writeText(const fs::path& path, const std::string& text)
{
    std::ofstream out(path, std::ios::binary);
    out << text;
}

// Parses `text` as file `fileName` and returns the InputError it must raise.
InputError parseError(const std::string& text, const std::string& fileName = "case/system/brokenDict")
{
    try {
        Dictionary::parseText(text, fileName);
    } catch (const InputError& error) {
        return error;
    }
    ADD_FAILURE() << "no InputError for:\n" << text;
    return InputError("", 0, "");
}

// Checks an error's file, line and that its message contains `words`.
void expectError(const InputError& error, const std::string& file, int line, const std::string& words)
{
    EXPECT_EQ(error.file(), file);
    EXPECT_EQ(error.line(), line) << error.what();
    EXPECT_NE(error.message().find(words), std::string::npos) << "message: " << error.message();
    EXPECT_NE(std::string(error.what()).find(file + ":" + std::to_string(line)), std::string::npos) << error.what();
}

template <class T>
std::string bytesOf(const T& value)
{
    std::string bytes(sizeof(T), '\0');
    std::memcpy(bytes.data(), &value, sizeof(T));
    return bytes;
}

const std::string binaryHeader = R"foam(FoamFile
{
    version     2.0;
    format      binary;
    arch        "LSB;label=32;scalar=64";
    class       pointVectorField;
    object      pointDisplacement;
}
)foam";

} // namespace

// ---------------------------------------------------------------------------------------
// Valid input

TEST(FoamDictionary, ParsesHeaderNestedDictionariesAndTypedValues)
{
    const std::string text = R"foam(/*--------------------------------*- C++ -*----------------------------------*\
  =========                 |
\*---------------------------------------------------------------------------*/
FoamFile
{
    version     2.0;
    format      ascii;
    class       dictionary;
    location    "system";
    object      dynamicMeshDict;
}
// * * * * //

motionSolver    rbm;          // trailing comment
deltaT          0.005;
nSteps          12;
big             8000000000;
name            "a \"quoted\" name";
enabled         on;
axis            (0 0 -1.5e-1);
solverCoeffs
{
    /* a block
       comment */
    tolerance   1e-06;
    inner { depth 2; }
}
)foam";
    Dictionary dictionary = Dictionary::parseText(text, "case/system/dynamicMeshDict");
    EXPECT_TRUE(dictionary.hasHeader());
    EXPECT_EQ(dictionary.header().className, "dictionary");
    EXPECT_EQ(dictionary.header().object, "dynamicMeshDict");
    EXPECT_EQ(dictionary.header().location, "system");
    EXPECT_FALSE(dictionary.header().isBinary());
    EXPECT_EQ(dictionary.name(), "dynamicMeshDict");

    EXPECT_EQ(dictionary.keywords(),
              (std::vector<std::string>{"motionSolver", "deltaT", "nSteps", "big", "name", "enabled", "axis", "solverCoeffs"}));
    EXPECT_EQ(dictionary.get<std::string>("motionSolver"), "rbm");
    EXPECT_DOUBLE_EQ(dictionary.get<double>("deltaT"), 0.005);
    EXPECT_EQ(dictionary.get<Label>("nSteps"), 12);
    EXPECT_EQ(dictionary.get<std::int64_t>("big"), 8000000000LL);
    EXPECT_EQ(dictionary.get<std::string>("name"), "a \"quoted\" name");
    EXPECT_TRUE(dictionary.get<bool>("enabled"));
    EXPECT_EQ(dictionary.get<Vector3>("axis"), (Vector3{0, 0, -0.15}));
    EXPECT_EQ(dictionary.lookup("deltaT").line(), 15);
    EXPECT_EQ(dictionary.lookup("deltaT").file(), "case/system/dynamicMeshDict");

    const Dictionary& coefficients = dictionary.subDictionary("solverCoeffs");
    EXPECT_EQ(coefficients.name(), "dynamicMeshDict/solverCoeffs");
    EXPECT_EQ(coefficients.line(), 21);
    EXPECT_DOUBLE_EQ(coefficients.get<double>("tolerance"), 1e-6);
    EXPECT_EQ(coefficients.lookup("tolerance").line(), 25);  // line counting continues through the block comment
    EXPECT_EQ(coefficients.subDictionary("inner").get<Label>("depth"), 2);
    EXPECT_EQ(coefficients.subDictionary("inner").name(), "dynamicMeshDict/solverCoeffs/inner");
    EXPECT_EQ(dictionary.getOrDefault<double>("missing", 7.5), 7.5);
    EXPECT_EQ(dictionary.findDictionary("deltaT"), nullptr);
    EXPECT_EQ(dictionary.lookup("name").valueText(), "\"a \\\"quoted\\\" name\"");
}

TEST(FoamDictionary, FileWithoutHeaderHasDefaultHeader)
{
    Dictionary dictionary = Dictionary::parseText("a 1;\n", "plain");
    EXPECT_FALSE(dictionary.hasHeader());
    EXPECT_EQ(dictionary.header().format, "ascii");
    EXPECT_EQ(dictionary.header().labelBytes, 4);
    EXPECT_EQ(dictionary.header().scalarBytes, 8);
}

TEST(FoamDictionary, HeaderArchGivesLabelAndScalarSizesAndBodyPosition)
{
    const std::string text = "// comment\nFoamFile\n{\n    format binary;\n    arch \"LSB;label=64;scalar=32\";\n"
                             "    class vectorField;\n    object points;\n}\n\n3\n(";
    std::size_t offset = 0;
    int line = 0;
    FoamFileHeader header = rbm::io::parseFoamFileHeader(text, "points", offset, line);
    EXPECT_TRUE(header.isBinary());
    EXPECT_EQ(header.labelBytes, 8);
    EXPECT_EQ(header.scalarBytes, 4);
    EXPECT_EQ(header.className, "vectorField");
    EXPECT_EQ(header.object, "points");
    EXPECT_EQ(line, 8);  // the closing brace's line: the body starts right after it
    EXPECT_EQ(text.substr(offset), "\n\n3\n(");
}

TEST(FoamDictionary, ParseFoamFileHeaderRequiresAHeader)
{
    std::size_t offset = 0;
    int line = 0;
    try {
        rbm::io::parseFoamFileHeader("\n\n3 (", "constant/polyMesh/owner", offset, line);
        FAIL() << "no error";
    } catch (const InputError& error) {
        expectError(error, "constant/polyMesh/owner", 3, "FoamFile");
    }
}

TEST(FoamDictionary, ReadsBoundaryListFileWithBothInGroupsSpellings)
{
    FoamFileHeader header;
    std::vector<Entry> patches = rbm::io::readDictionaryListFile(dataPath("boundary"), header);
    EXPECT_EQ(header.className, "polyBoundaryMesh");
    ASSERT_EQ(patches.size(), 3u);
    EXPECT_EQ(patches[0].keyword(), "inlet");
    EXPECT_EQ(patches[0].line(), 17);
    EXPECT_EQ(patches[1].keyword(), "walls");
    EXPECT_EQ(patches[2].keyword(), "frontAndBack");

    const Dictionary& inlet = patches[0].dictionary();
    EXPECT_EQ(inlet.get<std::string>("type"), "patch");
    EXPECT_EQ(inlet.get<Label>("nFaces"), 10);
    EXPECT_EQ(inlet.get<Label>("startFace"), 100);
    EXPECT_EQ(inlet.lookup("inGroups").stream(header).readWordList(), (std::vector<std::string>{"inlet"}));

    const Dictionary& walls = patches[1].dictionary();
    EXPECT_EQ(walls.get<std::string>("type"), "wall");
    EXPECT_EQ(walls.lookup("inGroups").stream(header).readWordList(), (std::vector<std::string>{"wall"}));
    EXPECT_EQ(walls.get<Label>("startFace"), 110);
    EXPECT_EQ(patches[2].dictionary().get<Label>("nFaces"), 200);
}

TEST(FoamDictionary, ReadsListsInEveryForm)
{
    const std::string text = R"foam(
counted     3(1 2 3);
uncounted   (4.5 -1 2e3);
repeated    4{7};
typed       List<scalar> 2(0.5 1e-05);
vectors     2((1 2 3) (4 5 6));
emptyList   0();
words       (inlet "out let" wall);
labels      List<label> 3(0 -1 2147483647);
field       nonuniform List<vector> 1((0 0 1));
)foam";
    Dictionary d = Dictionary::parseText(text, "lists");
    EXPECT_EQ(d.lookup("counted").stream().readScalarList(), (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(d.lookup("uncounted").stream().readScalarList(), (std::vector<double>{4.5, -1, 2000}));
    EXPECT_EQ(d.lookup("repeated").stream().readLabelList(), (std::vector<Label>{7, 7, 7, 7}));
    EXPECT_EQ(d.lookup("typed").stream().readScalarList(), (std::vector<double>{0.5, 1e-5}));
    EXPECT_EQ(d.lookup("vectors").stream().readVectorList(), (std::vector<Vector3>{{1, 2, 3}, {4, 5, 6}}));
    EXPECT_TRUE(d.lookup("emptyList").stream().readLabelList().empty());
    EXPECT_EQ(d.lookup("words").stream().readWordList(), (std::vector<std::string>{"inlet", "out let", "wall"}));
    EXPECT_EQ(d.lookup("labels").stream().readLabelList(), (std::vector<Label>{0, -1, 2147483647}));
    auto field = d.lookup("field").stream();
    EXPECT_EQ(field.readWord(), "nonuniform");
    EXPECT_EQ(field.readVectorList(), (std::vector<Vector3>{{0, 0, 1}}));
    EXPECT_TRUE(field.atEnd());
}

TEST(FoamDictionary, WordsKeepBalancedParenthesesAndNumbersAreTypedBySpelling)
{
    Dictionary d = Dictionary::parseText("div(phi,U) Gauss linearUpwind grad(U);\nn 10;\nx 10.0;\ny -3e2;\nw 2ndWall;\n",
                                         "fvSchemes");
    const auto& tokens = d.lookup("div(phi,U)").tokens();
    ASSERT_EQ(tokens.size(), 3u);
    EXPECT_EQ(tokens[2].text, "grad(U)");
    EXPECT_TRUE(d.lookup("n").tokens()[0].isInteger);
    EXPECT_FALSE(d.lookup("x").tokens()[0].isInteger);
    EXPECT_DOUBLE_EQ(d.get<double>("y"), -300.0);
    EXPECT_EQ(d.lookup("w").tokens()[0].kind, rbm::io::Token::Kind::Word);
}

TEST(FoamDictionary, SubstitutesScopedVariablesAndDictionaries)
{
    const std::string text = R"foam(
top         1.5;
a { x 2; b { y 3; } }
defaults { type fixedValue; value uniform (0 0 0); }
plain       $top;
dotted      $a.x;
deeper      $a.b.y;
braced      ${a.b.y};
inList      ($top $a.x 4);
copy        $defaults;
sub
{
    x       10;
    own     $x;
    parent  $..top;
    fromTop $:a.b.y;
    inherit $top;
    inner { up $..x; upUp $...top; }
}
patch
{
    $defaults;
    type    slip;
}
)foam";
    Dictionary d = Dictionary::parseText(text, "variables");
    EXPECT_DOUBLE_EQ(d.get<double>("plain"), 1.5);
    EXPECT_EQ(d.get<Label>("dotted"), 2);
    EXPECT_EQ(d.get<Label>("deeper"), 3);
    EXPECT_EQ(d.get<Label>("braced"), 3);
    EXPECT_EQ(d.lookup("inList").stream().readScalarList(), (std::vector<double>{1.5, 2, 4}));
    EXPECT_EQ(d.lookup("inList").tokens()[1].line, 9);  // substituted tokens are placed where they are used

    const Dictionary& copy = d.subDictionary("copy");
    EXPECT_EQ(copy.name(), "variables/copy");
    EXPECT_EQ(copy.get<std::string>("type"), "fixedValue");
    EXPECT_EQ(copy.lookup("value").valueText(), "uniform ( 0 0 0 )");

    const Dictionary& sub = d.subDictionary("sub");
    EXPECT_EQ(sub.get<Label>("own"), 10);
    EXPECT_DOUBLE_EQ(sub.get<double>("parent"), 1.5);
    EXPECT_EQ(sub.get<Label>("fromTop"), 3);
    EXPECT_DOUBLE_EQ(sub.get<double>("inherit"), 1.5);
    EXPECT_EQ(sub.subDictionary("inner").get<Label>("up"), 10);
    EXPECT_DOUBLE_EQ(sub.subDictionary("inner").get<double>("upUp"), 1.5);

    // The merged dictionary keeps its own later definition of `type` in the first position.
    const Dictionary& patch = d.subDictionary("patch");
    EXPECT_EQ(patch.keywords(), (std::vector<std::string>{"type", "value"}));
    EXPECT_EQ(patch.get<std::string>("type"), "slip");
}

TEST(FoamDictionary, RegularExpressionKeywordsMatchAfterLiteralsLastDefinedFirst)
{
    const std::string text = R"foam(
"(inlet|outlet)" { type fixedValue; }
".*Wall"         { type slip; }
"lower.*"        { type zeroGradient; }
lowerWall        { type noSlip; }
"front.*|back"   { type empty; }
)foam";
    Dictionary d = Dictionary::parseText(text, "boundaryField");
    EXPECT_EQ(d.subDictionary("inlet").get<std::string>("type"), "fixedValue");
    EXPECT_EQ(d.subDictionary("outlet").get<std::string>("type"), "fixedValue");
    EXPECT_EQ(d.subDictionary("upperWall").get<std::string>("type"), "slip");
    EXPECT_EQ(d.subDictionary("lowerWall").get<std::string>("type"), "noSlip");   // literal first
    EXPECT_EQ(d.subDictionary("lowerSide").get<std::string>("type"), "zeroGradient");
    // "lowerTheWall" matches both ".*Wall" and "lower.*": the later one wins.
    EXPECT_EQ(d.subDictionary("lowerTheWall").get<std::string>("type"), "zeroGradient");
    EXPECT_EQ(d.subDictionary("back").get<std::string>("type"), "empty");
    EXPECT_EQ(d.find("inletX"), nullptr);  // regex_match: the whole name must match
    EXPECT_EQ(d.find("side"), nullptr);
}

TEST(FoamDictionary, IncludesRelativeToTheIncludingFile)
{
    Dictionary d = Dictionary::readFile(dataPath("includes/main"));
    EXPECT_EQ(d.keywords(), (std::vector<std::string>{"before", "fromCommon", "fromNested", "coefficients", "after"}));
    EXPECT_EQ(d.get<Label>("before"), 1);
    EXPECT_EQ(d.get<Label>("fromCommon"), 2);
    EXPECT_EQ(d.get<Vector3>("fromNested"), (Vector3{1, 2, 3}));
    EXPECT_EQ(d.get<Label>("after"), 2);
    const Entry& nested = d.lookup("fromNested");
    EXPECT_EQ(nested.line(), 1);
    EXPECT_NE(nested.file().find("sub/nested"), std::string::npos) << nested.file();

    const Dictionary& coefficients = d.subDictionary("coefficients");
    EXPECT_DOUBLE_EQ(coefficients.get<double>("stiffness"), 4.5);
    EXPECT_EQ(coefficients.get<Label>("scale"), 1);
    EXPECT_EQ(coefficients.get<Label>("local"), 3);
}

TEST(FoamDictionary, ReadsGzipCompressedFileByItsPlainName)
{
    fs::path folder = scratchFolder("gzip");
    rbm::io::writeFileContents(folder / "controlDict", "FoamFile { format ascii; class dictionary; }\nendTime 2.5;\n", true);
    ASSERT_TRUE(fs::exists(folder / "controlDict.gz"));
    Dictionary d = Dictionary::readFile(folder / "controlDict");
    EXPECT_DOUBLE_EQ(d.get<double>("endTime"), 2.5);
    EXPECT_EQ(d.name(), "controlDict");
}

TEST(FoamDictionary, InputModesMergeOverwriteProtectAndRemove)
{
    const std::string text = R"foam(
a { x 1; y 2; }
a { y 3; z 4; }
b 1;
b 2;
#inputMode protect
b 3;
c { x 1; }
c { y 1; }
#inputMode overwrite
a { w 5; }
#inputMode merge
r1 1; r2 2; keep 3; regexGone 4;
#remove r1
#remove (r2 "regex.*")
)foam";
    Dictionary d = Dictionary::parseText(text, "modes");
    EXPECT_EQ(d.get<Label>("b"), 2);
    EXPECT_EQ(d.subDictionary("c").keywords(), (std::vector<std::string>{"x"}));
    EXPECT_EQ(d.subDictionary("a").keywords(), (std::vector<std::string>{"w"}));
    EXPECT_EQ(d.keywords(), (std::vector<std::string>{"a", "b", "c", "keep"}));

    Dictionary merged = Dictionary::parseText("a { x 1; y 2; s { p 1; } }\na { y 3; z 4; s { q 2; } }\n", "merge");
    const Dictionary& a = merged.subDictionary("a");
    EXPECT_EQ(a.keywords(), (std::vector<std::string>{"x", "y", "s", "z"}));
    EXPECT_EQ(a.get<Label>("y"), 3);
    EXPECT_EQ(a.subDictionary("s").keywords(), (std::vector<std::string>{"p", "q"}));
}

TEST(FoamDictionary, DecodesBinaryListsInsideDictionaries)
{
    std::string vectors = bytesOf(1.0) + bytesOf(-2.5) + bytesOf(1e-300) + bytesOf(4.0) + bytesOf(5.0) + bytesOf(6.0);
    // A ')' byte inside the data must not end the list early.
    std::string scalars = bytesOf(0.5) + std::string("\x29\x29\x29\x29\x29\x29\x29\x29", 8);
    double scalarWithParentheses;
    std::memcpy(&scalarWithParentheses, scalars.data() + 8, 8);
    std::string labels = bytesOf(std::int32_t{7}) + bytesOf(std::int32_t{-1}) + bytesOf(std::int32_t{123456});
    const std::string text = binaryHeader + "dimensions [0 1 0 0 0 0 0];\n" +
                             "internalField nonuniform List<vector> 2(" + vectors + ");\n" +
                             "scalars List<scalar> 2\n(" + scalars + ");\n" + "labels List<label> 3(" + labels + ");\n" +
                             "emptyList List<vector> 0;\n" + "after 1;\n";
    Dictionary d = Dictionary::parseText(text, "0/pointDisplacement");
    ASSERT_TRUE(d.header().isBinary());

    auto field = d.lookup("internalField").stream(d.header());
    EXPECT_EQ(field.readWord(), "nonuniform");
    EXPECT_EQ(field.readVectorList(), (std::vector<Vector3>{{1.0, -2.5, 1e-300}, {4, 5, 6}}));
    EXPECT_EQ(d.lookup("scalars").stream(d.header()).readScalarList(), (std::vector<double>{0.5, scalarWithParentheses}));
    EXPECT_EQ(d.lookup("labels").stream(d.header()).readLabelList(), (std::vector<Label>{7, -1, 123456}));
    EXPECT_TRUE(d.lookup("emptyList").stream(d.header()).readVectorList().empty());
    EXPECT_EQ(d.get<Label>("after"), 1);
    EXPECT_EQ(d.lookup("after").line(), 15);  // binary data is not counted as lines
}

TEST(FoamDictionary, DecodesSixtyFourBitLabelsAndThirtyTwoBitScalars)
{
    const std::string header = "FoamFile { format binary; arch \"LSB;label=64;scalar=32\"; class labelList; }\n";
    const std::string text = header + "labels List<label> 2(" + bytesOf(std::int64_t{5}) + bytesOf(std::int64_t{-9}) + ");\n" +
                             "scalars List<scalar> 1(" + bytesOf(0.25f) + ");\n" + "big List<label> 1(" +
                             bytesOf(std::int64_t{1} << 40) + ");\n";
    Dictionary d = Dictionary::parseText(text, "zones");
    EXPECT_EQ(d.lookup("labels").stream(d.header()).readLabelList(), (std::vector<Label>{5, -9}));
    EXPECT_EQ(d.lookup("scalars").stream(d.header()).readScalarList(), (std::vector<double>{0.25}));
    // The element size follows from the data, so a stream without the header decodes alike.
    EXPECT_EQ(d.lookup("labels").stream().readLabelList(), (std::vector<Label>{5, -9}));
    EXPECT_EQ(d.lookup("scalars").stream().readScalarList(), (std::vector<double>{0.25}));
    try {
        d.lookup("big").stream(d.header()).readLabelList();
        FAIL() << "no error for a label beyond 32 bits";
    } catch (const InputError& error) {
        expectError(error, "zones", 4, "does not fit in 32 bits");
    }
}

TEST(FoamDictionary, SetReplacesInPlaceOrAppends)
{
    Dictionary d("built", "", 0);
    d.set(Entry("a", "", 0, std::vector<rbm::io::Token>{{rbm::io::Token::Kind::Number, "1", 1.0, true, 0}}));
    d.set(Entry("b", "", 0, std::make_unique<Dictionary>("built/b", "", 0)));
    d.set(Entry("a", "", 0, std::vector<rbm::io::Token>{{rbm::io::Token::Kind::Number, "2", 2.0, true, 0}}));
    EXPECT_EQ(d.keywords(), (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(d.get<Label>("a"), 2);
    Dictionary copy = d;  // deep copy
    EXPECT_TRUE(copy.lookup("b").isDictionary());
    EXPECT_NE(&copy.subDictionary("b"), &d.subDictionary("b"));
}

// ---------------------------------------------------------------------------------------
// Malformed input: every error names the file and the line

TEST(FoamDictionaryErrors, UnterminatedStringNamesTheLineWhereItOpens)
{
    expectError(parseError("a 1;\nb \"never closed;\nc 2;\n"), "case/system/brokenDict", 2, "unterminated string");
}

TEST(FoamDictionaryErrors, UnterminatedCommentNamesTheLineWhereItOpens)
{
    expectError(parseError("a 1;\n\n/* comment\n b 2;\n"), "case/system/brokenDict", 3, "unterminated comment");
}

TEST(FoamDictionaryErrors, UnterminatedListNamesTheLineOfTheOpeningParenthesis)
{
    expectError(parseError("a 1;\nlist (1 2\n 3 4;\n b 5;\n"), "case/system/brokenDict", 2, "unterminated list");
}

TEST(FoamDictionaryErrors, UnterminatedDictionaryNamesTheLineOfTheOpeningBrace)
{
    expectError(parseError("a 1;\nsub\n{\n    b 2;\n"), "case/system/brokenDict", 3, "unterminated dictionary");
}

TEST(FoamDictionaryErrors, MissingSemicolonBeforeClosingBrace)
{
    expectError(parseError("sub\n{\n    a 1;\n    b 2\n}\n"), "case/system/brokenDict", 4, "missing ';'");
}

TEST(FoamDictionaryErrors, MissingSemicolonAtEndOfFile)
{
    expectError(parseError("a 1;\nb 2\n\n"), "case/system/brokenDict", 2, "missing ';'");
}

TEST(FoamDictionaryErrors, MissingSemicolonBeforeNextDictionary)
{
    expectError(parseError("a 1;\nb 2\nc\n{\n}\n"), "case/system/brokenDict", 2, "missing ';' at the end of entry 'b'");
}

TEST(FoamDictionaryErrors, ListCountThatDisagreesWithItsData)
{
    Dictionary d = Dictionary::parseText("a 1;\nlist 3\n(\n 1 2\n);\n", "case/constant/data");
    try {
        d.lookup("list").stream().readScalarList();
        FAIL() << "no error";
    } catch (const InputError& error) {
        expectError(error, "case/constant/data", 2, "disagrees");
    }
}

TEST(FoamDictionaryErrors, BinaryListShorterThanItsCount)
{
    // Count 3 but only 2 scalars of data before ')'.
    const std::string text = binaryHeader + "x 1;\nvalues List<scalar> 3(" + bytesOf(1.0) + bytesOf(2.0) + ");\n";
    expectError(parseError(text, "0/binaryField"), "0/binaryField", 10, "binary list of 3 elements");
}

TEST(FoamDictionaryErrors, UndefinedVariable)
{
    expectError(parseError("a 1;\nsub { b $notDefined; }\n"), "case/system/brokenDict", 2, "undefined variable $notDefined");
}

TEST(FoamDictionaryErrors, DictionaryVariableInsideAValue)
{
    expectError(parseError("d { x 1; }\n\ne (1 $d);\n"), "case/system/brokenDict", 3, "names a dictionary");
}

TEST(FoamDictionaryErrors, UnknownDirective)
{
    expectError(parseError("a 1;\n\n#frobnicate x\n"), "case/system/brokenDict", 3, "unknown directive '#frobnicate'");
}

TEST(FoamDictionaryErrors, UnsupportedCodeDirective)
{
    expectError(parseError("a 1;\nb #calc \"$a*2\";\n"), "case/system/brokenDict", 2, "#calc");
    expectError(parseError("a 1;\ncode\n#{\n x;\n#};\n"), "case/system/brokenDict", 3, "code blocks are not supported");
}

TEST(FoamDictionaryErrors, IncludeEtcIsAClearError)
{
    const std::string file = dataPath("includeEtc").string();
    try {
        Dictionary::readFile(dataPath("includeEtc"));
        FAIL() << "no error";
    } catch (const InputError& error) {
        expectError(error, file, 2, "#includeEtc \"caseDicts/setConstraintTypes\"");
    }
}

TEST(FoamDictionaryErrors, MissingIncludedFileNamesTheIncludingFileAndLine)
{
    const std::string file = dataPath("missingInclude").string();
    try {
        Dictionary::readFile(dataPath("missingInclude"));
        FAIL() << "no error";
    } catch (const InputError& error) {
        expectError(error, file, 10, "cannot find the file \"notThere\"");
    }
}

TEST(FoamDictionaryErrors, IncludeLoopIsDetected)
{
    try {
        Dictionary::readFile(dataPath("loop/a"));
        FAIL() << "no error";
    } catch (const InputError& error) {
        // a includes b (line 2 of a), b includes a again on its line 2.
        EXPECT_NE(error.file().find("loop/b"), std::string::npos) << error.what();
        EXPECT_EQ(error.line(), 2);
        EXPECT_NE(error.message().find("#include loop"), std::string::npos) << error.message();
    }
}

TEST(FoamDictionaryErrors, NestingDeeperThanTheLimitIsAnErrorNotACrash)
{
    std::string text;
    for (int i = 0; i < 5000; ++i) text += "a\n{\n";
    // The 1001st '{' is on line 2 * 1001.
    expectError(parseError(text), "case/system/brokenDict", 2002, "nested deeper than 1000");
    std::string lists = "x ";
    for (int i = 0; i < 5000; ++i) lists += "(\n";
    expectError(parseError(lists), "case/system/brokenDict", 1001, "nested deeper than 1000");
}

TEST(FoamDictionaryErrors, UnmatchedClosingBrace)
{
    expectError(parseError("a 1;\n}\n"), "case/system/brokenDict", 2, "unexpected '}'");
}

TEST(FoamDictionaryErrors, NumberWhereAKeywordIsExpected)
{
    expectError(parseError("a 1;\n\n3 4;\n"), "case/system/brokenDict", 3, "expected a keyword but found number 3");
}

TEST(FoamDictionaryErrors, MismatchedBrackets)
{
    expectError(parseError("a\n(1\n2];\n"), "case/system/brokenDict", 3, "expected ')' to close the '(' opened on line 2");
}

TEST(FoamDictionaryErrors, InvalidRegularExpressionKeyword)
{
    expectError(parseError("a 1;\n\"(inlet|outlet\" { type patch; }\n"), "case/system/brokenDict", 2,
                "not a valid regular expression");
}

TEST(FoamDictionaryErrors, DuplicateEntryWithInputModeError)
{
    expectError(parseError("#inputMode error\na 1;\nb 2;\na 3;\n"), "case/system/brokenDict", 4, "duplicate entry 'a'");
}

TEST(FoamDictionaryErrors, WrongValueTypeNamesTheEntryLine)
{
    Dictionary d = Dictionary::parseText("a 1;\n\ndeltaT small;\nn 2.5;\nv (1 2);\nflag maybe;\n", "case/system/controlDict");
    try {
        d.get<double>("deltaT");
        FAIL();
    } catch (const InputError& error) {
        expectError(error, "case/system/controlDict", 3, "entry 'deltaT'");
    }
    try {
        d.get<Label>("n");
        FAIL();
    } catch (const InputError& error) {
        expectError(error, "case/system/controlDict", 4, "integer");
    }
    try {
        d.get<Vector3>("v");
        FAIL();
    } catch (const InputError& error) {
        expectError(error, "case/system/controlDict", 5, "vector");
    }
    try {
        d.get<bool>("flag");
        FAIL();
    } catch (const InputError& error) {
        expectError(error, "case/system/controlDict", 6, "on/off");
    }
    try {
        d.lookup("endTime");
        FAIL();
    } catch (const InputError& error) {
        EXPECT_EQ(error.file(), "case/system/controlDict");
        EXPECT_NE(error.message().find("keyword endTime is undefined in dictionary controlDict"), std::string::npos);
    }
}

TEST(FoamDictionaryErrors, BadHeaderFormat)
{
    expectError(parseError("FoamFile\n{\n    format text;\n}\na 1;\n"), "case/system/brokenDict", 3, "ascii or binary");
    expectError(parseError("FoamFile\n{\n    format ascii\n}\na 1;\n"), "case/system/brokenDict", 3, "missing ';'");
}

TEST(FoamDictionaryErrors, DictionaryListFileCountDisagreesWithEntries)
{
    fs::path folder = scratchFolder("listCount");
    writeText(folder / "boundary", "FoamFile { format ascii; class polyBoundaryMesh; }\n\n2\n(\n a { type patch; }\n)\n");
    FoamFileHeader header;
    try {
        rbm::io::readDictionaryListFile(folder / "boundary", header);
        FAIL() << "no error";
    } catch (const InputError& error) {
        expectError(error, (folder / "boundary").string(), 3, "disagrees");
    }
    writeText(folder / "boundary", "2\n(\n a { type patch; }\n b\n type wall;\n)\n");
    try {
        rbm::io::readDictionaryListFile(folder / "boundary", header);
        FAIL() << "no error";
    } catch (const InputError& error) {
        expectError(error, (folder / "boundary").string(), 4, "expected '{' after 'b'");
    }
}

TEST(FoamDictionary, BigAsciiListsArePackedAndDecodeToTheSameValues)
{
    // 150 vectors (over FoamTokenizer::packedListThreshold) and 120 labels, one per line.
    std::string text = "FoamFile { format ascii; class pointVectorField; }\nfield nonuniform List<vector>\n150\n(\n";
    std::vector<Vector3> expected;
    for (int i = 0; i < 150; ++i) {
        expected.push_back({i * 0.5, -i * 1e-3, 1e5 + i});
        text += "(" + std::to_string(i * 0.5) + " " + std::to_string(-i * 1e-3) + " " + std::to_string(1e5 + i) + ")\n";
    }
    text += ")\n;\nlabels List<label> 120(";
    std::vector<Label> expectedLabels;
    for (int i = 0; i < 120; ++i) {
        expectedLabels.push_back(i * 1000 - 7);
        text += " " + std::to_string(i * 1000 - 7);
    }
    text += ");\nafter 1;\n";
    Dictionary d = Dictionary::parseText(text, "0/pointDisplacement");
    auto field = d.lookup("field").stream(d.header());
    EXPECT_EQ(field.readWord(), "nonuniform");
    const std::vector<Vector3> values = field.readVectorList();
    ASSERT_EQ(values.size(), expected.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
        EXPECT_DOUBLE_EQ(values[i].x, expected[i].x);
        EXPECT_DOUBLE_EQ(values[i].y, expected[i].y);
        EXPECT_DOUBLE_EQ(values[i].z, expected[i].z);
    }
    EXPECT_EQ(d.lookup("labels").stream(d.header()).readLabelList(), expectedLabels);
    EXPECT_EQ(d.lookup("labels").tokens()[2].kind, rbm::io::Token::Kind::Binary);  // packed, not 120 tokens
    EXPECT_EQ(d.lookup("after").line(), 158);
    // A label=64 ascii file packs 8-byte labels; a stream without the header still decodes them.
    Dictionary wide = Dictionary::parseText("FoamFile { format ascii; arch \"LSB;label=64;scalar=64\"; }\nl List<label> " +
                                                text.substr(text.find("120(")),
                                            "wide");
    EXPECT_EQ(wide.lookup("l").stream().readLabelList(), expectedLabels);  // 2 + 1 (count) + 1 '(' + 150 + ')' + ';' + labels line + 1
}

TEST(FoamDictionaryErrors, BigAsciiListCountThatDisagreesWithItsData)
{
    std::string text = "a 1;\nvalues List<scalar> 200\n(\n";
    for (int i = 0; i < 199; ++i) text += "1.5\n";
    text += ");\n";
    expectError(parseError(text), "case/system/brokenDict", 2, "disagrees with the 199 elements");
    std::string bad = "a 1;\nvalues List<scalar> 100\n(\n";
    for (int i = 0; i < 100; ++i) bad += (i == 50 ? "x\n" : "1\n");
    bad += ");\n";
    expectError(parseError(bad), "case/system/brokenDict", 54, "expected a number in the List<scalar> of size 100 but found 'x'");
}

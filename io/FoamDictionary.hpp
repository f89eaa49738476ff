#pragma once
// OpenFOAM dictionary files: controlDict, dynamicMeshDict, pointDisplacement, boundary, ...
//
// Syntax handled (OpenFOAM v1912):
//   FoamFile header; // and /* */ comments; `keyword value ... ;` entries; nested
//   `keyword { ... }` dictionaries; lists `N( ... )`, `( ... )`, `N{value}`; strings in
//   double quotes; `uniform` / `nonuniform List<T>` values (ascii, and binary when the
//   header says `format binary`); `#include "file"`, `#includeIfPresent`, `#includeEtc`
//   (clear error: rbm has no OpenFOAM installation to search), `#inputMode merge|overwrite|
//   protect|warn|error|default`, `#remove`; `$var`, `$dict.var`, `$:a.b`, `$..var`
//   and `${...}` substitution, also of whole dictionaries; regular-expression keywords
//   such as `"(inlet|outlet)"` or `".*Wall"` that `find` matches when no literal keyword does.
// Every error is an rbm::InputError naming the file and line.

#include "InputError.hpp"
#include "PolyMesh.hpp"
#include "Vector3.hpp"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rbm::io {

// One lexical token of an entry's value.
struct Token {
    enum class Kind { Word, String, Number, Punctuation, Binary };
    Kind kind = Kind::Word;
    std::string text;          // Word/String: content (no quotes); Number: as spelled; Punctuation: the character;
                               // Binary: the raw bytes of a binary list's contents (between its parentheses)
    double number = 0.0;       // Number only
    bool isInteger = false;    // Number only: spelled without '.', 'e' or 'E'
    int line = 0;

    bool isPunctuation(char c) const { return kind == Kind::Punctuation && text.size() == 1 && text[0] == c; }
    bool isWord(std::string_view w) const { return kind == Kind::Word && text == w; }
};

// Information of a file's FoamFile header that readers need.
struct FoamFileHeader {
    std::string format = "ascii";   // "ascii" or "binary"
    std::string className;          // e.g. "vectorField", "faceCompactList", "pointVectorField"
    std::string object;
    std::string location;
    int labelBytes = 4;             // from arch "label=32|64"
    int scalarBytes = 8;            // from arch "scalar=32|64"
    bool isBinary() const { return format == "binary"; }
};

// A cursor over a sequence of tokens with typed readers. Errors name file and line of the
// offending token.
class TokenStream {
public:
    TokenStream(const std::vector<Token>& tokens, std::string file, FoamFileHeader header = {});

    bool atEnd() const;
    const Token& peek() const;              // throws at end
    const Token& next();                    // throws at end
    void expectPunctuation(char c);         // throws "expected 'c' but found ..."

    double readScalar();
    Label readLabel();                      // integer that fits in 32 bits
    std::string readWord();                 // a Word token
    std::string readWordOrString();
    bool readBool();                        // on/off, yes/no, true/false, y/n, t/f, none
    Vector3 readVector();                   // ( x y z )

    // Lists in any of OpenFOAM's forms: N( ... ), ( ... ), N{value}, and a Binary token
    // after N when the header is binary. A count that disagrees with the data is an error.
    std::vector<double> readScalarList();
    std::vector<Label> readLabelList();
    std::vector<Vector3> readVectorList();
    std::vector<std::string> readWordList();
    // The same with at most `maxCount` elements; a larger size is an error raised before
    // anything is allocated. Use these when the expected size is known (a field's number of
    // points): the size of a uniform list `N{value}` is not bounded by the file's length.
    // Without `maxCount`, sizes up to the largest 32-bit label are accepted.
    std::vector<double> readScalarList(std::size_t maxCount);
    std::vector<Label> readLabelList(std::size_t maxCount);
    std::vector<Vector3> readVectorList(std::size_t maxCount);
    std::vector<std::string> readWordList(std::size_t maxCount);

    // Error at the current token (or at the last one when at end).
    [[noreturn]] void fail(const std::string& message) const;
    const std::string& file() const { return file_; }
    const FoamFileHeader& header() const { return header_; }

private:
    const std::vector<Token>* tokens_;
    std::size_t position_ = 0;
    std::string file_;
    FoamFileHeader header_;
};

class Dictionary;

// One entry of a dictionary: either a sub-dictionary or a primitive entry (tokens up to ';').
class Entry {
public:
    Entry(std::string keyword, std::string file, int line, std::vector<Token> tokens);
    Entry(std::string keyword, std::string file, int line, std::unique_ptr<Dictionary> dictionary);
    Entry(const Entry& other);
    Entry& operator=(const Entry& other);
    Entry(Entry&&) noexcept;
    Entry& operator=(Entry&&) noexcept;
    ~Entry();

    const std::string& keyword() const { return keyword_; }
    const std::string& file() const { return file_; }
    int line() const { return line_; }
    bool isDictionary() const { return dictionary_ != nullptr; }
    const Dictionary& dictionary() const;            // throws if primitive
    Dictionary& dictionary();
    const std::vector<Token>& tokens() const;        // throws if a dictionary
    TokenStream stream(const FoamFileHeader& header = {}) const;  // over tokens()
    // The value as text, tokens separated by single spaces (strings re-quoted).
    std::string valueText() const;

private:
    std::string keyword_;
    std::string file_;
    int line_ = 0;
    std::vector<Token> tokens_;
    std::unique_ptr<Dictionary> dictionary_;
};

class Dictionary {
public:
    Dictionary() = default;
    Dictionary(std::string name, std::string file, int line);

    // Reads and parses a file (or its .gz). `#include` paths are relative to its folder.
    static Dictionary readFile(const std::filesystem::path& path);
    // Parses text as if it were the content of file `fileName`.
    static Dictionary parseText(std::string_view text, const std::string& fileName);

    const std::string& name() const { return name_; }   // scoped, e.g. "dynamicMeshDict/solverCoeffs"
    const std::string& file() const { return file_; }
    int line() const { return line_; }
    const FoamFileHeader& header() const { return header_; }   // defaults when no FoamFile
    bool hasHeader() const { return hasHeader_; }

    // Entries in file order (FoamFile header excluded).
    const std::vector<Entry>& entries() const { return entries_; }
    std::vector<std::string> keywords() const;

    // Literal keyword first; then regular-expression keywords, last defined first.
    const Entry* find(std::string_view keyword) const;
    bool contains(std::string_view keyword) const { return find(keyword) != nullptr; }
    const Entry& lookup(std::string_view keyword) const;      // throws "keyword K is undefined in dictionary D"
    const Dictionary* findDictionary(std::string_view keyword) const;
    const Dictionary& subDictionary(std::string_view keyword) const;

    // Typed values of single-valued entries: double, Label, std::int64_t, std::string (word
    // or string), bool, Vector3. Errors say what was expected and name file and line.
    template <class T> T get(std::string_view keyword) const;
    template <class T> T getOrDefault(std::string_view keyword, const T& fallback) const
    {
        return contains(keyword) ? get<T>(keyword) : fallback;
    }

    // Adds or replaces an entry (used by the parser and by programs building dictionaries).
    void set(Entry entry);
    void setHeader(const FoamFileHeader& header) { header_ = header; hasHeader_ = true; }

private:
    std::string name_;
    std::string file_;
    int line_ = 0;
    FoamFileHeader header_;
    bool hasHeader_ = false;
    std::vector<Entry> entries_;
};

// Files whose body is a bare list of `name { ... }` dictionaries (constant/polyMesh/boundary,
// zone files): returns the entries in order, with the file's header in `header`.
std::vector<Entry> readDictionaryListFile(const std::filesystem::path& path, FoamFileHeader& header);

// Splits off and parses the FoamFile header at the start of `text` (after comments);
// `bodyOffset` / `bodyLine` receive where the rest begins. Throws when there is no header.
FoamFileHeader parseFoamFileHeader(std::string_view text, const std::string& fileName, std::size_t& bodyOffset,
                                   int& bodyLine);

} // namespace rbm::io

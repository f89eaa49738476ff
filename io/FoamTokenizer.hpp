#pragma once
// The lexer of OpenFOAM's dictionary syntax: turns file text into rbm::io::Token values.
//
// Rules follow OpenFOAM v1912's ISstream:
//  - `//` and `/* */` comments; an unterminated `/*` is an error at the line it opened.
//  - punctuation ( ) { } [ ] ; and a leading ','.
//  - strings in double quotes; `\"` is a quote, other backslashes are kept; an unescaped
//    newline inside a string is an error (OpenFOAM's "found '\n' while reading string").
//  - numbers: a token starting with a digit, or with + - . followed by a digit, that
//    reads completely as a number; otherwise it is a word ("2ndWall").
//  - words: anything else up to whitespace or ; { } " [ ], with balanced parentheses
//    kept inside the word (`div(phi,U)`), `$var`, `${a.b}` and `#directive` included.
//  - binary lists: when the header says `format binary`, a word `List<T>` (T contiguous:
//    scalar, vector, label, tensor, ...) followed by an integer N and '(' is followed by
//    N*sizeof(T) raw bytes, returned as one Binary token (the bytes without the
//    parentheses). OpenFOAM writes nothing at all after `0` for an empty binary list; an
//    empty Binary token is returned then, so list readers see the same shape either way.
//  - big ascii lists: in an ascii file, `List<scalar>`, `List<vector>` or `List<label>` with
//    at least `packedListThreshold` elements is parsed straight into the same packed binary
//    form (scalars as 8-byte doubles, labels with the header's label size) instead of one
//    token per number: a field of a million points would otherwise need 5 million tokens.
//    A count that disagrees with the elements is reported here, at the line of the count.
//    TokenStream's list readers decode both forms alike; code that walks tokens itself
//    must expect a Binary token after the count of such a list.

#include "FoamDictionary.hpp"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rbm::io {

class FoamTokenizer {
public:
    // Lexes `text` from `offset` (which is at line `line`), for error messages in `file`.
    FoamTokenizer(std::string_view text, std::string file, std::size_t offset = 0, int line = 1,
                  FoamFileHeader header = {});

    // Reads the next token; false at the end of the text.
    bool next(Token& token);
    // Reads all remaining tokens.
    std::vector<Token> readAll();

    std::size_t offset() const { return position_; }
    int line() const { return line_; }
    const std::string& file() const { return file_; }

    // Bytes of one element of a binary `List<T>` for the header's label and scalar sizes,
    // or 0 when T is not stored contiguously (word, string, ...).
    static std::size_t binaryElementBytes(std::string_view listWord, const FoamFileHeader& header);

    // Ascii `List<T>` with at least this many elements are packed (see above).
    static constexpr long long packedListThreshold = 100;

private:
    void skipSpaceAndComments();
    void readString(Token& token);
    void readWordOrNumber(Token& token);
    bool readBinaryList(Token& token);
    bool packAsciiList(Token& token);
    double readAsciiNumber(bool integer);
    [[noreturn]] void fail(int line, const std::string& message) const;

    std::string_view text_;
    std::string file_;
    std::size_t position_ = 0;
    int line_ = 1;
    FoamFileHeader header_;

    // Binary-list state: 1 after a contiguous `List<T>` word, 2 after its integer count.
    int binaryState_ = 0;
    std::size_t binaryElementBytes_ = 0;
    long long binaryCount_ = 0;
    int binaryCountLine_ = 0;
    std::string binaryListWord_;
};

} // namespace rbm::io

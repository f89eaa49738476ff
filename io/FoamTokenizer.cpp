#include "FoamTokenizer.hpp"

#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace rbm::io {

namespace {

bool isSpace(char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

bool isDigit(char c)
{
    return c >= '0' && c <= '9';
}

// Characters that end a word (parentheses are handled separately: balanced ones stay inside).
bool endsWord(char c)
{
    return isSpace(c) || c == ';' || c == '{' || c == '}' || c == '"' || c == '[' || c == ']';
}

// Parses the whole of `text` as a number; false when it is not one.
bool parseNumber(std::string_view text, double& value, bool& isInteger)
{
    if (text.empty()) return false;
    std::string_view digits = text;
    if (digits.front() == '+') digits.remove_prefix(1);
    if (digits.empty()) return false;
    const char* first = digits.data();
    const char* last = digits.data() + digits.size();
    auto result = std::from_chars(first, last, value);
    if (result.ec != std::errc() || result.ptr != last) return false;
    isInteger = digits.find_first_of(".eE") == std::string_view::npos;
    return true;
}

} // namespace

FoamTokenizer::FoamTokenizer(std::string_view text, std::string file, std::size_t offset, int line,
                             FoamFileHeader header)
    : text_(text), file_(std::move(file)), position_(offset), line_(line), header_(std::move(header))
{}

void FoamTokenizer::fail(int line, const std::string& message) const
{
    throw InputError(file_, line, message);
}

std::size_t FoamTokenizer::binaryElementBytes(std::string_view listWord, const FoamFileHeader& header)
{
    if (listWord.size() < 7 || listWord.substr(0, 5) != "List<" || listWord.back() != '>') return 0;
    std::string_view type = listWord.substr(5, listWord.size() - 6);
    const auto scalar = static_cast<std::size_t>(header.scalarBytes);
    if (type == "scalar") return scalar;
    if (type == "vector") return 3 * scalar;
    if (type == "label") return static_cast<std::size_t>(header.labelBytes);
    if (type == "tensor") return 9 * scalar;
    if (type == "symmTensor") return 6 * scalar;
    if (type == "sphericalTensor") return scalar;
    if (type == "diagTensor") return 3 * scalar;
    if (type == "vector2D") return 2 * scalar;
    if (type == "bool") return 1;
    return 0;
}

void FoamTokenizer::skipSpaceAndComments()
{
    while (position_ < text_.size()) {
        char c = text_[position_];
        if (c == '\n') {
            ++line_;
            ++position_;
        } else if (isSpace(c)) {
            ++position_;
        } else if (c == '/' && position_ + 1 < text_.size() && text_[position_ + 1] == '/') {
            while (position_ < text_.size() && text_[position_] != '\n') ++position_;
        } else if (c == '/' && position_ + 1 < text_.size() && text_[position_ + 1] == '*') {
            const int startLine = line_;
            position_ += 2;
            bool closed = false;
            while (position_ < text_.size()) {
                if (text_[position_] == '*' && position_ + 1 < text_.size() && text_[position_ + 1] == '/') {
                    position_ += 2;
                    closed = true;
                    break;
                }
                if (text_[position_] == '\n') ++line_;
                ++position_;
            }
            if (!closed) fail(startLine, "unterminated comment: '/*' without a closing '*/'");
        } else {
            return;
        }
    }
}

void FoamTokenizer::readString(Token& token)
{
    const int startLine = line_;
    ++position_;  // opening quote
    std::string content;
    bool escaped = false;
    while (true) {
        if (position_ >= text_.size()) fail(startLine, "unterminated string: no closing '\"' before the end of the file");
        char c = text_[position_++];
        if (c == '"') {
            if (escaped) {
                content.back() = '"';
                escaped = false;
                continue;
            }
            break;
        }
        if (c == '\n') {
            ++line_;
            if (escaped) {  // line continuation
                content.pop_back();
                escaped = false;
                continue;
            }
            fail(startLine, "unterminated string: found a line break before the closing '\"'");
        }
        escaped = (c == '\\') ? !escaped : false;
        content.push_back(c);
    }
    token.kind = Token::Kind::String;
    token.text = std::move(content);
    token.line = startLine;
}

void FoamTokenizer::readWordOrNumber(Token& token)
{
    const std::size_t start = position_;
    const char first = text_[position_];
    token.line = line_;

    // ${...}: everything up to the matching '}'.
    if (first == '$' && position_ + 1 < text_.size() && text_[position_ + 1] == '{') {
        std::size_t end = text_.find('}', position_);
        std::size_t lineBreak = text_.find('\n', position_);
        if (end == std::string_view::npos || (lineBreak != std::string_view::npos && lineBreak < end)) {
            fail(line_, "unterminated variable '${': no closing '}' on the same line");
        }
        position_ = end + 1;
        token.kind = Token::Kind::Word;
        token.text = std::string(text_.substr(start, position_ - start));
        return;
    }

    const bool numberLike = isDigit(first) ||
                            ((first == '-' || first == '+' || first == '.') && position_ + 1 < text_.size() &&
                             (isDigit(text_[position_ + 1]) ||
                              (text_[position_ + 1] == '.' && position_ + 2 < text_.size() && isDigit(text_[position_ + 2]))));
    if (numberLike) {
        std::size_t end = position_;
        while (end < text_.size()) {
            char c = text_[end];
            if (isDigit(c) || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-') {
                ++end;
            } else {
                break;
            }
        }
        const bool followedByWordCharacter =
            end < text_.size() && !endsWord(text_[end]) && text_[end] != '(' && text_[end] != ')' && text_[end] != ',' &&
            !(text_[end] == '/' && end + 1 < text_.size() && (text_[end + 1] == '/' || text_[end + 1] == '*'));
        if (!followedByWordCharacter) {
            double value = 0.0;
            bool isInteger = false;
            std::string_view spelled = text_.substr(position_, end - position_);
            if (parseNumber(spelled, value, isInteger)) {
                position_ = end;
                token.kind = Token::Kind::Number;
                token.text = std::string(spelled);
                token.number = value;
                token.isInteger = isInteger;
                return;
            }
        }
        // Not a number after all: read it as a word.
    }

    int depth = 0;
    while (position_ < text_.size()) {
        char c = text_[position_];
        if (endsWord(c)) break;
        if (c == '/' && position_ + 1 < text_.size() && (text_[position_ + 1] == '/' || text_[position_ + 1] == '*')) break;
        if (c == '(') {
            ++depth;
        } else if (c == ')') {
            if (depth == 0) break;
            --depth;
        } else if (c == ',' && depth == 0) {
            break;
        }
        ++position_;
    }
    token.kind = Token::Kind::Word;
    token.text = std::string(text_.substr(start, position_ - start));
}

bool FoamTokenizer::readBinaryList(Token& token)
{
    // Called with binaryState_ == 2, after skipping space: the binary block starts here.
    binaryState_ = 0;
    const std::size_t byteCount = static_cast<std::size_t>(binaryCount_) * binaryElementBytes_;
    token.kind = Token::Kind::Binary;
    token.line = line_;
    token.text.clear();
    token.number = 0.0;
    token.isInteger = false;
    if (position_ >= text_.size() || text_[position_] != '(') {
        if (binaryCount_ == 0) return true;  // OpenFOAM writes no parentheses for an empty binary list
        fail(line_, "binary list of " + std::to_string(binaryCount_) + " elements: expected '(' after the count");
    }
    const std::size_t dataStart = position_ + 1;
    if (dataStart + byteCount >= text_.size()) {
        fail(line_, "binary list of " + std::to_string(binaryCount_) + " elements needs " + std::to_string(byteCount) +
                        " bytes but the file ends after " + std::to_string(text_.size() - dataStart));
    }
    if (text_[dataStart + byteCount] != ')') {
        fail(line_, "binary list of " + std::to_string(binaryCount_) +
                        " elements: expected ')' after its data (the count disagrees with the data, or the file is not " +
                        "binary as its header says)");
    }
    token.text.assign(text_.data() + dataStart, byteCount);
    position_ = dataStart + byteCount + 1;
    return true;
}

bool FoamTokenizer::next(Token& token)
{
    if (binaryState_ == 2 && !header_.isBinary()) {
        if (packAsciiList(token)) return true;
    }
    if (binaryState_ == 2) {
        // Only whitespace separates the count from the '(' of the binary block.
        while (position_ < text_.size() && isSpace(text_[position_])) {
            if (text_[position_] == '\n') ++line_;
            ++position_;
        }
        return readBinaryList(token);
    }

    skipSpaceAndComments();
    if (position_ >= text_.size()) return false;

    token.number = 0.0;
    token.isInteger = false;
    const char c = text_[position_];
    if (c == '(' || c == ')' || c == '{' || c == '}' || c == '[' || c == ']' || c == ';' || c == ',') {
        token.kind = Token::Kind::Punctuation;
        token.text.assign(1, c);
        token.line = line_;
        ++position_;
    } else if (c == '"') {
        readString(token);
    } else if (c == '#' && position_ + 1 < text_.size() && text_[position_ + 1] == '{') {
        fail(line_, "'#{ ... #}' code blocks are not supported by rbm (they need OpenFOAM's run-time compiler)");
    } else {
        readWordOrNumber(token);
    }

    // Binary-list detection, and in ascii files the detection of big lists to pack.
    if (token.kind == Token::Kind::Word) {
        binaryElementBytes_ = binaryElementBytes(token.text, header_);
        if (!header_.isBinary()) {
            const bool packable = (token.text == "List<scalar>" || token.text == "List<vector>") ? header_.scalarBytes == 8
                                                                                                 : token.text == "List<label>";
            if (!packable) binaryElementBytes_ = 0;
        }
        binaryState_ = binaryElementBytes_ > 0 ? 1 : 0;
        if (binaryState_ == 1) binaryListWord_ = token.text;
    } else if (binaryState_ == 1 && token.kind == Token::Kind::Number && token.isInteger && token.number >= 0 &&
               (header_.isBinary() || token.number >= static_cast<double>(packedListThreshold))) {
        // A size beyond 32-bit labels made the conversion below undefined and the byte count
        // wrap around (found by fuzzing: `List<vector> 3e125`-like spellings of integers).
        if (token.number > static_cast<double>(std::numeric_limits<std::int32_t>::max())) {
            fail(token.line, "the size " + token.text + " of a " + binaryListWord_ + " is larger than 32-bit labels can count");
        }
        binaryCount_ = static_cast<long long>(token.number);
        binaryCountLine_ = token.line;
        binaryState_ = 2;
    } else {
        binaryState_ = 0;
    }
    return true;
}

double FoamTokenizer::readAsciiNumber(bool integer)
{
    skipSpaceAndComments();
    const std::size_t start = position_;
    while (position_ < text_.size()) {
        const char c = text_[position_];
        if (isSpace(c) || c == '(' || c == ')' || c == ';' || c == '{' || c == '}' || c == '/') break;
        ++position_;
    }
    const std::string_view spelled = text_.substr(start, position_ - start);
    double value = 0.0;
    bool isInteger = false;
    if (!parseNumber(spelled, value, isInteger) || (integer && !isInteger)) {
        const std::string found = spelled.empty() ? (position_ < text_.size() ? std::string(1, text_[position_]) : "end of file")
                                                  : std::string(spelled);
        fail(line_, std::string("expected ") + (integer ? "an integer" : "a number") + " in the " + binaryListWord_ +
                        " of size " + std::to_string(binaryCount_) + " but found '" + found + "'");
    }
    return value;
}

bool FoamTokenizer::packAsciiList(Token& token)
{
    skipSpaceAndComments();
    if (position_ >= text_.size() || text_[position_] != '(') {
        binaryState_ = 0;  // `N{value}` or something else: ordinary tokens
        return false;
    }
    binaryState_ = 0;
    const int openLine = line_;
    ++position_;
    const bool isVector = binaryListWord_ == "List<vector>";
    const bool isLabel = binaryListWord_ == "List<label>";
    const std::size_t count = static_cast<std::size_t>(binaryCount_);
    // The packed bytes are allocated before the elements are read: the size must be one the
    // rest of the text can hold (at least "0 " per number, "(0 0 0)" per vector), or a corrupt
    // size such as 2000000000 allocates gigabytes (found by fuzzing).
    const std::size_t smallestElement = isVector ? 7 : 2;
    if (count > (text_.size() - position_) / smallestElement + 1) {
        fail(binaryCountLine_, "the size " + std::to_string(count) + " of a " + binaryListWord_ +
                                   " is larger than the rest of the file can hold (" +
                                   std::to_string(text_.size() - position_) + " bytes)");
    }
    std::string bytes;
    bytes.resize(count * binaryElementBytes_);
    char* out = bytes.data();
    auto disagree = [&](std::size_t listed, bool more) {
        fail(binaryCountLine_, "the size " + std::to_string(count) + " of a " + binaryListWord_ + " disagrees with the " +
                                   (more ? "more than " + std::to_string(listed) : std::to_string(listed)) +
                                   " elements listed");
    };
    for (std::size_t i = 0; i < count; ++i) {
        skipSpaceAndComments();
        if (position_ >= text_.size()) fail(openLine, "unterminated " + binaryListWord_ + ": the '(' opened here is never closed");
        if (text_[position_] == ')') disagree(i, false);
        if (isVector) {
            if (text_[position_] != '(') {
                fail(line_, "expected '(' starting element " + std::to_string(i) + " of a " + binaryListWord_);
            }
            ++position_;
            for (int c = 0; c < 3; ++c) {
                const double component = readAsciiNumber(false);
                std::memcpy(out, &component, sizeof(double));
                out += sizeof(double);
            }
            skipSpaceAndComments();
            if (position_ >= text_.size() || text_[position_] != ')') {
                fail(line_, "expected ')' closing element " + std::to_string(i) + " (a vector of 3 components) of a " +
                                binaryListWord_);
            }
            ++position_;
        } else if (isLabel) {
            const double value = readAsciiNumber(true);
            if (header_.labelBytes == 4) {
                if (value < -2147483648.0 || value > 2147483647.0) fail(line_, "label does not fit in 32 bits");
                const auto label = static_cast<std::int32_t>(value);
                std::memcpy(out, &label, 4);
                out += 4;
            } else {
                const auto label = static_cast<std::int64_t>(value);
                std::memcpy(out, &label, 8);
                out += 8;
            }
        } else {
            const double value = readAsciiNumber(false);
            std::memcpy(out, &value, sizeof(double));
            out += sizeof(double);
        }
    }
    skipSpaceAndComments();
    if (position_ >= text_.size()) fail(openLine, "unterminated " + binaryListWord_ + ": the '(' opened here is never closed");
    if (text_[position_] != ')') disagree(count, true);
    ++position_;
    token.kind = Token::Kind::Binary;
    token.text = std::move(bytes);
    token.line = openLine;
    token.number = 0.0;
    token.isInteger = false;
    return true;
}

std::vector<Token> FoamTokenizer::readAll()
{
    std::vector<Token> tokens;
    Token token;
    while (next(token)) tokens.push_back(token);
    return tokens;
}

} // namespace rbm::io

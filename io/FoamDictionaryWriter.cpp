#include "FoamDictionaryWriter.hpp"

#include "FoamListIO.hpp"
#include "FoamTokenizer.hpp"
#include "KeywordPattern.hpp"

#include <charconv>
#include <cstring>

namespace rbm::io {

namespace {

// Components of one element of List<T> for the types written as groups of scalars.
int componentCount(std::string_view type)
{
    if (type == "scalar" || type == "sphericalTensor") return 1;
    if (type == "vector2D") return 2;
    if (type == "vector" || type == "diagTensor") return 3;
    if (type == "symmTensor") return 6;
    if (type == "tensor") return 9;
    return 0;
}

void appendQuoted(std::string& out, const std::string& text)
{
    out += '"';
    for (char c : text) {
        if (c == '"') out += '\\';
        out += c;
    }
    out += '"';
}

double scalarAt(const char* bytes, std::size_t scalarBytes)
{
    if (scalarBytes == 4) {
        float f;
        std::memcpy(&f, bytes, 4);
        return f;
    }
    double d;
    std::memcpy(&d, bytes, 8);
    return d;
}

// Appends the decoded elements of a binary list (the parentheses included).
void appendBinaryList(std::string& out, const Token& data, std::string_view listWord, std::size_t count, int precision)
{
    auto unknown = [&]() {
        throw InputError("", data.line, "cannot write binary data of " + std::to_string(data.text.size()) + " bytes as a " +
                                            std::string(listWord) + " of size " + std::to_string(count));
    };
    if (listWord.size() < 7 || listWord.substr(0, 5) != "List<" || listWord.back() != '>') unknown();
    const std::string_view type = listWord.substr(5, listWord.size() - 6);
    const bool multiLine = count > 10;
    if (count == 0) {
        out += "()";
        return;
    }
    if (data.text.size() % count != 0) unknown();
    const std::size_t elementBytes = data.text.size() / count;
    out += multiLine ? "\n(\n" : "(";
    const char* bytes = data.text.data();
    for (std::size_t i = 0; i < count; ++i) {
        if (i > 0 && !multiLine) out += ' ';
        const char* element = bytes + i * elementBytes;
        if (type == "label") {
            if (elementBytes == 4) {
                std::int32_t value;
                std::memcpy(&value, element, 4);
                appendLabel(out, value);
            } else if (elementBytes == 8) {
                std::int64_t value;
                std::memcpy(&value, element, 8);
                appendLabel(out, value);
            } else {
                unknown();
            }
        } else if (type == "bool") {
            if (elementBytes != 1) unknown();
            out += *element != 0 ? '1' : '0';
        } else {
            const int components = componentCount(type);
            if (components == 0) unknown();
            const std::size_t scalarBytes = elementBytes / static_cast<std::size_t>(components);
            if ((scalarBytes != 4 && scalarBytes != 8) || scalarBytes * static_cast<std::size_t>(components) != elementBytes) unknown();
            if (components > 1) out += '(';
            for (int c = 0; c < components; ++c) {
                if (c > 0) out += ' ';
                appendScalar(out, scalarAt(element + static_cast<std::size_t>(c) * scalarBytes, scalarBytes), precision);
            }
            if (components > 1) out += ')';
        }
        if (multiLine) out += '\n';
    }
    out += multiLine ? ")\n" : ")";
}

std::string shortestNumber(double value)
{
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

Token numberToken(double value)
{
    Token token;
    token.kind = Token::Kind::Number;
    token.text = shortestNumber(value);
    token.number = value;
    token.isInteger = token.text.find_first_of(".eE") == std::string::npos;
    return token;
}

Token countToken(std::size_t count)
{
    Token token;
    token.kind = Token::Kind::Number;
    token.text = std::to_string(count);
    token.number = static_cast<double>(count);
    token.isInteger = true;
    return token;
}

Token wordToken(const std::string& word)
{
    Token token;
    token.kind = Token::Kind::Word;
    token.text = word;
    return token;
}

Token punctuationToken(char c)
{
    Token token;
    token.kind = Token::Kind::Punctuation;
    token.text.assign(1, c);
    return token;
}

// True when `word` has more '(' than ')' (the tokenizer keeps balanced parentheses in words).
bool leavesParenthesisOpen(std::string_view word)
{
    int depth = 0;
    for (char c : word) {
        if (c == '(') ++depth;
        if (c == ')' && depth > 0) --depth;
    }
    return depth > 0;
}

} // namespace

bool keywordNeedsQuotes(std::string_view keyword)
{
    // Unquoted, the keyword must read back as the one word it is: not a number ("12"), a
    // directive ("#x"), a variable ("$x"), the header ("FoamFile"), nor text that ends a
    // word or starts a comment (found by fuzzing: such keywords were written bare and did not
    // parse again).
    bool readsBackAsWord = !keyword.empty() && keyword.front() != '#' && keyword.front() != '$' && keyword != "FoamFile";
    if (readsBackAsWord) {
        try {
            FoamTokenizer tokenizer(keyword, "");
            Token token;
            readsBackAsWord = tokenizer.next(token) && token.kind == Token::Kind::Word && token.text == keyword &&
                              !tokenizer.next(token);
        } catch (const InputError&) {
            readsBackAsWord = false;
        }
    }
    if (!readsBackAsWord) return true;
    // A word that looks like an expression but is none (`a++`, `?a$`) stays bare: quoted, it
    // would be rejected as an invalid expression when read again (found by fuzzing).
    std::string reason;
    if (isPatternKeyword(keyword) && !isValidPattern(std::string(keyword), reason)) return false;
    // Expressions are quoted, as OpenFOAM treats only quoted keywords as expressions; so are
    // quotes, which OpenFOAM's words may not hold.
    return keyword.find_first_of("'*?|[]^$\\+") != std::string_view::npos;
}

void appendTokens(std::string& out, const std::vector<Token>& tokens, int precision)
{
    bool first = true;
    for (std::size_t i = 0; i < tokens.size(); ++i) {
        const Token& token = tokens[i];
        // No space before ')' or ']', unless the previous token is a word with an unclosed '('
        // ("b(" from `(b( )`): written as `b()`, the word would swallow the ')' when read
        // again (found by fuzzing).
        const bool closing = (token.isPunctuation(')') || token.isPunctuation(']')) &&
                             !(i > 0 && tokens[i - 1].kind == Token::Kind::Word && leavesParenthesisOpen(tokens[i - 1].text));
        const bool afterOpening = i > 0 && (tokens[i - 1].isPunctuation('(') || tokens[i - 1].isPunctuation('['));
        const bool afterMultiLineList = !out.empty() && out.back() == '\n';
        if (!first && !closing && !afterOpening && !afterMultiLineList && token.kind != Token::Kind::Binary) out += ' ';
        first = false;
        switch (token.kind) {
        case Token::Kind::String: appendQuoted(out, token.text); break;
        case Token::Kind::Binary: {
            if (i < 2 || tokens[i - 1].kind != Token::Kind::Number || tokens[i - 2].kind != Token::Kind::Word) {
                throw InputError("", token.line, "binary data without a preceding 'List<T> N'");
            }
            // The count was already written; a multi-line list puts it on its own line.
            const std::size_t count = static_cast<std::size_t>(tokens[i - 1].number);
            if (count > 10) {
                // Move the count to its own line, as OpenFOAM writes long lists.
                const std::size_t countLength = tokens[i - 1].text.size();
                out.erase(out.size() - countLength);
                while (!out.empty() && out.back() == ' ') out.pop_back();
                out += '\n';
                out += tokens[i - 1].text;
            }
            appendBinaryList(out, token, tokens[i - 2].text, count, precision);
            break;
        }
        default: out += token.text; break;
        }
    }
}

void appendEntry(std::string& out, const Entry& entry, int indent, int precision)
{
    const std::string padding(static_cast<std::size_t>(4 * indent), ' ');
    out += padding;
    const std::size_t keywordStart = out.size();
    if (keywordNeedsQuotes(entry.keyword())) {
        appendQuoted(out, entry.keyword());
    } else {
        out += entry.keyword();
    }
    const std::size_t keywordLength = out.size() - keywordStart;
    if (entry.isDictionary()) {
        out += '\n';
        out += padding;
        out += "{\n";
        appendDictionaryEntries(out, entry.dictionary(), indent + 1, precision);
        out += padding;
        out += "}\n";
        return;
    }
    if (!entry.tokens().empty()) {
        out.append(keywordLength < 16 ? 16 - keywordLength : 1, ' ');
        appendTokens(out, entry.tokens(), precision);
    }
    out += ";\n";
}

void appendDictionaryEntries(std::string& out, const Dictionary& dictionary, int indent, int precision)
{
    for (const Entry& entry : dictionary.entries()) appendEntry(out, entry, indent, precision);
}

Entry vectorFieldEntry(const std::string& keyword, std::span<const Vector3> values, bool allowUniform)
{
    std::vector<Token> tokens;
    bool uniform = allowUniform && !values.empty();
    for (std::size_t i = 1; i < values.size() && uniform; ++i) uniform = values[i] == values[0];
    if (uniform) {
        tokens = {wordToken("uniform"), punctuationToken('('), numberToken(values[0].x), numberToken(values[0].y),
                  numberToken(values[0].z), punctuationToken(')')};
    } else {
        Token data;
        data.kind = Token::Kind::Binary;
        static_assert(sizeof(Vector3) == 3 * sizeof(double));
        data.text.assign(reinterpret_cast<const char*>(values.data()), values.size_bytes());
        tokens = {wordToken("nonuniform"), wordToken("List<vector>"), countToken(values.size()),
                  std::move(data)};
    }
    return Entry(keyword, "", 0, std::move(tokens));
}

Entry wordEntry(const std::string& keyword, const std::string& word)
{
    return Entry(keyword, "", 0, std::vector<Token>{wordToken(word)});
}

} // namespace rbm::io

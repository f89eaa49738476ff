#include "FoamDictionary.hpp"

#include "CompressedFile.hpp"
#include "FoamTokenizer.hpp"
#include "KeywordPattern.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>

namespace rbm::io {

namespace fs = std::filesystem;

static_assert(std::endian::native == std::endian::little,
              "binary OpenFOAM files (arch LSB) are decoded by copying bytes; a big-endian host needs byte swapping");

namespace {

// Deeper nesting than this is certainly a broken file; the limit turns it into a clear
// error instead of a stack overflow of the recursive parser.
constexpr int maximumNestingDepth = 1000;
// Include chains longer than this are reported even when no file repeats (e.g. generated names).
constexpr std::size_t maximumIncludeDepth = 64;
// Most bytes (tokens and dictionaries) that `$variable` substitutions may copy while one file is
// parsed. Each substitution copies its entry, so a chain `a1 ($a0 $a0); a2 ($a1 $a1); ...`
// doubles at every line: 40 lines of text asked for terabytes (found by fuzzing). Real
// dictionaries copy kilobytes.
constexpr std::size_t maximumSubstitutedBytes = std::size_t{64} << 20;

std::string describe(const Token& token)
{
    switch (token.kind) {
    case Token::Kind::Word: return "word '" + token.text + "'";
    case Token::Kind::String: return "string \"" + token.text + "\"";
    case Token::Kind::Number: return "number " + token.text;
    case Token::Kind::Punctuation: return "'" + token.text + "'";
    case Token::Kind::Binary: return "binary data (" + std::to_string(token.text.size()) + " bytes)";
    }
    return "token";
}

std::string quoted(const std::string& text)
{
    std::string out = "\"";
    for (char c : text) {
        if (c == '"') out += '\\';
        out += c;
    }
    return out + '"';
}

bool parseInteger(const Token& token, std::int64_t& value)
{
    if (token.kind != Token::Kind::Number || !token.isInteger) return false;
    std::string_view text = token.text;
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    auto result = std::from_chars(text.data(), text.data() + text.size(), value);
    return result.ec == std::errc() && result.ptr == text.data() + text.size();
}

std::optional<bool> switchValue(const Token& token)
{
    if (token.kind != Token::Kind::Word && token.kind != Token::Kind::String) return std::nullopt;
    const std::string& w = token.text;
    if (w == "on" || w == "yes" || w == "true" || w == "y" || w == "t") return true;
    if (w == "off" || w == "no" || w == "false" || w == "n" || w == "f" || w == "none") return false;
    return std::nullopt;
}

std::string withoutGzSuffix(const std::string& name)
{
    if (name.size() > 3 && name.compare(name.size() - 3, 3, ".gz") == 0) return name.substr(0, name.size() - 3);
    return name;
}

std::string canonicalName(const fs::path& path)
{
    std::error_code error;
    fs::path canonical = fs::weakly_canonical(path, error);
    return error ? path.lexically_normal().string() : canonical.string();
}

// True when the first token of `text` (after comments) is the word FoamFile.
bool startsWithFoamFileHeader(std::string_view text, const std::string& fileName)
{
    FoamTokenizer tokenizer(text, fileName);
    Token first;
    return tokenizer.next(first) && first.isWord("FoamFile");
}

// What copying tokens or a dictionary costs, in bytes, for maximumSubstitutedBytes.
std::size_t footprint(const std::vector<Token>& tokens)
{
    std::size_t bytes = 0;
    for (const Token& token : tokens) bytes += sizeof(Token) + token.text.size();
    return bytes;
}

std::size_t footprint(const Dictionary& dictionary)
{
    std::size_t bytes = sizeof(Dictionary);
    for (const Entry& entry : dictionary.entries()) {
        bytes += sizeof(Entry) + entry.keyword().size() + (entry.isDictionary() ? footprint(entry.dictionary()) : footprint(entry.tokens()));
    }
    return bytes;
}

// A copy of `source` whose name, and the names of its sub-dictionaries, start at `name`.
Dictionary renamedCopy(const Dictionary& source, const std::string& name)
{
    Dictionary copy(name, source.file(), source.line());
    for (const Entry& entry : source.entries()) {
        if (entry.isDictionary()) {
            copy.set(Entry(entry.keyword(), entry.file(), entry.line(),
                           std::make_unique<Dictionary>(renamedCopy(entry.dictionary(), name + "/" + entry.keyword()))));
        } else {
            copy.set(entry);
        }
    }
    return copy;
}

enum class InputMode { Merge, Overwrite, Protect, Warn, Error };

// State shared by the parsers of a file and the files it includes.
struct ParseState {
    std::vector<Dictionary*> scopes;          // dictionaries being filled, outermost first
    std::vector<std::string> includeChain;    // canonical names of the files being read
    InputMode mode = InputMode::Merge;
    std::optional<InputMode> nextEntryMode;   // from #default, #overwrite, ... (one entry)
    fs::path topFile;
    int depth = 0;                            // dictionary nesting depth
    std::size_t substitutedBytes = 0;         // copied by $variable substitutions so far
};

// Recursive-descent parser over the tokens of one file.
class BodyParser {
public:
    BodyParser(const std::vector<Token>& tokens, std::string file, ParseState& state, FoamFileHeader header)
        : tokens_(tokens), file_(std::move(file)), state_(state), header_(std::move(header))
    {}

    // Entries up to the '}' closing a dictionary opened at `openLine` (nested) or to the end.
    void parseEntries(Dictionary& dictionary, bool nested, int openLine);
    // The body of boundary/zone files: [N] ( name { ... } ... ).
    std::vector<Entry> parseDictionaryList(Dictionary& root);

private:
    [[noreturn]] void fail(int line, const std::string& message) const { throw InputError(file_, line, message); }
    bool atEnd() const { return position_ >= tokens_.size(); }
    int lastLine() const { return tokens_.empty() ? 0 : tokens_.back().line; }

    void parseEntry(Dictionary& dictionary);
    // Kept out of parseEntry, which recurses through parseSubDictionary once per nesting level:
    // its frame is large (10 kB with AddressSanitizer), and 1000 levels of it overflowed an
    // 8 MB stack in the sanitizer build.
    [[gnu::noinline]] void parsePrimitiveEntry(Dictionary& dictionary, const Token& keyword);
    std::unique_ptr<Dictionary> parseSubDictionary(const Dictionary& parent, const Token& keyword);
    void parseDirective(Dictionary& dictionary);
    void include(Dictionary& dictionary, const Token& directive, bool optional);
    void remove(Dictionary& dictionary, const Token& directive);
    void mergeVariableDictionary(Dictionary& dictionary, const Token& variable);
    void addEntry(Dictionary& dictionary, Entry entry);
    // Counts `bytes` against maximumSubstitutedBytes; fails at `line` when over.
    void chargeSubstitution(std::size_t bytes, int line);

    // The entry a `$...` token names, or tokens of an environment variable of that name.
    const Entry* resolveVariable(const Token& variable, std::vector<Token>& environmentTokens) const;
    const Entry* findScoped(std::string_view name, const Token& variable) const;
    const Entry* findFromLevel(int level, std::string_view path, bool upward) const;
    std::string expandPathVariables(const std::string& text, int line) const;
    fs::path caseDirectory() const;

    const std::vector<Token>& tokens_;
    std::size_t position_ = 0;
    std::string file_;
    ParseState& state_;
    FoamFileHeader header_;
};

void BodyParser::parseEntries(Dictionary& dictionary, bool nested, int openLine)
{
    while (true) {
        if (atEnd()) {
            if (nested) {
                fail(openLine, "unterminated dictionary '" + dictionary.name() + "': the '{' opened here is never closed");
            }
            return;
        }
        const Token& token = tokens_[position_];
        if (token.isPunctuation('}')) {
            if (nested) {
                ++position_;
                return;
            }
            fail(token.line, "unexpected '}' without a matching '{'");
        }
        if (token.isPunctuation(';')) {  // stray ';' between entries: harmless, OpenFOAM skips it too
            ++position_;
            continue;
        }
        if (token.kind == Token::Kind::Word && token.text.front() == '#') {
            parseDirective(dictionary);
            continue;
        }
        if (token.kind == Token::Kind::Word && token.text.front() == '$') {
            ++position_;
            mergeVariableDictionary(dictionary, token);
            if (!atEnd() && tokens_[position_].isPunctuation(';')) ++position_;
            continue;
        }
        if (token.kind != Token::Kind::Word && token.kind != Token::Kind::String) {
            fail(token.line, "expected a keyword but found " + describe(token));
        }
        parseEntry(dictionary);
    }
}

std::unique_ptr<Dictionary> BodyParser::parseSubDictionary(const Dictionary& parent, const Token& keyword)
{
    const int openLine = tokens_[position_].line;
    ++position_;  // '{'
    if (state_.depth + 1 > maximumNestingDepth) {
        fail(openLine, "dictionaries nested deeper than " + std::to_string(maximumNestingDepth) + " levels");
    }
    auto sub = std::make_unique<Dictionary>(parent.name() + "/" + keyword.text, file_, keyword.line);
    state_.scopes.push_back(sub.get());
    ++state_.depth;
    parseEntries(*sub, true, openLine);
    --state_.depth;
    state_.scopes.pop_back();
    return sub;
}

void BodyParser::parseEntry(Dictionary& dictionary)
{
    const Token keyword = tokens_[position_++];
    if (keyword.kind == Token::Kind::String && isPatternKeyword(keyword.text)) {
        std::string reason;
        if (!isValidPattern(keyword.text, reason)) {
            fail(keyword.line, "keyword \"" + keyword.text + "\" is not a valid regular expression: " + reason);
        }
    }
    if (atEnd()) {
        fail(keyword.line, "keyword '" + keyword.text + "' has no value: expected a value and ';', or '{'");
    }
    if (tokens_[position_].isPunctuation('{')) {
        auto sub = parseSubDictionary(dictionary, keyword);
        addEntry(dictionary, Entry(keyword.text, file_, keyword.line, std::move(sub)));
        return;
    }
    parsePrimitiveEntry(dictionary, keyword);
}

void BodyParser::parsePrimitiveEntry(Dictionary& dictionary, const Token& keyword)
{
    // Primitive entry: tokens up to ';' outside brackets, with $variables expanded.
    std::vector<Token> value;
    std::vector<char> openers;
    std::vector<int> openerLines;
    const std::string entryName = "'" + keyword.text + "'";
    while (true) {
        if (atEnd()) {
            if (!openers.empty()) {
                fail(openerLines.back(), std::string("unterminated list in entry ") + entryName + ": the '" +
                                             openers.back() + "' opened here is never closed");
            }
            fail(value.empty() ? keyword.line : value.back().line,
                 "missing ';' at the end of entry " + entryName + " (end of file reached)");
        }
        const Token& token = tokens_[position_];
        if (token.kind == Token::Kind::Punctuation) {
            const char c = token.text[0];
            if (c == ';' && openers.empty()) {
                ++position_;
                break;
            }
            if (c == '(' || c == '[') {
                openers.push_back(c);
                openerLines.push_back(token.line);
            } else if (c == '{') {
                const bool afterCount = !value.empty() && value.back().kind == Token::Kind::Number && value.back().isInteger;
                if (openers.empty() && !afterCount) {
                    // `a 1  b { ... }`: the ';' after the value of a is missing.
                    const int line = value.size() >= 2 ? value[value.size() - 2].line : keyword.line;
                    fail(line, "missing ';' at the end of entry " + entryName + " (found '" + value.back().text +
                                   " {' on line " + std::to_string(token.line) + ")");
                }
                openers.push_back(c);
                openerLines.push_back(token.line);
            } else if (c == ')' || c == ']' || c == '}') {
                if (openers.empty()) {
                    if (c == '}') {
                        fail(value.empty() ? keyword.line : value.back().line,
                             "missing ';' at the end of entry " + entryName + " (found '}' on line " +
                                 std::to_string(token.line) + ")");
                    }
                    fail(token.line, std::string("unexpected '") + c + "' in entry " + entryName + " without a matching '" +
                                         (c == ')' ? '(' : '[') + "'");
                }
                const char open = openers.back();
                const char expected = open == '(' ? ')' : (open == '[' ? ']' : '}');
                if (c != expected) {
                    fail(token.line, std::string("expected '") + expected + "' to close the '" + open + "' opened on line " +
                                         std::to_string(openerLines.back()) + " but found '" + c + "'");
                }
                openers.pop_back();
                openerLines.pop_back();
            }
            if (openers.size() > static_cast<std::size_t>(maximumNestingDepth)) {
                fail(token.line, "lists nested deeper than " + std::to_string(maximumNestingDepth) + " levels");
            }
            value.push_back(token);
            ++position_;
            continue;
        }
        if (token.kind == Token::Kind::Word && token.text.front() == '$') {
            std::vector<Token> environmentTokens;
            const Entry* entry = resolveVariable(token, environmentTokens);
            ++position_;
            if (entry != nullptr && entry->isDictionary()) {
                // `key $dict;` copies the dictionary.
                if (value.empty() && openers.empty() && !atEnd() && tokens_[position_].isPunctuation(';')) {
                    ++position_;
                    chargeSubstitution(footprint(entry->dictionary()), token.line);
                    addEntry(dictionary,
                             Entry(keyword.text, file_, keyword.line,
                                   std::make_unique<Dictionary>(
                                       renamedCopy(entry->dictionary(), dictionary.name() + "/" + keyword.text))));
                    return;
                }
                fail(token.line, "variable " + token.text + " names a dictionary, which can only be used alone as a value ('" +
                                     keyword.text + " " + token.text + ";') or as an entry of its own ('" + token.text + ";')");
            }
            const std::vector<Token>& spliced = entry != nullptr ? entry->tokens() : environmentTokens;
            chargeSubstitution(footprint(spliced), token.line);
            for (Token t : spliced) {
                t.line = token.line;  // report errors where the variable is used
                value.push_back(std::move(t));
            }
            continue;
        }
        if (token.kind == Token::Kind::Word && token.text.front() == '#') {
            fail(token.line, "directive " + token.text + " in the value of entry " + entryName +
                                 " is not supported by rbm (it needs OpenFOAM's run-time evaluation)");
        }
        value.push_back(token);
        ++position_;
    }
    addEntry(dictionary, Entry(keyword.text, file_, keyword.line, std::move(value)));
}

void BodyParser::chargeSubstitution(std::size_t bytes, int line)
{
    state_.substitutedBytes += bytes;
    if (state_.substitutedBytes > maximumSubstitutedBytes) {
        fail(line, "$variable substitutions copy more than " + std::to_string(maximumSubstitutedBytes >> 20) +
                       " MB: variables that repeat other variables, each doubling the text?");
    }
}

void BodyParser::addEntry(Dictionary& dictionary, Entry entry)
{
    InputMode mode = state_.nextEntryMode.value_or(state_.mode);
    state_.nextEntryMode.reset();

    const Entry* existing = nullptr;
    for (const Entry& e : dictionary.entries()) {
        if (e.keyword() == entry.keyword()) {
            existing = &e;
            break;
        }
    }
    if (existing == nullptr) {
        dictionary.set(std::move(entry));
        return;
    }
    switch (mode) {
    case InputMode::Merge:
        if (existing->isDictionary() && entry.isDictionary()) {
            // Merge recursively: sub-dictionaries merge, primitive entries are replaced.
            ParseState mergeState;
            mergeState.mode = InputMode::Merge;
            BodyParser merger(tokens_, file_, mergeState, header_);
            Dictionary merged = existing->dictionary();
            for (const Entry& e : entry.dictionary().entries()) merger.addEntry(merged, e);
            dictionary.set(Entry(existing->keyword(), existing->file(), existing->line(),
                                 std::make_unique<Dictionary>(std::move(merged))));
        } else {
            dictionary.set(std::move(entry));
        }
        return;
    case InputMode::Overwrite: dictionary.set(std::move(entry)); return;
    case InputMode::Protect:
    case InputMode::Warn: return;  // keep the first definition (rbm has no warning channel in the library)
    case InputMode::Error:
        throw InputError(entry.file(), entry.line(),
                         "duplicate entry '" + entry.keyword() + "' (first defined at " + existing->file() + ":" +
                             std::to_string(existing->line()) + ") while '#inputMode error' is active");
    }
}

void BodyParser::parseDirective(Dictionary& dictionary)
{
    const Token directive = tokens_[position_++];
    const std::string& name = directive.text;
    auto argument = [&]() -> const Token& {
        if (atEnd()) fail(directive.line, "directive " + name + " needs an argument");
        return tokens_[position_++];
    };

    if (name == "#include" || name == "#includeIfPresent" || name == "#sinclude") {
        include(dictionary, directive, name != "#include");
    } else if (name == "#includeEtc") {
        const Token& file = argument();
        fail(directive.line, "#includeEtc \"" + file.text +
                                 "\" cannot be resolved: rbm does not search an OpenFOAM installation; copy the file "
                                 "into the case and use #include");
    } else if (name == "#includeFunc" || name == "#includeFuncIfPresent") {
        // Function objects (post-processing) do not concern mesh motion: the line is skipped.
        argument();
    } else if (name == "#inputMode") {
        const Token& mode = argument();
        if (mode.isWord("merge") || mode.isWord("default")) {
            state_.mode = InputMode::Merge;
        } else if (mode.isWord("overwrite")) {
            state_.mode = InputMode::Overwrite;
        } else if (mode.isWord("protect")) {
            state_.mode = InputMode::Protect;
        } else if (mode.isWord("warn")) {
            state_.mode = InputMode::Warn;
        } else if (mode.isWord("error")) {
            state_.mode = InputMode::Error;
        } else {
            fail(mode.line, "unknown #inputMode " + describe(mode) +
                                "; valid modes are merge, overwrite, protect, warn, error, default");
        }
    } else if (name == "#default") {
        state_.nextEntryMode = InputMode::Protect;
    } else if (name == "#overwrite") {
        state_.nextEntryMode = InputMode::Overwrite;
    } else if (name == "#merge") {
        state_.nextEntryMode = InputMode::Merge;
    } else if (name == "#warn") {
        state_.nextEntryMode = InputMode::Warn;
    } else if (name == "#error") {
        state_.nextEntryMode = InputMode::Error;
    } else if (name == "#remove") {
        remove(dictionary, directive);
    } else if (name == "#calc" || name == "#eval" || name == "#codeStream" || name == "#if" || name == "#ifeq" ||
               name == "#else" || name == "#endif" || name == "#neg") {
        fail(directive.line, "directive " + name + " is not supported by rbm (it needs OpenFOAM's run-time evaluation)");
    } else {
        fail(directive.line, "unknown directive '" + name +
                                 "'; rbm supports #include, #includeIfPresent, #sinclude, #includeEtc (reported as an "
                                 "error), #includeFunc (ignored), #inputMode, #remove, #default, #overwrite, #merge, "
                                 "#warn, #error");
    }
}

void BodyParser::remove(Dictionary& dictionary, const Token& directive)
{
    if (atEnd()) fail(directive.line, "#remove needs a keyword or a list of keywords");
    std::vector<std::string> keys;
    const Token& first = tokens_[position_++];
    if (first.isPunctuation('(')) {
        while (true) {
            if (atEnd()) fail(first.line, "unterminated list after #remove: the '(' opened here is never closed");
            const Token& t = tokens_[position_++];
            if (t.isPunctuation(')')) break;
            if (t.kind != Token::Kind::Word && t.kind != Token::Kind::String) {
                fail(t.line, "#remove expects keywords but found " + describe(t));
            }
            keys.push_back(t.text);
        }
    } else if (first.kind == Token::Kind::Word || first.kind == Token::Kind::String) {
        keys.push_back(first.text);
    } else {
        fail(first.line, "#remove expects a keyword or a list of keywords but found " + describe(first));
    }
    auto removed = [&](const std::string& keyword) {
        for (const std::string& key : keys) {
            if (key == keyword || (isPatternKeyword(key) && patternMatches(key, keyword))) return true;
        }
        return false;
    };
    Dictionary kept(dictionary.name(), dictionary.file(), dictionary.line());
    if (dictionary.hasHeader()) kept.setHeader(dictionary.header());
    for (const Entry& entry : dictionary.entries()) {
        if (!removed(entry.keyword())) kept.set(entry);
    }
    dictionary = std::move(kept);  // same object: the scope pointers stay valid
}

fs::path BodyParser::caseDirectory() const
{
    if (const char* fromEnvironment = std::getenv("FOAM_CASE")) return fromEnvironment;
    // The nearest folder above the top-level file that holds a system/ folder.
    fs::path folder = fs::absolute(state_.topFile).parent_path();
    for (fs::path candidate = folder; !candidate.empty(); candidate = candidate.parent_path()) {
        std::error_code error;
        if (fs::is_directory(candidate / "system", error)) return candidate;
        if (candidate == candidate.parent_path()) break;
    }
    return {};
}

std::string BodyParser::expandPathVariables(const std::string& text, int line) const
{
    std::string out;
    for (std::size_t i = 0; i < text.size();) {
        if (text[i] == '<') {
            const std::size_t close = text.find('>', i);
            if (close != std::string::npos) {
                const std::string tag = text.substr(i + 1, close - i - 1);
                if (tag == "case" || tag == "system" || tag == "constant") {
                    fs::path root = caseDirectory();
                    if (root.empty()) fail(line, "cannot expand <" + tag + "> in '" + text + "': no case folder found");
                    out += (tag == "case" ? root : root / tag).string();
                    i = close + 1;
                    continue;
                }
            }
        }
        if (text[i] != '$') {
            out += text[i++];
            continue;
        }
        std::size_t start = i + 1;
        std::size_t end = start;
        std::string name;
        if (start < text.size() && text[start] == '{') {
            end = text.find('}', start);
            if (end == std::string::npos) fail(line, "unterminated '${' in '" + text + "'");
            name = text.substr(start + 1, end - start - 1);
            ++end;
        } else {
            while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '_')) ++end;
            name = text.substr(start, end - start);
        }
        if (name == "FOAM_CASE" || name == "FOAM_CASESRC") {
            fs::path root = caseDirectory();
            if (root.empty()) fail(line, "cannot expand $" + name + " in '" + text + "': no case folder found");
            out += root.string();
        } else if (const char* value = std::getenv(name.c_str())) {
            out += value;
        } else {
            fail(line, "undefined environment variable $" + name + " in '" + text + "'");
        }
        i = end;
    }
    return out;
}

void BodyParser::include(Dictionary& dictionary, const Token& directive, bool optional)
{
    if (atEnd()) fail(directive.line, directive.text + " needs a file name");
    const Token& nameToken = tokens_[position_++];
    if (nameToken.kind != Token::Kind::String && nameToken.kind != Token::Kind::Word) {
        fail(nameToken.line, directive.text + " expects a file name but found " + describe(nameToken));
    }
    fs::path path = expandPathVariables(nameToken.text, nameToken.line);
    if (path.is_relative()) path = fs::path(file_).parent_path() / path;
    if (!existsMaybeCompressed(path)) {
        if (optional) return;
        fail(directive.line, "cannot find the file \"" + nameToken.text + "\" included here (looked for " + path.string() +
                                 ")");
    }
    const fs::path resolved = resolveMaybeCompressed(path);
    const std::string canonical = canonicalName(resolved);
    if (std::find(state_.includeChain.begin(), state_.includeChain.end(), canonical) != state_.includeChain.end()) {
        std::string chain;
        for (const std::string& f : state_.includeChain) chain += f + " -> ";
        fail(directive.line, "#include loop: " + chain + canonical);
    }
    if (state_.includeChain.size() >= maximumIncludeDepth) {
        fail(directive.line, "#include nested deeper than " + std::to_string(maximumIncludeDepth) + " files");
    }
    const std::string text = readFileContents(resolved);
    const std::string includedFile = resolved.string();
    FoamFileHeader header = header_;
    std::size_t offset = 0;
    int line = 1;
    if (startsWithFoamFileHeader(text, includedFile)) header = parseFoamFileHeader(text, includedFile, offset, line);
    const std::vector<Token> tokens = FoamTokenizer(text, includedFile, offset, line, header).readAll();

    state_.includeChain.push_back(canonical);
    BodyParser included(tokens, includedFile, state_, header);
    included.parseEntries(dictionary, false, 0);
    state_.includeChain.pop_back();
}

const Entry* BodyParser::findFromLevel(int level, std::string_view path, bool upward) const
{
    // Split at '.' or '/' into components; the first may be found in enclosing scopes.
    std::vector<std::string_view> components;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= path.size(); ++i) {
        if (i == path.size() || path[i] == '.' || path[i] == '/') {
            components.push_back(path.substr(start, i - start));
            start = i + 1;
        }
    }
    if (components.empty() || components.front().empty()) return nullptr;
    const Entry* entry = nullptr;
    for (int l = level; l >= 0; --l) {
        entry = state_.scopes[static_cast<std::size_t>(l)]->find(components.front());
        if (entry != nullptr || !upward) break;
    }
    for (std::size_t c = 1; c < components.size() && entry != nullptr; ++c) {
        if (!entry->isDictionary() || components[c].empty()) return nullptr;
        entry = entry->dictionary().find(components[c]);
    }
    return entry;
}

const Entry* BodyParser::findScoped(std::string_view name, const Token& variable) const
{
    const int innermost = static_cast<int>(state_.scopes.size()) - 1;
    if (name.empty()) return nullptr;
    if (name.front() == ':') return findFromLevel(0, name.substr(1), false);
    if (name.front() == '.') {
        std::size_t dots = 0;
        while (dots < name.size() && name[dots] == '.') ++dots;
        const int level = innermost - static_cast<int>(dots - 1);
        if (level < 0) fail(variable.line, "variable " + variable.text + " goes above the top-level dictionary");
        return findFromLevel(level, name.substr(dots), true);
    }
    // A literal keyword (which may itself contain dots) wins over a scoped path.
    for (int l = innermost; l >= 0; --l) {
        if (const Entry* entry = state_.scopes[static_cast<std::size_t>(l)]->find(name)) return entry;
    }
    if (name.find_first_of("./") != std::string_view::npos) return findFromLevel(innermost, name, true);
    return nullptr;
}

const Entry* BodyParser::resolveVariable(const Token& variable, std::vector<Token>& environmentTokens) const
{
    std::string_view name = std::string_view(variable.text).substr(1);
    if (!name.empty() && name.front() == '{') {
        name.remove_prefix(1);
        if (!name.empty() && name.back() == '}') name.remove_suffix(1);
    }
    if (const Entry* entry = findScoped(name, variable)) return entry;
    const std::string nameText(name);
    if (const char* value = std::getenv(nameText.c_str())) {
        environmentTokens = FoamTokenizer(value, file_, 0, variable.line).readAll();
        return nullptr;
    }
    fail(variable.line, "undefined variable " + variable.text + ": no entry '" + nameText +
                            "' in this dictionary, its parents, or the environment");
}

void BodyParser::mergeVariableDictionary(Dictionary& dictionary, const Token& variable)
{
    std::vector<Token> environmentTokens;
    const Entry* entry = resolveVariable(variable, environmentTokens);
    if (entry == nullptr || !entry->isDictionary()) {
        fail(variable.line, "variable " + variable.text +
                                " is used as an entry of its own, which needs a dictionary, but it names a value");
    }
    chargeSubstitution(footprint(entry->dictionary()), variable.line);
    const Dictionary copy = renamedCopy(entry->dictionary(), dictionary.name());
    for (const Entry& e : copy.entries()) addEntry(dictionary, e);
}

std::vector<Entry> BodyParser::parseDictionaryList(Dictionary& root)
{
    std::optional<std::int64_t> count;
    int countLine = 0;
    if (!atEnd() && tokens_[position_].kind == Token::Kind::Number) {
        std::int64_t n = 0;
        if (!parseInteger(tokens_[position_], n) || n < 0) {
            fail(tokens_[position_].line, "expected the number of entries but found " + describe(tokens_[position_]));
        }
        count = n;
        countLine = tokens_[position_].line;
        ++position_;
    }
    if (atEnd()) fail(lastLine(), "expected '(' starting the list of dictionaries but the file ends");
    const Token& open = tokens_[position_++];
    if (!open.isPunctuation('(')) fail(open.line, "expected '(' starting the list of dictionaries but found " + describe(open));

    std::vector<Entry> entries;
    while (true) {
        if (atEnd()) fail(open.line, "unterminated list of dictionaries: the '(' opened here is never closed");
        const Token& keyword = tokens_[position_];
        if (keyword.isPunctuation(')')) {
            ++position_;
            break;
        }
        if (keyword.kind != Token::Kind::Word && keyword.kind != Token::Kind::String) {
            fail(keyword.line, "expected the name of a dictionary but found " + describe(keyword));
        }
        ++position_;
        if (atEnd() || !tokens_[position_].isPunctuation('{')) {
            fail(keyword.line, "expected '{' after '" + keyword.text + "'");
        }
        auto sub = parseSubDictionary(root, keyword);
        entries.emplace_back(keyword.text, file_, keyword.line, std::move(sub));
    }
    if (!atEnd()) fail(tokens_[position_].line, "unexpected " + describe(tokens_[position_]) + " after the list of dictionaries");
    if (count && static_cast<std::size_t>(*count) != entries.size()) {
        fail(countLine, "the list count " + std::to_string(*count) + " disagrees with the " + std::to_string(entries.size()) +
                            " dictionaries listed");
    }
    return entries;
}

// ---- list decoding shared by the TokenStream readers ----

// `scalarsPerElement`: 1 for scalars and labels, 3 for vectors, 0 for lists that are never
// binary (words). The size of a binary element's scalars (4 or 8 bytes) follows from the byte
// count, so a list packed from an ascii file (FoamTokenizer) decodes whatever header the
// caller passes; the tokenizer already cut the data with the file's own header.
// `maxCount` bounds the size before anything is allocated: the size of a uniform list
// `N{value}` is not bounded by the text (a pointDisplacement with `2000000000{(0 0 0)}` asked for
// 48 GB; found by fuzzing).
template <class T, class ReadOne, class DecodeBinary>
std::vector<T> readListOf(TokenStream& stream, const std::string& what, ReadOne readOne, std::size_t scalarsPerElement,
                          DecodeBinary decode, std::size_t maxCount)
{
    if (!stream.atEnd() && stream.peek().kind == Token::Kind::Word && stream.peek().text.rfind("List<", 0) == 0) {
        stream.next();
    }
    const Token& first = stream.peek();
    std::vector<T> values;
    if (first.kind == Token::Kind::Number) {
        std::int64_t count = 0;
        if (!parseInteger(first, count) || count < 0) stream.fail("expected the size of a " + what + " but found " + describe(first));
        const int countLine = first.line;
        if (static_cast<std::uint64_t>(count) > maxCount) {
            stream.fail("the size " + std::to_string(count) + " of a " + what + " is larger than the " + std::to_string(maxCount) +
                        " elements expected here");
        }
        stream.next();
        if (stream.atEnd()) stream.fail("expected '(' after the size " + std::to_string(count) + " of a " + what);
        const Token& open = stream.peek();
        if (open.kind == Token::Kind::Binary) {
            stream.next();
            if (scalarsPerElement == 0) throw InputError(stream.file(), open.line, "a " + what + " cannot be stored as binary data");
            const std::size_t n = static_cast<std::size_t>(count);
            std::size_t elementBytes = 0;
            for (std::size_t width : {std::size_t{8}, std::size_t{4}}) {
                if (open.text.size() == n * scalarsPerElement * width) elementBytes = scalarsPerElement * width;
            }
            if (n == 0 && open.text.empty()) return values;
            if (elementBytes == 0) {
                throw InputError(stream.file(), countLine,
                                 "binary " + what + " of size " + std::to_string(count) + " needs " +
                                     std::to_string(n * scalarsPerElement * 8) + " (64-bit) or " +
                                     std::to_string(n * scalarsPerElement * 4) + " (32-bit) bytes but has " +
                                     std::to_string(open.text.size()));
            }
            values.resize(n);
            for (std::size_t i = 0; i < n; ++i) values[i] = decode(open.text.data() + i * elementBytes, elementBytes / scalarsPerElement, open.line);
            return values;
        }
        if (open.isPunctuation('{')) {
            stream.next();
            T value = readOne();
            stream.expectPunctuation('}');
            values.assign(static_cast<std::size_t>(count), value);
            return values;
        }
        if (!open.isPunctuation('(')) stream.fail("expected '(' after the size " + std::to_string(count) + " of a " + what + " but found " + describe(open));
        stream.next();
        values.reserve(static_cast<std::size_t>(std::min<std::int64_t>(count, 1 << 24)));
        while (true) {
            if (stream.atEnd()) throw InputError(stream.file(), open.line, "unterminated " + what + ": the '(' opened here is never closed");
            if (stream.peek().isPunctuation(')')) break;
            values.push_back(readOne());
        }
        stream.next();
        if (values.size() != static_cast<std::size_t>(count)) {
            throw InputError(stream.file(), countLine,
                             "the size " + std::to_string(count) + " of a " + what + " disagrees with the " +
                                 std::to_string(values.size()) + " elements listed");
        }
        return values;
    }
    if (!first.isPunctuation('(')) stream.fail("expected a " + what + " but found " + describe(first));
    const int openLine = first.line;
    stream.next();
    while (true) {
        if (stream.atEnd()) throw InputError(stream.file(), openLine, "unterminated " + what + ": the '(' opened here is never closed");
        if (stream.peek().isPunctuation(')')) break;
        values.push_back(readOne());
    }
    stream.next();
    if (values.size() > maxCount) {
        throw InputError(stream.file(), openLine,
                         "the " + what + " has " + std::to_string(values.size()) + " elements, more than the " +
                             std::to_string(maxCount) + " expected here");
    }
    return values;
}

// Without a size the caller expects, lists are bounded by what a 32-bit label can count.
constexpr std::size_t largestListSize = static_cast<std::size_t>(std::numeric_limits<Label>::max());

double decodeScalar(const char* bytes, int scalarBytes)
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

} // namespace

// ---------------------------------------------------------------------------------------
// TokenStream

TokenStream::TokenStream(const std::vector<Token>& tokens, std::string file, FoamFileHeader header)
    : tokens_(&tokens), file_(std::move(file)), header_(std::move(header))
{}

bool TokenStream::atEnd() const
{
    return position_ >= tokens_->size();
}

const Token& TokenStream::peek() const
{
    if (atEnd()) fail("unexpected end of the value");
    return (*tokens_)[position_];
}

const Token& TokenStream::next()
{
    const Token& token = peek();
    ++position_;
    return token;
}

void TokenStream::fail(const std::string& message) const
{
    int line = 0;
    if (!tokens_->empty()) line = atEnd() ? tokens_->back().line : (*tokens_)[position_].line;
    throw InputError(file_, line, message);
}

void TokenStream::expectPunctuation(char c)
{
    if (atEnd()) fail(std::string("expected '") + c + "' but the value ends");
    if (!peek().isPunctuation(c)) fail(std::string("expected '") + c + "' but found " + describe(peek()));
    ++position_;
}

double TokenStream::readScalar()
{
    if (atEnd()) fail("expected a number but the value ends");
    const Token& token = peek();
    if (token.kind != Token::Kind::Number) fail("expected a number but found " + describe(token));
    ++position_;
    return token.number;
}

Label TokenStream::readLabel()
{
    if (atEnd()) fail("expected an integer but the value ends");
    const Token& token = peek();
    std::int64_t value = 0;
    if (!parseInteger(token, value)) fail("expected an integer but found " + describe(token));
    if (value < std::numeric_limits<Label>::min() || value > std::numeric_limits<Label>::max()) {
        fail("integer " + token.text + " does not fit in a 32-bit label");
    }
    ++position_;
    return static_cast<Label>(value);
}

std::string TokenStream::readWord()
{
    if (atEnd()) fail("expected a word but the value ends");
    const Token& token = peek();
    if (token.kind != Token::Kind::Word) fail("expected a word but found " + describe(token));
    ++position_;
    return token.text;
}

std::string TokenStream::readWordOrString()
{
    if (atEnd()) fail("expected a word or a string but the value ends");
    const Token& token = peek();
    if (token.kind != Token::Kind::Word && token.kind != Token::Kind::String) {
        fail("expected a word or a string but found " + describe(token));
    }
    ++position_;
    return token.text;
}

bool TokenStream::readBool()
{
    if (atEnd()) fail("expected on/off, yes/no or true/false but the value ends");
    const Token& token = peek();
    std::optional<bool> value = switchValue(token);
    if (!value) fail("expected on/off, yes/no or true/false but found " + describe(token));
    ++position_;
    return *value;
}

Vector3 TokenStream::readVector()
{
    if (atEnd()) fail("expected a vector '(x y z)' but the value ends");
    if (!peek().isPunctuation('(')) fail("expected a vector '(x y z)' but found " + describe(peek()));
    ++position_;
    Vector3 v;
    v.x = readScalar();
    v.y = readScalar();
    v.z = readScalar();
    if (!atEnd() && !peek().isPunctuation(')')) fail("expected ')' closing a vector of 3 components but found " + describe(peek()));
    expectPunctuation(')');
    return v;
}

std::vector<double> TokenStream::readScalarList()
{
    return readScalarList(largestListSize);
}

std::vector<double> TokenStream::readScalarList(std::size_t maxCount)
{
    return readListOf<double>(
        *this, "scalar list", [&] { return readScalar(); }, 1,
        [](const char* bytes, std::size_t scalarBytes, int) { return decodeScalar(bytes, static_cast<int>(scalarBytes)); }, maxCount);
}

std::vector<Label> TokenStream::readLabelList()
{
    return readLabelList(largestListSize);
}

std::vector<Label> TokenStream::readLabelList(std::size_t maxCount)
{
    return readListOf<Label>(
        *this, "label list", [&] { return readLabel(); }, 1,
        [&](const char* bytes, std::size_t labelBytes, int line) -> Label {
            if (labelBytes == 4) {
                std::int32_t value;
                std::memcpy(&value, bytes, 4);
                return value;
            }
            std::int64_t value;
            std::memcpy(&value, bytes, 8);
            if (value < std::numeric_limits<Label>::min() || value > std::numeric_limits<Label>::max()) {
                throw InputError(file_, line, "label " + std::to_string(value) + " does not fit in 32 bits");
            }
            return static_cast<Label>(value);
        }, maxCount);
}

std::vector<Vector3> TokenStream::readVectorList()
{
    return readVectorList(largestListSize);
}

std::vector<Vector3> TokenStream::readVectorList(std::size_t maxCount)
{
    return readListOf<Vector3>(
        *this, "vector list", [&] { return readVector(); }, 3, [](const char* bytes, std::size_t scalarBytes, int) {
            const int size = static_cast<int>(scalarBytes);
            return Vector3{decodeScalar(bytes, size), decodeScalar(bytes + scalarBytes, size),
                           decodeScalar(bytes + 2 * scalarBytes, size)};
        }, maxCount);
}

std::vector<std::string> TokenStream::readWordList()
{
    return readWordList(largestListSize);
}

std::vector<std::string> TokenStream::readWordList(std::size_t maxCount)
{
    return readListOf<std::string>(
        *this, "word list", [&] { return readWordOrString(); }, 0,
        [](const char*, std::size_t, int) { return std::string(); }, maxCount);
}

// ---------------------------------------------------------------------------------------
// Entry

Entry::Entry(std::string keyword, std::string file, int line, std::vector<Token> tokens)
    : keyword_(std::move(keyword)), file_(std::move(file)), line_(line), tokens_(std::move(tokens))
{}

Entry::Entry(std::string keyword, std::string file, int line, std::unique_ptr<Dictionary> dictionary)
    : keyword_(std::move(keyword)), file_(std::move(file)), line_(line), dictionary_(std::move(dictionary))
{}

Entry::Entry(const Entry& other)
    : keyword_(other.keyword_), file_(other.file_), line_(other.line_), tokens_(other.tokens_),
      dictionary_(other.dictionary_ ? std::make_unique<Dictionary>(*other.dictionary_) : nullptr)
{}

Entry& Entry::operator=(const Entry& other)
{
    if (this != &other) {
        Entry copy(other);
        *this = std::move(copy);
    }
    return *this;
}

Entry::Entry(Entry&&) noexcept = default;
Entry& Entry::operator=(Entry&&) noexcept = default;
Entry::~Entry() = default;

const Dictionary& Entry::dictionary() const
{
    if (!dictionary_) throw InputError(file_, line_, "entry '" + keyword_ + "' is a value, not a dictionary");
    return *dictionary_;
}

Dictionary& Entry::dictionary()
{
    if (!dictionary_) throw InputError(file_, line_, "entry '" + keyword_ + "' is a value, not a dictionary");
    return *dictionary_;
}

const std::vector<Token>& Entry::tokens() const
{
    if (dictionary_) throw InputError(file_, line_, "entry '" + keyword_ + "' is a dictionary, not a value");
    return tokens_;
}

TokenStream Entry::stream(const FoamFileHeader& header) const
{
    return TokenStream(tokens(), file_, header);
}

std::string Entry::valueText() const
{
    std::string text;
    for (const Token& token : tokens()) {
        if (!text.empty()) text += ' ';
        switch (token.kind) {
        case Token::Kind::String: text += quoted(token.text); break;
        case Token::Kind::Binary: text += "<" + std::to_string(token.text.size()) + " bytes of binary data>"; break;
        default: text += token.text; break;
        }
    }
    return text;
}

// ---------------------------------------------------------------------------------------
// Dictionary

Dictionary::Dictionary(std::string name, std::string file, int line)
    : name_(std::move(name)), file_(std::move(file)), line_(line)
{}

Dictionary Dictionary::readFile(const fs::path& path)
{
    const fs::path resolved = resolveMaybeCompressed(path);
    return parseText(readFileContents(resolved), resolved.string());
}

Dictionary Dictionary::parseText(std::string_view text, const std::string& fileName)
{
    Dictionary dictionary(withoutGzSuffix(fs::path(fileName).filename().string()), fileName, 0);
    FoamFileHeader header;
    std::size_t offset = 0;
    int line = 1;
    if (startsWithFoamFileHeader(text, fileName)) {
        header = parseFoamFileHeader(text, fileName, offset, line);
        dictionary.setHeader(header);
    }
    const std::vector<Token> tokens = FoamTokenizer(text, fileName, offset, line, header).readAll();

    ParseState state;
    state.scopes.push_back(&dictionary);
    state.includeChain.push_back(canonicalName(fileName));
    state.topFile = fileName;
    BodyParser parser(tokens, fileName, state, header);
    parser.parseEntries(dictionary, false, 0);
    return dictionary;
}

std::vector<std::string> Dictionary::keywords() const
{
    std::vector<std::string> result;
    result.reserve(entries_.size());
    for (const Entry& entry : entries_) result.push_back(entry.keyword());
    return result;
}

const Entry* Dictionary::find(std::string_view keyword) const
{
    for (const Entry& entry : entries_) {
        if (entry.keyword() == keyword) return &entry;
    }
    const std::string name(keyword);
    for (auto it = entries_.rbegin(); it != entries_.rend(); ++it) {
        if (isPatternKeyword(it->keyword()) && patternMatches(it->keyword(), name)) return &*it;
    }
    return nullptr;
}

const Entry& Dictionary::lookup(std::string_view keyword) const
{
    if (const Entry* entry = find(keyword)) return *entry;
    throw InputError(file_, line_, "keyword " + std::string(keyword) + " is undefined in dictionary " + name_);
}

const Dictionary* Dictionary::findDictionary(std::string_view keyword) const
{
    const Entry* entry = find(keyword);
    return entry != nullptr && entry->isDictionary() ? &entry->dictionary() : nullptr;
}

const Dictionary& Dictionary::subDictionary(std::string_view keyword) const
{
    const Entry& entry = lookup(keyword);
    if (!entry.isDictionary()) {
        throw InputError(entry.file(), entry.line(),
                         "entry '" + entry.keyword() + "' in dictionary " + name_ + " should be a dictionary '{ ... }'");
    }
    return entry.dictionary();
}

template <class T>
T Dictionary::get(std::string_view keyword) const
{
    const Entry& entry = lookup(keyword);
    auto fail = [&](const std::string& expected) {
        const std::string found = entry.isDictionary() ? std::string("a dictionary") : "'" + entry.valueText() + "'";
        throw InputError(entry.file(), entry.line(),
                         "entry '" + entry.keyword() + "' in dictionary " + name_ + ": expected " + expected + " but found " + found);
    };
    if (entry.isDictionary()) {
        if constexpr (std::is_same_v<T, double>) fail("a number");
        else if constexpr (std::is_same_v<T, Label> || std::is_same_v<T, std::int64_t>) fail("an integer");
        else if constexpr (std::is_same_v<T, std::string>) fail("a word");
        else if constexpr (std::is_same_v<T, bool>) fail("on/off, yes/no or true/false");
        else fail("a vector (x y z)");
    }
    const std::vector<Token>& tokens = entry.tokens();
    if constexpr (std::is_same_v<T, double>) {
        if (tokens.size() != 1 || tokens[0].kind != Token::Kind::Number) fail("a single number");
        return tokens[0].number;
    } else if constexpr (std::is_same_v<T, Label> || std::is_same_v<T, std::int64_t>) {
        std::int64_t value = 0;
        if (tokens.size() != 1 || !parseInteger(tokens[0], value)) fail("a single integer");
        if constexpr (std::is_same_v<T, Label>) {
            if (value < std::numeric_limits<Label>::min() || value > std::numeric_limits<Label>::max()) {
                fail("an integer that fits in 32 bits");
            }
        }
        return static_cast<T>(value);
    } else if constexpr (std::is_same_v<T, std::string>) {
        if (tokens.size() != 1 || (tokens[0].kind != Token::Kind::Word && tokens[0].kind != Token::Kind::String)) {
            fail("a single word");
        }
        return tokens[0].text;
    } else if constexpr (std::is_same_v<T, bool>) {
        std::optional<bool> value = tokens.size() == 1 ? switchValue(tokens[0]) : std::nullopt;
        if (!value) fail("on/off, yes/no or true/false");
        return *value;
    } else {
        static_assert(std::is_same_v<T, Vector3>, "Dictionary::get supports double, Label, int64_t, string, bool, Vector3");
        TokenStream stream(tokens, entry.file());
        if (tokens.size() != 5) fail("a vector (x y z)");
        try {
            return stream.readVector();
        } catch (const InputError&) {
            fail("a vector (x y z)");
        }
        return {};
    }
}

template double Dictionary::get<double>(std::string_view) const;
template Label Dictionary::get<Label>(std::string_view) const;
template std::int64_t Dictionary::get<std::int64_t>(std::string_view) const;
template std::string Dictionary::get<std::string>(std::string_view) const;
template bool Dictionary::get<bool>(std::string_view) const;
template Vector3 Dictionary::get<Vector3>(std::string_view) const;

void Dictionary::set(Entry entry)
{
    for (Entry& existing : entries_) {
        if (existing.keyword() == entry.keyword()) {
            existing = std::move(entry);
            return;
        }
    }
    entries_.push_back(std::move(entry));
}

// ---------------------------------------------------------------------------------------
// Free functions

FoamFileHeader parseFoamFileHeader(std::string_view text, const std::string& fileName, std::size_t& bodyOffset,
                                   int& bodyLine)
{
    FoamTokenizer tokenizer(text, fileName);
    Token token;
    if (!tokenizer.next(token) || !token.isWord("FoamFile")) {
        throw InputError(fileName, token.line > 0 ? token.line : 1,
                         "expected a 'FoamFile { ... }' header at the start of the file");
    }
    const int headerLine = token.line;
    if (!tokenizer.next(token) || !token.isPunctuation('{')) {
        throw InputError(fileName, headerLine, "expected '{' after FoamFile");
    }
    FoamFileHeader header;
    while (true) {
        Token keyword;
        if (!tokenizer.next(keyword)) throw InputError(fileName, headerLine, "unterminated FoamFile header: no closing '}'");
        if (keyword.isPunctuation('}')) break;
        if (keyword.kind != Token::Kind::Word) {
            throw InputError(fileName, keyword.line, "expected a keyword in the FoamFile header but found " + describe(keyword));
        }
        std::vector<Token> value;
        while (true) {
            Token t;
            if (!tokenizer.next(t)) throw InputError(fileName, keyword.line, "unterminated FoamFile header: no closing '}'");
            if (t.isPunctuation(';')) break;
            if (t.isPunctuation('}')) {
                throw InputError(fileName, value.empty() ? keyword.line : value.back().line,
                                 "missing ';' at the end of entry '" + keyword.text + "' in the FoamFile header");
            }
            value.push_back(t);
        }
        const std::string& key = keyword.text;
        auto single = [&]() -> std::string {
            if (value.size() != 1 || value[0].kind == Token::Kind::Punctuation) {
                throw InputError(fileName, keyword.line, "FoamFile entry '" + key + "' should be a single word or string");
            }
            return value[0].text;
        };
        if (key == "format") {
            header.format = single();
            if (header.format != "ascii" && header.format != "binary") {
                throw InputError(fileName, keyword.line, "FoamFile format '" + header.format + "' should be ascii or binary");
            }
        } else if (key == "class") {
            header.className = single();
        } else if (key == "object") {
            header.object = single();
        } else if (key == "location") {
            header.location = single();
        } else if (key == "arch") {
            // e.g. "LSB;label=32;scalar=64"
            const std::string arch = single();
            std::stringstream parts(arch);
            std::string part;
            while (std::getline(parts, part, ';')) {
                if (part == "MSB") {
                    throw InputError(fileName, keyword.line, "big-endian (MSB) binary files are not supported: arch \"" + arch + "\"");
                }
                const std::size_t equals = part.find('=');
                if (equals == std::string::npos) continue;
                const std::string name = part.substr(0, equals);
                const std::string bits = part.substr(equals + 1);
                if (name == "label") {
                    if (bits != "32" && bits != "64") {
                        throw InputError(fileName, keyword.line, "arch label size '" + bits + "' should be 32 or 64");
                    }
                    header.labelBytes = bits == "32" ? 4 : 8;
                } else if (name == "scalar") {
                    if (bits != "32" && bits != "64") {
                        throw InputError(fileName, keyword.line, "arch scalar size '" + bits + "' should be 32 or 64");
                    }
                    header.scalarBytes = bits == "32" ? 4 : 8;
                }
            }
        }
        // version, note and other entries carry nothing a reader needs.
    }
    bodyOffset = tokenizer.offset();
    bodyLine = tokenizer.line();
    return header;
}

std::vector<Entry> readDictionaryListFile(const fs::path& path, FoamFileHeader& header)
{
    const fs::path resolved = resolveMaybeCompressed(path);
    const std::string fileName = resolved.string();
    const std::string text = readFileContents(resolved);
    header = FoamFileHeader{};
    std::size_t offset = 0;
    int line = 1;
    if (startsWithFoamFileHeader(text, fileName)) header = parseFoamFileHeader(text, fileName, offset, line);
    const std::vector<Token> tokens = FoamTokenizer(text, fileName, offset, line, header).readAll();

    Dictionary root(withoutGzSuffix(resolved.filename().string()), fileName, 0);
    ParseState state;
    state.scopes.push_back(&root);
    state.includeChain.push_back(canonicalName(resolved));
    state.topFile = resolved;
    BodyParser parser(tokens, fileName, state, header);
    return parser.parseDictionaryList(root);
}

} // namespace rbm::io

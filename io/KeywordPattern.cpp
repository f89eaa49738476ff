#include "KeywordPattern.hpp"

#include <algorithm>
#include <memory>
#include <mutex>
#include <regex>
#include <unordered_map>
#include <vector>

namespace rbm::io {

bool isPatternKeyword(std::string_view keyword)
{
    return keyword.find_first_of("*+?|[]^$\\(){}") != std::string_view::npos;
}

namespace {

// Longest keyword used as a regular expression. std::regex compiles by recursion over the
// pattern: thousands of nested groups overflowed the stack (found by fuzzing). OpenFOAM's
// keyword expressions are a few dozen characters.
constexpr std::size_t maximumPatternLength = 1024;

// ECMAScript syntax, matched by libstdc++'s breadth-first executor (__polynomial): time
// linear in the name for a given pattern, where the default backtracking one took exponential
// time ("(a|a)*b" against a name of 40 a's hung the parser) and recursed once per character
// of the name (a 100 000-character name overflowed the stack); both found by fuzzing. That
// mode refuses back-references, which keyword expressions have no use for.
constexpr std::regex::flag_type patternSyntax = std::regex::ECMAScript
#if defined(__GLIBCXX__)
                                                | std::regex_constants::__polynomial
#endif
    ;

// Most automaton states a keyword expression may need (see automatonSize).
constexpr std::size_t maximumAutomatonSize = 10000;

// An upper bound of the number of states std::regex builds for `pattern`, at most `limit`;
// `backReference` tells whether the pattern has a back-reference `\n`.
// It copies the atom before a counted repetition x{n}, x{n,}, x{n,m} about max(n, m) times, so
// nested counts multiply: `(a{300}){300}` built 90 000 states (seconds) before std::regex gave
// up at its limit of 100 000. And libstdc++ reads those counts, and back-reference numbers,
// into a long without an overflow check: `a{2222222222222222222}` and `(a)\2222222222222222222`
// were undefined behaviour in its compiler. Found by fuzzing; numbers are read here saturating.
std::size_t automatonSize(const std::string& pattern, std::size_t limit, bool& backReference)
{
    backReference = false;
    const std::size_t size = pattern.size();
    const auto add = [limit](std::size_t a, std::size_t b) { return std::min(limit, a + b); };  // a, b <= limit
    const auto multiply = [limit](std::size_t a, std::size_t b) { return b != 0 && a > limit / b ? limit : a * b; };
    const auto isDigit = [&](std::size_t i) { return i < size && pattern[i] >= '0' && pattern[i] <= '9'; };
    const auto number = [&](std::size_t& i) {
        std::size_t value = 0;
        for (; isDigit(i); ++i) value = std::min(limit, 10 * value + static_cast<std::size_t>(pattern[i] - '0'));
        return value;
    };
    struct Sequence {
        std::size_t states = 0;     // of the sequence so far
        std::size_t lastAtom = 0;   // of its last atom, which a repetition count copies
    };
    std::vector<Sequence> open(1);  // the sequences of the groups being read, outermost first
    const auto atom = [&](std::size_t states) {
        open.back().states = add(open.back().states, states);
        open.back().lastAtom = states;
    };
    for (std::size_t i = 0; i < size;) {
        const char c = pattern[i++];
        if (c == '\\') {
            if (isDigit(i) && pattern[i] != '0') {
                backReference = true;
                number(i);
            } else if (i < size) {
                ++i;
            }
            atom(1);
        } else if (c == '[') {               // a class, up to its ']' (a ']' first is literal)
            if (i < size && pattern[i] == '^') ++i;
            if (i < size && pattern[i] == ']') ++i;
            for (; i < size && pattern[i] != ']'; ++i) {
                if (pattern[i] == '\\') ++i;
            }
            ++i;
            atom(1);
        } else if (c == '(') {
            open.emplace_back();
        } else if (c == ')' && open.size() > 1) {
            const std::size_t group = open.back().states;
            open.pop_back();
            atom(add(group, 2));
        } else if (c == '{') {
            const std::size_t low = number(i);
            std::size_t high = low;
            if (i < size && pattern[i] == ',') {
                ++i;
                if (isDigit(i)) high = number(i);
            }
            Sequence& sequence = open.back();
            const std::size_t copies = multiply(sequence.lastAtom, add(std::max(low, high), 1));
            sequence.states = add(sequence.states - std::min(sequence.states, sequence.lastAtom), copies);
            sequence.lastAtom = copies;
        } else if (c == '|') {
            atom(1);
            open.back().lastAtom = 0;
        } else {
            atom(1);
        }
    }
    std::size_t states = 0;
    for (const Sequence& sequence : open) states = add(states, sequence.states);
    return states;
}

std::shared_ptr<const std::regex> compile(const std::string& pattern, std::string& error)
{
    if (pattern.size() > maximumPatternLength) {
        error = "longer than " + std::to_string(maximumPatternLength) + " characters";
        return nullptr;
    }
    bool backReference = false;
    if (automatonSize(pattern, maximumAutomatonSize + 1, backReference) > maximumAutomatonSize) {
        error = "its repetition counts make it too large (more than " + std::to_string(maximumAutomatonSize) + " states)";
        return nullptr;
    }
    if (backReference) {  // refused by the breadth-first matcher too, but only after reading the number
        error = "back-references (\\1, \\2, ...) are not supported";
        return nullptr;
    }
    try {
        return std::make_shared<const std::regex>(pattern, patternSyntax);
    } catch (const std::regex_error& e) {
        error = e.what();
        return nullptr;
    }
}

// Compiling a std::regex costs far more than matching; dictionaries look the same few
// patterns up many times (one per patch), so compiled patterns are kept. The cache is
// emptied when it grows large: a program reading many dictionaries must not grow forever.
std::shared_ptr<const std::regex> compiledPattern(const std::string& pattern)
{
    static std::mutex mutex;
    static std::unordered_map<std::string, std::shared_ptr<const std::regex>> cache;
    std::lock_guard<std::mutex> lock(mutex);
    auto found = cache.find(pattern);
    if (found != cache.end()) return found->second;
    if (cache.size() >= 4096) cache.clear();
    std::string error;
    return cache.emplace(pattern, compile(pattern, error)).first->second;
}

} // namespace

bool patternMatches(const std::string& pattern, const std::string& name)
{
    const std::shared_ptr<const std::regex> expression = compiledPattern(pattern);
    return expression != nullptr && std::regex_match(name, *expression);
}

bool isValidPattern(const std::string& pattern, std::string& error)
{
    return compile(pattern, error) != nullptr;
}

} // namespace rbm::io

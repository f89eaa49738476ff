#pragma once
// Regular-expression keywords of OpenFOAM dictionaries, e.g. `"(inlet|outlet)"` or `".*Wall"`.
//
// OpenFOAM treats a keyword as a pattern when it was written as a quoted string containing
// regular-expression characters. rbm's Entry keeps only the keyword's text, so the test is on
// the text alone: a keyword is a pattern when it contains one of  * + ? | [ ] ^ $ \ ( ) { }.
// '.' alone does not count (literal keywords such as "a.b" stay literal). Literal matches
// always win over pattern matches, so a word such as `div(phi,U)` that passes this test still
// finds its own entry first.

#include <string>
#include <string_view>

namespace rbm::io {

// True when `keyword` is used as a regular expression for lookups.
bool isPatternKeyword(std::string_view keyword);

// True when the pattern keyword `pattern` matches all of `name` (std::regex_match, ECMAScript,
// as OpenFOAM's regExp matches whole words). False when `pattern` is not a valid expression.
bool patternMatches(const std::string& pattern, const std::string& name);

// True when `pattern` compiles as a regular expression; `error` receives the reason otherwise.
bool isValidPattern(const std::string& pattern, std::string& error);

} // namespace rbm::io

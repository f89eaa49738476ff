#include "KeywordPattern.hpp"

#include <memory>
#include <mutex>
#include <regex>
#include <unordered_map>

namespace rbm::io {

bool isPatternKeyword(std::string_view keyword)
{
    return keyword.find_first_of("*+?|[]^$\\(){}") != std::string_view::npos;
}

namespace {

// Compiling a std::regex costs far more than matching; dictionaries look the same few
// patterns up many times (one per patch), so compiled patterns are kept.
const std::regex* compiledPattern(const std::string& pattern)
{
    static std::mutex mutex;
    static std::unordered_map<std::string, std::unique_ptr<std::regex>> cache;
    std::lock_guard<std::mutex> lock(mutex);
    auto found = cache.find(pattern);
    if (found != cache.end()) return found->second.get();
    std::unique_ptr<std::regex> compiled;
    try {
        compiled = std::make_unique<std::regex>(pattern, std::regex::ECMAScript);
    } catch (const std::regex_error&) {
        compiled = nullptr;
    }
    return cache.emplace(pattern, std::move(compiled)).first->second.get();
}

} // namespace

bool patternMatches(const std::string& pattern, const std::string& name)
{
    const std::regex* expression = compiledPattern(pattern);
    return expression != nullptr && std::regex_match(name, *expression);
}

bool isValidPattern(const std::string& pattern, std::string& error)
{
    try {
        std::regex expression(pattern, std::regex::ECMAScript);
        return true;
    } catch (const std::regex_error& e) {
        error = e.what();
        return false;
    }
}

} // namespace rbm::io

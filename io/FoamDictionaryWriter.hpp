#pragma once
// Writing dictionary entries back as OpenFOAM text (ascii): boundaryField entries of field
// files, or any Dictionary a program builds.
//
// Layout follows OpenFOAM's: `keyword` padded to 16 columns, 4 spaces per indentation level,
// sub-dictionaries as
//     name
//     {
//         ...
//     }
// and a list of more than 10 elements written one element a line after its size, shorter
// ones on one line (`2((0 0 0) (1 0 0))`). Binary list data (from a binary file, or packed
// by FoamTokenizer) is written in ascii with `precision` significant digits; the sizes of its
// labels and scalars (32 or 64 bits) follow from the byte count and the list's size, so no
// header is needed. Other numbers are written as they were spelled.

#include "FoamDictionary.hpp"

#include <span>
#include <string>

namespace rbm::io {

// Appends the value tokens of an entry, separated by single spaces (none inside brackets).
// Throws rbm::InputError for binary data that is not a list of a known type.
void appendTokens(std::string& out, const std::vector<Token>& tokens, int precision);

// Appends one entry (primitive: `keyword value;`, dictionary: `keyword { ... }`) at
// indentation level `indent`.
void appendEntry(std::string& out, const Entry& entry, int indent, int precision);

// Appends every entry of `dictionary` at indentation level `indent`.
void appendDictionaryEntries(std::string& out, const Dictionary& dictionary, int indent, int precision);

// True when `keyword` must be written in quotes (regular expressions, spaces, ...).
bool keywordNeedsQuotes(std::string_view keyword);

// An entry `keyword nonuniform List<vector> N(...)` holding `values` exactly (as packed
// doubles; written out with the writer's precision), or `keyword uniform (x y z)` when all
// values are equal and `allowUniform` is true (what OpenFOAM writes for a uniform field).
Entry vectorFieldEntry(const std::string& keyword, std::span<const Vector3> values, bool allowUniform = true);

// A single-token entry `keyword word;`.
Entry wordEntry(const std::string& keyword, const std::string& word);

} // namespace rbm::io

// libFuzzer target dictionaryFuzzer: The OpenFOAM dictionary parser (Dictionary::parseText), typed accessors, write/re-parse round trip.
// Entry function rbm::fuzz::parseDictionary (FuzzEntryPoints.hpp); see fuzz/README.md.

#include "FuzzTarget.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    return rbm::fuzz::runFuzzInput(rbm::fuzz::parseDictionary, data, size);
}

// libFuzzer target pointFieldFuzzer: A pointVectorField file read against a fixed 30-point mesh with 5 patches.
// Entry function rbm::fuzz::readPointField (FuzzEntryPoints.hpp); see fuzz/README.md.

#include "FuzzTarget.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    return rbm::fuzz::runFuzzInput(rbm::fuzz::readPointField, data, size);
}

// libFuzzer target binaryListFuzzer: Binary polyMesh list bodies behind a generated binary header (first byte: list kind, label 32/64, scalar 64/32).
// Entry function rbm::fuzz::readBinaryListFile (FuzzEntryPoints.hpp); see fuzz/README.md.

#include "FuzzTarget.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    return rbm::fuzz::runFuzzInput(rbm::fuzz::readBinaryListFile, data, size);
}

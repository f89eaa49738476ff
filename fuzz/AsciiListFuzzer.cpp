// libFuzzer target asciiListFuzzer: One polyMesh list file (points, faces, owner, neighbour, ...) with its FoamFile header; the header's class picks the reader.
// Entry function rbm::fuzz::readListFile (FuzzEntryPoints.hpp); see fuzz/README.md.

#include "FuzzTarget.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    return rbm::fuzz::runFuzzInput(rbm::fuzz::readListFile, data, size);
}

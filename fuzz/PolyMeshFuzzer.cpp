// libFuzzer target polyMeshFuzzer: A whole polyMesh folder (points, faces, owner, neighbour, boundary, zones), the files separated by @@file@@.
// Entry function rbm::fuzz::readPolyMeshFolder (FuzzEntryPoints.hpp); see fuzz/README.md.

#include "FuzzTarget.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    return rbm::fuzz::runFuzzInput(rbm::fuzz::readPolyMeshFolder, data, size);
}

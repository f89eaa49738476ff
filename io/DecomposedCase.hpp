#pragma once
// OpenFOAM's decomposed cases: decomposePar writes processor0 … processorN−1, each holding the
// polyMesh of one subdomain (constant/polyMesh) whose faces shared with another subdomain form
// patches of type `processor` (entries myProcNo, neighbProcNo), and beside it
// pointProcAddressing: every local point's label in the undecomposed mesh.

#include "PolyMesh.hpp"

#include <filesystem>
#include <vector>

namespace rbm::io {

// How many processor folders the case has (0: not decomposed). Throws InputError naming the
// case when they are not numbered 0 … N−1 without a gap.
int countProcessorFolders(const std::filesystem::path& caseDir);

struct ProcessorMesh {
    PolyMesh mesh;
    std::vector<Label> pointProcAddressing;  // per point: its label in the undecomposed mesh
};

// processorN/constant/polyMesh and its pointProcAddressing. Throws InputError naming the file
// for a missing file, a list that is not one label per point, a negative label, or a
// processor patch whose myProcNo is not N.
ProcessorMesh readProcessorMesh(const std::filesystem::path& caseDir, int processor);

} // namespace rbm::io

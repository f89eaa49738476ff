#pragma once
// OpenFOAM's decomposePar on a benchmark case: the case split into processor0 … processorN−1 by
// `method simple`, the decomposition both decomposed programs then run on.

#include "OpenFoamMoveMesh.hpp"
#include "Record.hpp"

#include <array>
#include <filesystem>
#include <string>

namespace rbm::benchmark {

namespace fs = std::filesystem;

// The subdomains along x, y and z: 2 → (2 1 1), 4 → (2 2 1), 8 → (2 2 2), else (N 1 1).
std::array<int, 3> simpleSplit(int ranks);

std::string simpleSplitText(int ranks);

// system/decomposeParDict: numberOfSubdomains `ranks`, method simple, simpleSplit(ranks).
std::string decomposeParDict(int ranks);

// The boundaryField of 0/pointDisplacement as OpenFOAM v1912's decomposePar can map it. Its
// mapping constructor of solidBodyMotionDisplacement builds the motion function from the
// `<function>Coeffs` sub-dictionary alone ("Entry 'solidBodyMotionFunction' not found in
// ...top.rotatingMotionCoeffs"), so the keyword is repeated inside that sub-dictionary (where
// the function, whose coefficients may be the dictionary itself, takes no notice of it).
std::string decomposableBoundaryField(const std::string& boundaryField);

// Writes system/decomposeParDict into the case `dir` (made by writeMotionCase) and runs
// decomposePar there (log.decomposePar): wall time, peak MiB, exit code.
Record runDecomposePar(const OpenFoam& openfoam, const fs::path& dir, int ranks);

// Copies the processor folders of `from` (their constant/ and 0/) and its decomposeParDict (which
// a -parallel OpenFOAM run reads) into the case `to`.
void copyProcessorFolders(const fs::path& from, const fs::path& to, int ranks);

} // namespace rbm::benchmark

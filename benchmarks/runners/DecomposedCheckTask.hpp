#pragma once
// The child task that checks a decomposed run against the undecomposed mesh: every processor's
// moved points (processorK/1/polyMesh/points, placed by processorK/constant/polyMesh/
// pointProcAddressing) gathered into the whole mesh and evaluated (QualityEvaluator, as the
// serial runs' results are), and, for rbm, compared with the serial rbmMoveMesh run's points:
// the largest |decomposed − serial| over every processor's points, relative to the point's
// shortest edge in the initial mesh.

#include "Record.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace rbm::benchmark {

namespace fs = std::filesystem;

// polyMeshDir: the undecomposed constant/polyMesh; decomposedCase: the case with processor*/1;
// serialCase: a serial run's case with 1/polyMesh/points, or empty (no comparison). Every key of
// the record starts with `prefix`.
Record runDecomposedCheckTask(const fs::path& polyMeshDir, const fs::path& decomposedCase, int ranks,
                              const fs::path& serialCase, const std::string& prefix);

} // namespace rbm::benchmark

#pragma once
// A case decomposed over N ranks (decomposePar, method simple) and moved by both decomposed
// programs on the same decomposition, one step each, whole processes:
//   mpirun -np N rbmMoveMesh -case <rbm> -parallel -noVTK   (each rank reads processor<rank> only)
//   mpirun -np N moveMesh -case <openfoam> -parallel         (OpenFOAM's displacementLaplacian)
// Each rank's peak resident memory, wall and CPU time (MpiRun.hpp), then the moved points checked
// in a child (DecomposedCheckTask.hpp): quality of both, rbm's difference to its serial run.

#include "OpenFoamMoveMesh.hpp"
#include "Record.hpp"

#include <filesystem>
#include <string>

namespace rbm::benchmark {

namespace fs = std::filesystem;

struct DecomposedRunInput {
    std::string caseName;
    fs::path polyMeshSource;   // the undecomposed constant/polyMesh
    std::string boundaryField; // of 0/pointDisplacement (stepBoundaryField)
    std::string diffusivity;   // OpenFOAM's displacementLaplacian
    fs::path rbmMoveMesh;      // the program
    fs::path serialRbmCase;    // the serial rbmMoveMesh run's case (1/polyMesh/points), or empty
    fs::path logDir;
};

// Runs both programs in dir/rbm and dir/openfoam; the record's keys: ranks, decomposition,
// decomposePar*, rbm* and openfoam* (addMpiRun), the rbm log line's figures (rbmLog*), and the
// check's (rbm.*, openfoam.*, rbmMaxDifferenceToSerial*).
Record runDecomposedMoveMesh(const OpenFoam& openfoam, const DecomposedRunInput& input, const fs::path& dir, int ranks);

} // namespace rbm::benchmark

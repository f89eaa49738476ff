#pragma once
// What rbmMoveMesh writes for a time: <time>/polyMesh/points and <time>/pointDisplacement, the
// latter with the input's boundary conditions (so OpenFOAM reads the same case) and the current
// values of the prescribed patches (and of every patch whose entry had a value). Staged into a
// TimeFolderWriter; the caller commits (a decomposed run only when every rank staged its part).

#include "ControlDict.hpp"
#include "PointVectorField.hpp"
#include "PolyMesh.hpp"
#include "TimeFolderWriter.hpp"
#include "Vector3.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace rbm::app {

// `prescribedPatches`: per patch, 1 when its condition prescribes its points.
void stageMeshMotion(io::TimeFolderWriter& folder, const std::string& timeName, const PolyMesh& mesh,
                     const std::vector<Vector3>& points, const std::vector<Vector3>& displacement,
                     const io::PointVectorField& boundaryField, const std::vector<std::uint8_t>& prescribedPatches,
                     const io::ControlDict& control);

} // namespace rbm::app

#pragma once
// A case's motion as OpenFOAM case files: the folder moveMesh and rbmMoveMesh run on, and the
// boundaryField of 0/pointDisplacement (one step of the case's motion, or the airfoil pitching).

#include "PolyMesh.hpp"
#include "Vector3.hpp"
#include <filesystem>
#include <string>
#include <vector>

namespace rbm::benchmark {

namespace fs = std::filesystem;

// Pitch (5 deg about the quarter chord) and plunge (0.05 chord) in phase, period 1 s
// (tutorials/naca4415Pitching).
std::string pitchingBoundaryField(const std::string& airfoilType);

std::string pointDisplacementFile(const std::string& boundaryField);

void writeText(const fs::path& file, const std::string& text);

std::string foamHeader(const std::string& className, const std::string& location, const std::string& object);

std::string vectorText(const Vector3& v);

// boundaryField of the single-step motion of a case: the moving patch turns by the case's angle
// during t = 0 -> 1 (rotatingMotion, omega in rad/s), fixed patches stay, free ones are
// zeroGradient.
std::string stepBoundaryField(const std::string& caseName, const std::vector<Patch>& patches);

// A case folder for moveMesh or rbmMoveMesh: mesh, controlDict, schemes, solution, the
// dynamicMeshDict body and 0/pointDisplacement.
void writeMotionCase(const fs::path& dir, const fs::path& polyMeshSource, const std::string& application,
                     const std::string& dynamicMeshBody, const std::string& boundaryField, int steps);

} // namespace rbm::benchmark

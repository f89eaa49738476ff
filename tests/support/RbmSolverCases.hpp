#pragma once
// Builders shared by the tests of the OpenFOAM-facing solver: a rigidBodyMotionSolver over a
// mesh, made from the entries of its rigidBodyMotionSolverCoeffs, and the boundary-layer
// airfoil fixture (tests/data/airfoilBoundaryLayer).

#include "FoamDictionary.hpp"
#include "MotionSolverRegistry.hpp"
#include "PolyMesh.hpp"
#include "PolyMeshReader.hpp"

#include <filesystem>
#include <memory>
#include <string>

namespace rbm::test {

// A rigidBodyMotionSolver over `mesh` with the given coefficient entries (the body of
// rigidBodyMotionSolverCoeffs) and, optionally, 0/pointDisplacement's boundaryField.
inline std::unique_ptr<motion::MotionSolver> makeSolver(const PolyMesh& mesh, const std::string& coefficients,
                                                        const io::Dictionary* pointDisplacement = nullptr)
{
    const io::Dictionary dict = io::Dictionary::parseText(
        "motionSolver rigidBodyMotionSolver;\nrigidBodyMotionSolverCoeffs\n{\n" + coefficients + "\n}\n",
        "constant/dynamicMeshDict");
    return motion::builtinMotionSolvers().create(mesh, dict, pointDisplacement, "/nonexistent/case");
}

// The NACA4415 fixture with a hexahedral boundary layer, read once per test program.
inline const PolyMesh& airfoilMesh()
{
    static const PolyMesh mesh =
        io::readPolyMesh(std::filesystem::path(RBM_TEST_DATA_DIR) / "airfoilBoundaryLayer" / "constant" / "polyMesh");
    return mesh;
}

} // namespace rbm::test

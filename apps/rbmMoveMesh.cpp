// rbmMoveMesh: OpenFOAM's moveMesh with the rigid body motion (RBM) mesh-motion solver.
//
//   rbmMoveMesh [-case DIR] [-noVTK] [-parallel] [-writeInvalid] [-help] [-version] [PETSc options]
//
// Moves the mesh of an OpenFOAM case from startTime to endTime: at every time step the
// boundary conditions of <time>/pointDisplacement are evaluated, the motion solver of
// constant/dynamicMeshDict computes the displacement of the other points, the quality of the
// moved mesh is checked, and at write times <time>/polyMesh/points, <time>/pointDisplacement
// and VTK output are written. Exit status: 0 success; 1 inverted cells, no convergence or a
// failure during the run; 2 bad input. Everything is in MoveMeshRun (testable without a
// process); see docs/rbmMoveMesh.md.

#include "MoveMeshRun.hpp"
#include "ReturnFreedMemory.hpp"

#include <iostream>

int main(int argc, char** argv)
{
    rbm::useOneHeapForAllThreads();   // before any thread starts
    return rbm::app::moveMeshMain(argc, argv, std::cout, std::cerr);
}

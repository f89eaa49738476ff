#pragma once
// The host's mesh, boundary and displacement arrays (HostMotionSolver.hpp's C++17 types) in the
// form rbm's core takes (PolyMesh, BoundaryDescription, Vector3) and back: shared by the host solvers of a whole mesh
// (HostMotionSolver) and of one rank's part of a decomposed mesh (HostPartMotionSolver).
// C++20, internal to rbm_host: the host never includes it.

#include "BoundaryDescription.hpp"
#include "HostMotionSolver.hpp"
#include "PolyMesh.hpp"

#include <vector>

namespace rbm::host {

// Throws std::invalid_argument when the arrays' sizes do not fit together.
PolyMesh toPolyMesh(const HostMesh& host);

// One entry per patch of `mesh`, its points in OpenFOAM's localPoints order and the host's
// sliding normals normalised. Throws std::invalid_argument for a wrong count of patches or of
// normals (`solverName` heads the message).
motion::BoundaryDescription toBoundaryDescription(const PolyMesh& mesh, const std::vector<HostPatchBoundary>& boundary,
                                                  const char* solverName);

// `displacement`: 3 values a point (x0 y0 z0 x1 ...), as many as `vectors` has points.
void readVectors(const double* displacement, std::vector<Vector3>& vectors);
void writeVectors(const std::vector<Vector3>& vectors, double* displacement);

} // namespace rbm::host

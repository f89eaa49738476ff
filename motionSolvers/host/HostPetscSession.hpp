#pragma once
// The one PETSc session of every host solver in a process (HostMotionSolver,
// HostPartMotionSolver). C++20, internal to rbm_host.

#include "PetscSupport.hpp"

#include <memory>

namespace rbm::host {

// PETSc is initialised by the first solver that asks (after the host initialised MPI, if it
// does: PETSc then runs on the host's MPI_COMM_WORLD) and finalised when the last holder lets
// go, while the host's MPI is still up (OpenFOAM finalises MPI after its meshes are destroyed).
std::shared_ptr<motion::PetscSession> sharedPetscSession();

} // namespace rbm::host

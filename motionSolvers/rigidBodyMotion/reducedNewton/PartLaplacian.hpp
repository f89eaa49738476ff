#pragma once
// K⁻¹ of the reduced Newton method on one rank's part of a distributed 3D problem
// (RbmProblem::isPart; docs/parallel.md, "Distributed data"): the projected vector Laplacian
// P (K ⊗ I) P + s (I − P) (RbmProblem::projectSlidingBlocks) assembled by rows, each rank
// inserting the rows of its owned unknown nodes, into one PETSc matrix over the ranks, and
// solved by CG with PETSc's algebraic multigrid (GAMG, block size 3) to a relative tolerance,
// set up once when the part's solver is built. Its setup and every solve are collective.
//
// Unknown rows: each rank's owned unknown nodes in their part order, after the lower ranks'
// (one contiguous range per rank); a ghost unknown's row comes from its owner through the
// node exchange.
//
// PETSc options: prefix rbm_reduced_ as LaplacianPreconditioner (-rbm_reduced_pc_type hypre,
// -rbm_reduced_ksp_monitor, ...).

#include "PetscSupport.hpp"
#include "RbmProblem.hpp"

#include <memory>
#include <span>
#include <vector>

namespace rbm::motion {

class PartLaplacian {
public:
    // laplacian: K's scalar entries in the part problem's blockPattern() order
    // (coupledDisplacementLaplacian). Throws std::invalid_argument unless the problem is a 3D part.
    PartLaplacian(const RbmProblem& problem, std::span<const double> laplacian, double relativeTolerance);
    ~PartLaplacian();
    PartLaplacian(const PartLaplacian&) = delete;
    PartLaplacian& operator=(const PartLaplacian&) = delete;

    // z = (P (K ⊗ I) P)⁻¹ P r on the owned rows (3 per unknown node; ghost rows of z zero, of r
    // ignored); false if CG did not converge.
    bool apply(std::span<const double> r, std::span<double> z);
    // CG iterations of the last apply.
    int lastIterations() const { return lastIterations_; }

private:
    // Each unknown node's global row (−1 for prescribed nodes), ghosts' from their owners.
    std::vector<PetscInt> unknownRows() const;
    void assemble(std::span<const double> laplacian);

    const RbmProblem& problem_;
    PetscMat matrix_;
    PetscKsp solver_;
    PetscVec rightHandSide_, solution_;
    std::unique_ptr<InheritedOptions> options_;
    std::vector<double> projected_;
    int lastIterations_ = 0;
};

} // namespace rbm::motion

#pragma once
// The rigidBodyMotionSolver on one rank's part of a decomposed 3D mesh (docs/parallel.md,
// "The distributed run"): each MPI rank holds its processor mesh as decomposePar wrote it,
// the halo of cells around the points it owns (MeshPart), and the rows of those points. The
// same energy as the serial solver — node classes, weights and stiffening factors of every
// node and edge equal to the serial ones — minimised by the same reduced Newton iteration, its
// products, dot products and K⁻¹ (PartLaplacian) distributed; nothing is gathered but the
// stiffening's wall surface (PartStiffening.hpp).
//
// Per solve:
//   1. the prescribed values of every node, from the ranks whose own patch faces hold it
//      (PartBoundary.hpp);
//   2. `stiffening auto`'s rule (EdgeStiffening.hpp) with its decisions reduced over the
//      ranks: rigid when every rank finds its pieces of the prescribed patches rigid, moved
//      when any rank saw a patch move;
//   3. the reduced Newton solve, warm-started from the previous one;
//   4. every point of the processor mesh gets its node's displacement.
//
// Refused here (rbm::InputError naming rigidBodyMotionSolverCoeffs' file): a variant other
// than the default reduced Newton solver, pseudo-3D (2D) meshes and cyclic patches. Not done
// on parts (the serial solver's later stages): sub-step halving, untangling, and putting
// points of curved unconstrained patches back onto their surface (warnings() names such
// patches); an inverted step stops the run as any invalid step does.

#include "BoundaryDescription.hpp"
#include "FoamDictionary.hpp"
#include "MeshPart.hpp"
#include "MotionSolver.hpp"
#include "PolyMesh.hpp"
#include "RigidBodyMotionOptions.hpp"

#include <mpi.h>

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace rbm::motion {

// Whether a part solves these options: the default variant (coupling coupled, formulation
// nonlinear, algorithm reducedNewton) with subSteps auto or 1 (a part does not divide a step).
bool partsSolve(const RigidBodyMotionOptions& options);

// The checks PartRigidBodyMotion makes that need no other rank (the variant, 2D, cyclic
// patches, the names of floatingPatches and of the stiffening's patches), for a front door to
// make on every rank before the collective set-up: throws rbm::InputError.
void checkPartIsSolvable(const io::Dictionary& coefficients, const PolyMesh& localMesh,
                         const BoundaryDescription& boundary);

class PartRigidBodyMotion {
public:
    // Collective. `localMesh`: the rank's processor mesh (its points are points0) with
    // `globalIds` its pointProcAddressing; `boundary`: the description of its conditions (its
    // processor patches ignored); `coefficients`: rigidBodyMotionSolverCoeffs. Every argument
    // must outlive this object. PETSc must be initialised on `communicator`.
    PartRigidBodyMotion(MPI_Comm communicator, const PolyMesh& localMesh, std::span<const Label> globalIds,
                        const BoundaryDescription& boundary, const io::Dictionary& coefficients);
    ~PartRigidBodyMotion();
    PartRigidBodyMotion(const PartRigidBodyMotion&) = delete;
    PartRigidBodyMotion& operator=(const PartRigidBodyMotion&) = delete;

    // `displacement`, one per point of the local mesh: in, the values the rank's conditions
    // gave its patch points at this time; out, every point's displacement. Collective; the
    // report's figures are the same on every rank (inverted cells and quality are the front
    // door's, which sees the cells).
    MotionSolveReport solve(std::vector<Vector3>& displacement);

    const MeshPart& part() const;
    // What the front door must tell the user once (a curved unconstrained patch, not put back
    // onto its surface on parts); the same on every rank.
    const std::vector<std::string>& warnings() const;
    const RigidBodyMotionOptions& options() const;
    // options().describe() and the stiffened patches.
    std::string describe() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace rbm::motion

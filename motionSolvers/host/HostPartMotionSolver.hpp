#pragma once
// rbm's rigid body motion solver on one rank's part of a decomposed 3D mesh, for a host that
// evaluates its own boundary conditions (the OpenFOAM plugin in `-parallel` runs): the
// distributed counterpart of HostMotionSolver.hpp, whose types it shares. No rank holds the
// whole mesh: each passes its own mesh (OpenFOAM's local polyMesh with its `processor`
// patches) and one global label per local point, and gets back its own points' displacement.
// The result is the serial solver's (the same energy, minimised to the same tolerance;
// docs/parallel.md, "The distributed run").
//
// This header must stay C++17 (the host's language) like HostMotionSolver.hpp: no MPI type
// either. HostPartMotionSolver.cpp (C++20) implements it with motion::PartRigidBodyMotion (the
// solve) and motion::PartQuality (the whole mesh's step figures, reduced over the ranks) on
// MPI_COMM_WORLD, whose rank r must hold processor r (OpenFOAM's Pstream::myProcNo(), as its
// processor patches' myProcNo says): the host has initialised MPI; PETSc is initialised on it
// by the first host solver of the process (HostPetscSession.hpp).
//
// What the part solver takes (checked by solvesVariant and the constructor): the default
// variant (coupling coupled, formulation nonlinear, algorithm reducedNewton), a 3D mesh and
// no cyclic patch. Sliding patches slide on the whole patch's point normals, which the part
// solver sums from every rank's faces (PartBoundary.hpp): the host's normals are not read, so
// a condition whose normal is not the patch's own (fixedNormalSlip) needs HostMotionSolver.
// Not done on parts (the serial solver's later stages): sub-step halving, untangling.
//
// Every member is collective: every rank calls it, in the same order.

#include "HostMotionSolver.hpp"

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace rbm::host {

class HostPartMotionSolver {
public:
    // Whether the coefficients choose a variant the part solver takes (the default one).
    // Local (not collective). Throws HostInputError for bad coefficients.
    static bool solvesVariant(const std::string& coefficientsText, const std::string& coefficientsFile);

    // `localMesh`: the rank's mesh at its reference points (points0), its patches in the host's
    // order with the shared ones first (the same list on every rank) and the `processor`
    // patches last, each with entries myProcNo (this rank) and neighbProcNo.
    // `globalPointLabels`: per local point, its label in the whole mesh (0 .. global point
    // count − 1; a point on several ranks has the same label on each).
    // `boundary`: one entry per patch of `localMesh`, processor patches `ignored`; sliding
    // patches need 3 normal components per patch point (not read, see above).
    // `coefficientsText`, `coefficientsFile`: as HostMotionSolver's.
    // Throws HostInputError on every rank when one rank's input is bad (the lowest such rank's
    // message), std::runtime_error (std::invalid_argument) for other failures.
    HostPartMotionSolver(const HostMesh& localMesh, const std::vector<int>& globalPointLabels,
                         const std::string& coefficientsText, const std::string& coefficientsFile,
                         const std::vector<HostPatchBoundary>& boundary);
    ~HostPartMotionSolver();
    HostPartMotionSolver(const HostPartMotionSolver&) = delete;
    HostPartMotionSolver& operator=(const HostPartMotionSolver&) = delete;

    // The rank's own points, and the whole mesh's (each shared point once).
    std::size_t pointCount() const;
    long long globalPointCount() const;

    // As HostMotionSolver::solve, on the rank's points: `displacement` (3 × pointCount()
    // values) is read at the points of the rank's prescribed patches and overwritten with every
    // local point's displacement. The report is the same on every rank: the whole mesh's
    // figures (inverted cells, quality with the faces between the ranks) and its verdict; the
    // first report's warnings include the set-up's (a curved unconstrained patch whose points
    // the part solver does not put back onto its surface).
    HostStepReport solve(int step, double time, const std::string& timeName, double* displacement,
                         std::size_t valueCount);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace rbm::host

#pragma once
// rbmMoveMesh -parallel on a decomposed case (docs/parallel.md, "The distributed run"): under
// mpirun -np N on a case that decomposePar split into processor0 … processorN−1, rank r reads
// processor<r> only — its polyMesh with pointProcAddressing, its <time>/pointDisplacement —
// and the case's system/controlDict and constant/dynamicMeshDict. No rank holds the whole mesh.
//
//  - Setup reads and checks every rank's input before any collective step; all ranks agree on
//    the outcome, so bad input on one rank stops every rank (exit status 2), each failing rank
//    naming its file, and nothing is written.
//  - Each step: every rank evaluates its patches' conditions, the distributed solve
//    (motionSolvers/rigidBodyMotion/decomposed/PartRigidBodyMotion.hpp) moves every point, the
//    quality figures are reduced over the ranks (the whole mesh's, equal on every rank), and
//    rank 0 prints the step's line and appends its JSON line
//    (postProcessing/rbmMoveMesh/<startTime>/log.jsonl in the case).
//  - A write time is written in two phases: every rank stages processor<r>/<time> (points and
//    pointDisplacement); only when all staged does every rank commit, so that either every
//    processor folder has the time or none does. reconstructPar and ParaView's decomposed
//    reader read the result. No VTK (ParaView reads the processor folders).
//  - An invalid step (inverted cells, no convergence) stops the run as in a serial run; with
//    -writeInvalid it is written anyway. A failure inside a collective step (a PETSc error)
//    cannot be agreed on: the rank that meets it prints it and aborts every rank (MPI_Abort).

#include "MoveMeshRun.hpp"

#include <mpi.h>

#include <iosfwd>

namespace rbm::app {

// Whether `options` asks for the decomposed run: -parallel on a case with processor folders.
bool isDecomposedRun(const MoveMeshOptions& options);

// The run on every rank of `communicator` (one rank per processor folder). Rank 0 prints the
// header, the step lines and the summary on `out`; every rank's errors go to `err`. Returns
// the exit status, the same on every rank.
int runDecomposedMoveMesh(const MoveMeshOptions& options, MPI_Comm communicator, std::ostream& out,
                          std::ostream& err);

} // namespace rbm::app

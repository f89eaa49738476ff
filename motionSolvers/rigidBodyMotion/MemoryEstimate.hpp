#pragma once
// How much memory an RBM solve needs, estimated before anything is assembled, and how much
// the machine can give, so that a run too large for the machine stops at once with a clear
// message instead of swapping for hours or being killed by the kernel half way.
//
// The model (bytes), per linear system the solve holds:
//  - direct factorisation (2D, and 3D up to directSolverRowLimit rows, PetscSupport.hpp, or
//    `linearSolver direct`): 130 bytes × log2(rows) per row, fitted to the peak memory the
//    benchmark measured on its 2D meshes at 1e4 and 1e5 nodes (linearized: 685 MiB at 3e5
//    rows). A 3D factor fills as nested dissection predicts, rows^(4/3) (separators of
//    n^(2/3) nodes, dense blocks of the b × b node blocks): 12 bytes × 11 b² n^(4/3), n
//    unknown nodes, b = 6, fitted to peaks measured on hex boxes (MemoryEstimate.cpp);
//  - Krylov + multigrid (3D above the row limit, or `linearSolver iterative`): the assembled
//    block array, PETSc's AIJ copy and the multigrid hierarchy, about 38 bytes per stored value;
//  - reduced Newton in 3D with K iterative: K's single-precision copy and its multigrid
//    hierarchy, 30 bytes per block of K, and 500 bytes per unknown node (MemoryEstimate.cpp);
//  - matrix-free linearized (3D, or `linearSolver matrixFree`):
//    the scalar displacement Laplacian and its multigrid, ~40 bytes per block, plus ~400 bytes
//    per node (MemoryEstimate.cpp).
// and per variant: Newton keeps an LU of its Hessian besides the linearized Cholesky factor
// (× 2.3 measured); decoupled linearized solves two systems (× 2); decoupled nonlinear and
// local/global factorise one scalar Laplacian over the nodes (rows = unknown nodes, one value
// per block); linearized sub-steps after the first build a second system next to the kept one
// (× 2). The benchmark (benchmarks/RbmBenchmark.cpp) skips runs with the same figures.

#include "PetscSupport.hpp"
#include "PolyMesh.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace rbm {
struct MeshTopology;
}

namespace rbm::motion {

class RbmProblem;
struct RigidBodyMotionOptions;

// The RBM variants as the solver objects they create (makeRbmSolver, RbmSolverSelection.hpp).
enum class SolveVariant {
    decoupledNonlinear,   // DecoupledSolver, nonlinear model
    decoupledLinearized,  // DecoupledSolver, linearized model
    coupledLinearized,    // CoupledLinearizedSolver
    coupledNewton,        // CoupledNewtonSolver
    coupledLocalGlobal,   // LocalGlobalSolver (then Newton where it stalls)
    coupledReducedNewton, // ReducedNewtonSolver: the scalar Laplacian only
};

// The size of the coupled problem.
struct SolveSize {
    int dimension = 3;          // 2: solved on one plane of a pseudo-3D mesh
    double unknownNodes = 0.0;  // free and sliding nodes
    double blocks = 0.0;        // blocks of the coupled matrix: unknown nodes + directed edges between them
};

struct MemoryEstimate {
    double bytes = 0.0;
    double rows = 0.0;   // scalar unknowns of the largest system
    bool direct = false; // a sparse factorisation (else Krylov + multigrid)
    bool matrixFree = false;  // the linearized system unassembled (MatrixFreeLinearizedSystem.hpp)
};

// The estimate for one variant. `systems`: how many such systems are alive at once (2 for
// linearized sub-steps after the first, see linearSystemsAtOnce).
MemoryEstimate estimateSolveMemory(SolveVariant variant, const SolveSize& size,
                                   LinearSolverKind linearSolver = LinearSolverKind::automatic, int systems = 1);

// The exact size of a built problem (the benchmark's use).
SolveSize solveSizeOf(const RbmProblem& problem);

// The size before any solver exists, from the mesh: the cell-neighbour graph (points sharing
// a cell, CellNeighbourGraph.hpp) counted, not stored, over the points that are not
// prescribed (`prescribed[p]` non-zero). A pseudo-3D mesh is solved on one plane: each
// planar node is two points, each seeing its twin and its planar neighbours on both planes,
// so nodes = points / 2 and blocks = (sum over points of 1 + neighbours) / 4.
SolveSize estimateSolveSize(const MeshTopology& topology, std::span<const std::uint8_t> prescribed, bool pseudoTwoD);

SolveVariant solveVariantOf(const RigidBodyMotionOptions& options);
// 2 for the linearized formulations when sub-steps may be more than one, else 1.
int linearSystemsAtOnce(const RigidBodyMotionOptions& options);

// What the machine can give now: the smaller of MemAvailable (/proc/meminfo) and, inside a
// cgroup v2 with a limit, memory.max − memory.current. `source` says which.
struct AvailableMemory {
    double bytes = 0.0;
    std::string source;
};
std::optional<AvailableMemory> availableMemory();

// "1.23 GiB", "456 MiB", "12.0 KiB".
std::string formatBytes(double bytes);

} // namespace rbm::motion

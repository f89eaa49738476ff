#pragma once
// The hierarchy of smoothed-aggregation algebraic multigrid (Vaněk, Mandel & Brezina 1996) for a
// scalar symmetric positive definite matrix whose near null space is the constant vector (a
// weighted graph Laplacian with some rows held by boundary values): rbm's own, for the 3D cycle
// of ThreeVectorMultigrid (issue 12).
//
// Why not PCGAMG's: GAMG builds the same kind of hierarchy, but on the 27-point Laplacian of a
// hexahedral mesh its set-up is a large part of a step, most of it creating a filtered graph and
// coarsening by a maximal independent set on that graph SQUARED (125 entries a row; measured on
// rbmBenchmark's twist3D case, docs/motionSolver.md, "The preconditioner K⁻¹"). Greedy aggregation on the matrix's own graph makes aggregates of the same size (a node
// and its whole neighbourhood: 3 × 3 × 3 nodes on a hexahedral grid, as MIS on the squared graph)
// in one pass over the pattern. The rest is as GAMG: the tentative prolongator T (1 where a row
// belongs to an aggregate), smoothed once, P = (I − ω D⁻¹A) T with ω = 4 / (3 λ), λ the largest
// eigenvalue of D⁻¹A by power iteration, and the Galerkin coarse operator Pᵀ A P (PETSc's
// MatPtAP). Repeated on the coarse operator until it has at most coarsestRows rows.
//
// Aggregation (the three phases of the paper, in row order, so deterministic), on the strong
// couplings, |a_ij| ≥ θ √(a_ii a_jj) with θ = strongCouplingThreshold:
//   1. a row none of whose strong neighbours is aggregated yet starts an aggregate of itself and
//      its strong neighbours;
//   2. every row left joins the aggregate of its strongest aggregated neighbour (largest |a_ij|,
//      the first in column order among equals), among the aggregates of phase 1;
//   3. rows still left (no aggregated neighbour) start aggregates of themselves and their
//      strong neighbours not yet aggregated.
// Why a threshold: on a boundary-layer mesh the couplings along a layer are 1/AR² of those
// across it (weights 1/|d|², cells of aspect ratio AR up to thousands). Aggregates of whole
// neighbourhoods then mix both directions and the point smoother cannot damp what they miss:
// tutorials/wing3D at 27 864 cells (AR ≈ 3 000) needed about 190 CG iterations of the cycle per
// K ⊗ I solve (38 s for a step; a factorisation 4.6 s). Aggregating along the strong couplings
// only (semi-coarsening across the layers) takes 11 (4.0–4.7 s, 235 MB against the
// factorisation's 646 MB). θ = 0.005 keeps every coupling of the 27-point stencil of a cube
// (the weakest, a corner's 1/3 over a diagonal of 14.7: 0.023), so isotropic meshes aggregate
// as without it (rbmBenchmark's twist3D: the same iterations and residuals); couplings drop
// out from aspect ratios of about 10.

#include <span>
#include <vector>

namespace rbm::motion {

// θ of the strong couplings (see above).
inline constexpr double strongCouplingThreshold = 0.005;

// A sparse matrix in compressed rows.
struct CompressedRows {
    std::vector<int> offsets{0}, columns;
    std::vector<double> values;
    int rows() const { return static_cast<int>(offsets.size()) - 1; }
};

// The aggregate of every row (0 … count − 1) of the matrix pattern (rowOffsets, columns: both
// triangles, any order within a row, the diagonal ignored); values (the same layout) choose the
// strongest neighbour in phase 2. Every row is in exactly one aggregate; every aggregate is
// connected in the pattern.
std::vector<int> aggregateRows(std::span<const int> rowOffsets, std::span<const int> columns,
                               std::span<const double> values, int& count);

// One coarser level: the interpolation from it (rows of the finer level × its rows) and its
// operator Pᵀ A P.
struct AggregationLevel {
    CompressedRows interpolation;
    CompressedRows coarseOperator;
};

// The levels below the given matrix, finest first, until one has at most coarsestRows rows (or
// aggregation no longer halves the rows). Throws std::runtime_error where a level cannot be
// built (a zero or negative diagonal).
std::vector<AggregationLevel> buildSmoothedAggregation(std::span<const int> rowOffsets, std::span<const int> columns,
                                                       std::span<const double> values, int coarsestRows);

} // namespace rbm::motion

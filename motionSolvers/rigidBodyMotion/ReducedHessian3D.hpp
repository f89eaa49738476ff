#pragma once
// The reduced Hessian S = ∇²Ẽ of ReducedNewtonSolver (see its file comment for the formulas),
// specialised for 3D and lean in memory: per-node data only, nothing per graph edge.
//
// The generic kernel keeps R_i d_ij for every directed edge (24 B) and the transpose edge's index
// (4 B) and gathers R_j d_kj through it; at 10⁶ hexahedra that is 27·10⁶ edges, 750 MB read in a
// random order by every product. Here every edge term is rebuilt from node data:
//
//   b_i = Σ_j w (R_i d_ij) × (v_j − v_i) = axial(R_i T_i),  T_i = Σ_j w d_ij (v_j − v_i)ᵀ,
//         axial(A) = (A₁₂ − A₂₁, A₂₀ − A₀₂, A₀₁ − A₁₀)   ((R d) × v = ε (R d) v componentwise);
//   y_i = H_δδ,i⁻¹ b_i;
//   (S v)_k = D_k v_k − 2 Σ_j w v_j + y_k × c_k + Σ_j w M_j d_kj,
//         D_k = Σ_j w (1 + t_j),  c_k = R_k Σ_j w d_kj,  M_j = [y_j]× R_j (M_j d = y_j × R_j d);
//
// with v and M zero at prescribed nodes (t_j = 0 there), which reproduces the generic kernel's
// Σ_j w [(1 + t_j)(v_k − v_j) + y_k × R_k d + t_j y_j × R_j d]. Per edge both passes read the
// neighbour's index and weight (12 B) and node-indexed data; per unknown node 25 doubles and per node 20 are kept.
//
// Layout: the node-indexed data the edge loops gather (x_j, v_j and M_j's columns) are held
// as four-double vectors (GCC's vector extension, the fourth lane zero), so that every edge
// term is a handful of whole-vector operations on one aligned 32-byte load each instead of
// scalar code that spills its accumulators (SSE2 has 16 registers for 9 + 3 sums). The passes
// run as AVX2 where the CPU has it (VectorInstructions.hpp); the operations per lane are those
// of the scalar formulas in the same order, so the products are bit for bit the scalar
// kernel's. The price is memory, 20 instead of 12 doubles per node, for fewer instructions
// per edge term; what it gives the solve shows in rbmBenchmark's twist3D case.
//
// Determinism: every loop writes its own node's entries; each node's sums run in graph order.
//
// One rank's part (RbmProblem::isPart): the passes cover the owned nodes; the ghosts' v_j and
// M_j come from their owners (one ghost update before each pass); ghost rows of S v are zero.

#include "RbmEnergy.hpp"
#include "RbmProblem.hpp"

#include <array>
#include <span>
#include <vector>

namespace rbm::motion {

class ReducedHessian3D {
public:
    explicit ReducedHessian3D(const RbmProblem& problem);

    // The per-node data of apply at displacements u (one per node) and their fitted rotations
    // R*(u) (one per node): H_δδ,i⁻¹ (restricted to the normal at mirror nodes), c_i. apply reads
    // the rotations themselves, not a copy (72 bytes a node less): they must stay alive and
    // unchanged until the next prepare (the Newton iterate's, during its CG).
    void prepare(std::span<const Vector3> displacement, std::span<const Matrix3> rotations);
    // y = P S P v (compact vectors, 3 per unknown node).
    void apply(std::span<const double> v, std::span<double> y);
    // Between solves: frees what prepare() computes and apply() works in (about 250 bytes a node,
    // which the caller's quality check and output need more); the next prepare() allocates it
    // again. The reference positions and the diagonal stay.
    void release();

    // Bytes held (for MemoryEstimate and its test): per unknown node and per node.
    static constexpr double bytesPerUnknownNode = (6 + 3 + 1 + 3 + 3) * 8.0;
    static constexpr double bytesPerNode = (4 + 4 + 12) * 8.0;

    // Four doubles, one vector register (AVX2) or two (SSE2); lane 3 is always zero. Stored
    // through AlignedDouble4: without AVX GCC gives the vector type only 16-byte alignment (and
    // std::vector ignores attributes on its argument), while the AVX2 kernel loads 32-aligned.
    using Double4 = double __attribute__((vector_size(32)));
    struct alignas(32) AlignedDouble4 {
        Double4 value;
    };

private:
    void allocateSolveData();  // the arrays release() frees, zeroed

    const RbmProblem& problem_;
    std::span<const Matrix3> rotations_;           // per node: R_i, prepare's (not owned)
    std::vector<std::array<double, 6>> inverse_;   // per unknown node: H_δδ⁻¹ (symmetric: 00 01 02 11 12 22)
    std::vector<Vector3> rotatedSum_;              // per unknown node: c_i = R_i Σ_j w d_ij
    std::vector<double> diagonal_;                 // per unknown node: D_i = Σ_j w (1 + t_j)
    std::vector<Vector3> ownTerm_;                 // per unknown node: y_i × c_i (work)
    std::vector<AlignedDouble4> position_;                // per node: x (reference point)
    std::vector<AlignedDouble4> nodeVector_;              // per node: v (zero at prescribed nodes)
    std::vector<AlignedDouble4> nodeMap_;               // per node 3: the columns of M_j = [y_j]× R_j (zero at prescribed nodes)
    std::vector<double> projected_;
};

} // namespace rbm::motion

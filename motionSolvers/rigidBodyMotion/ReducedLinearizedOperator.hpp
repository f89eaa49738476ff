#pragma once
// The linearized coupled RBM energy with the rotations eliminated node by node, applied
// without a matrix (the memory-lean way to solve the linearized method on large 3D meshes).
//
// The linearized energy (RbmEnergy.hpp, smallAngle; thesis §2.4 eq 2.48, §2.5.1 eq 2.92)
//
//     E(u, ω) = 1/2 Σ_{i unknown} Σ_{j∈N(i)} w_ij |u_j − u_i − ω_i × d_ij|²,   d_ij = x_j − x_i,
//
// holds the rotation ω_i of a node in the terms of its own neighbourhood only. So for given
// displacements the best rotations follow node by node, from a 3×3 system (2D: a scalar):
//
//     M_i ω_i = Σ_j w_ij d_ij × (u_j − u_i),   M_i = Σ_j w_ij (|d_ij|² I − d_ij d_ijᵀ),
//
// and E_reduced(u) = min_ω E(u, ω) is a quadratic in the displacements alone: the Schur
// complement S = H_uu − H_uω H_ωω⁻¹ H_ωu of the linearized Hessian, exact, not an
// approximation. Its minimiser is the u of the coupled linearized solution; the ω of that
// solution are the best rotations of that u. By the envelope theorem its gradient is ∂E/∂u at
// the best ω, which per unknown node k is a sum over its neighbours j (d = x_j − x_k, w = w_kj):
//
//     g_k = Σ_j w [(1 + [j unknown]) (u_k − u_j) + ω_k × d + [j unknown] ω_j × d].
//
// Applying S costs two passes over the graph edges and stores nothing per edge beyond the
// problem's own weights, against 6×6 = 36 values per edge for the assembled 3D Hessian (7.8 KB
// per node of a hexahedral mesh). Both passes write only their own node's entries, so they
// run on threads with results independent of the thread count.
//
// Constraints: a mirror (symmetry-plane) node turns about its normal n only, so its best
// rotation is n (n·b)/(nᵀ M n); in 2D every rotation is about z. Sliding displacements are
// handled by the caller (RbmProblem::projectSliding with block size = dimension).
//
// The preconditioner of choice is the displacement block H_uu itself: a scalar weighted graph
// Laplacian (the same for every component), L_kk = Σ_j w_kj (1 + [j unknown]),
// L_kj = −2 w_kj for unknown j. S ≤ H_uu, with equality on fields whose neighbourhoods do not
// turn; see docs/motionSolver.md for the iteration counts this gives.

#include "RbmProblem.hpp"

#include <array>
#include <span>
#include <vector>

namespace rbm::motion {

// H_uu of the coupled energy as a scalar matrix over unknown nodes in blockPattern() order:
// K_kk = Σ_j w_kj (1 + [j unknown]), K_kj = −2 w_kj for unknown j. The same for every
// component and for the exact and the linearized energy (E is quadratic in u).
std::vector<double> coupledDisplacementLaplacian(const RbmProblem& problem);

class ReducedLinearizedOperator {
public:
    // Keeps a reference to problem. Throws std::invalid_argument for a node whose
    // neighbours do not fix its rotation (all of them on one line through it).
    explicit ReducedLinearizedOperator(const RbmProblem& problem);

    const RbmProblem& problem() const { return problem_; }
    // Unknowns of the reduced system: dimension() displacement components per unknown node.
    int size() const { return problem_.unknownNodeCount() * problem_.dimension(); }

    // ∇E_reduced at the node displacements `displacement` (one per node: prescribed nodes
    // as prescribed, unknown nodes as the current iterate), dimension() entries per unknown
    // node. Not projected onto sliding planes.
    void gradient(std::span<const Vector3> displacement, std::span<double> gradient) const;
    // y = S x for a compact displacement vector x (size() entries; prescribed nodes zero).
    void apply(std::span<const double> x, std::span<double> y) const;
    // The best rotation of every unknown node for the node displacements (in z in 2D).
    void bestRotations(std::span<const Vector3> displacement, std::span<Vector3> rotation) const;

    // H_uu as a scalar matrix over unknown nodes in CSR form (the columns of
    // problem.blockPattern(), diagonal included): the preconditioner's operator.
    std::vector<double> displacementLaplacianValues() const;

private:
    const RbmProblem& problem_;
    // Per unknown node: the symmetric 3×3 map b ↦ ω (M⁻¹, or n nᵀ/(nᵀ M n) for a node held
    // to turn about n), stored row-major.
    std::vector<std::array<double, 9>> rotationMaps_;
    // Work arrays of apply(): node displacements and best rotations (mutable: apply() is
    // logically const and called from PETSc's MatMult).
    mutable std::vector<Vector3> workDisplacement_;
    mutable std::vector<Vector3> workRotation_;
};

} // namespace rbm::motion

#pragma once
// The reduced energy of the coupled nonlinear RBM method, a function of the displacements
// alone, and its derivatives. The exact energy (RbmEnergy.hpp)
//
//     E(u, R) = 1/2 Σ_i Σ_j w_ij |e_ij − R_i d_ij|²,   e_ij = p_j − p_i, d_ij = x_j − x_i,
//
// holds R_i in the terms of node i alone, so
//
//     Ẽ(u) = min_R E(u, R) = E(u, R*(u)),   R*_i(u) = the best fit of node i's edges
//
// (the local step of LocalGlobalSolver: 2D atan2, 3D Kabsch) has the same minima as E:
// (u, R*(u)) minimises E iff u minimises Ẽ. Newton on Ẽ therefore never meets the stationary
// points with flipped node frames that Newton on (u, R) can stop at (CoupledNewtonSolver.hpp).
//
// Derivatives (envelope theorem, ∂E/∂R = 0 at R*):
//   ∇Ẽ = ∂E/∂u at R*, per unknown node k with d = x_j − x_k, t_j = [j unknown]:
//       g_k = Σ_j w [(1 + t_j)(u_k − u_j − d) + R_k d + t_j R_j d]   (= K u − b(R*));
//   ∇²Ẽ = S = H_uu − H_uδ H_δδ⁻¹ H_δu, the Schur complement of the exact Hessian in a
//       local rotation chart R_i ← exp([δ_i]×) R_i (at ∂E/∂δ = 0 it does not depend on the
//       chart). With q = R_i d_ij and e = e_ij:
//         H_uu = K ⊗ I, K the coupled weighted graph Laplacian (constant: E is quadratic in u);
//         H_δδ,i = Σ_j w [(q·e) I − (e qᵀ + q eᵀ)/2]   (block diagonal: δ_i only in node i's terms);
//         S v:  y_i = H_δδ,i⁻¹ Σ_j w q_ij × (v_j − v_i),
//               (S v)_k = (K v)_k + Σ_j w (y_k × R_k d + t_j y_j × R_j d).
//   At u = 0 (R* = I) S is the linearized method's reduced operator (ReducedLinearizedOperator).
//   A mirror node turns about its normal n only (δ = n φ); 2D rotations about z.
//
// The kernels: 2D PlanarReducedKernels.hpp, 3D ReducedHessian3D.hpp for S (per-node data
// only, nothing stored per edge). Vectors of unknowns are compact: dimension() entries per
// unknown node, projected onto the sliding planes (P). Every loop over nodes writes its own
// node's entries and every sum runs in node order: bit-identical for any thread count.
//
// One rank's part of a distributed problem (RbmProblem::isPart, 3D): every evaluation covers
// the owned nodes (their terms, fits and rows; the ghosts' rotations come from their owners,
// the ghost rows of g and S v are zero) and the energy and the rounding level are summed over
// the ranks. Equal to the whole problem's to rounding (the sums run in another order).
//
// With `transverseStiffness λ` the energy is Ẽ + E_t, E_t the penalty on the displacement's
// variation across a translation (TransverseGradientPenalty.hpp, quadratic in u and free of the
// rotations): every method below adds its value, gradient and Hessian product.

#include "NeighbourhoodScaling.hpp"
#include "RbmEnergy.hpp"
#include "RbmProblem.hpp"
#include "TransverseGradientPenalty.hpp"

#include <memory>
#include <span>
#include <vector>

namespace rbm::motion {

class PlanarReducedKernels;
class ReducedHessian3D;

class ReducedEnergy {
public:
    // scaling: rigid neighbourhoods (the thesis' energy, the default) or similarities
    // (NeighbourhoodScaling.hpp; planar problems only, std::invalid_argument in 3D).
    // transverseStiffness: λ of TransverseGradientPenalty.hpp (0: none, the default).
    explicit ReducedEnergy(const RbmProblem& problem, NeighbourhoodScaling scaling = {}, double transverseStiffness = 0.0);
    ~ReducedEnergy();
    ReducedEnergy(const ReducedEnergy&) = delete;
    ReducedEnergy& operator=(const ReducedEnergy&) = delete;

    // The translation direction of the transverse penalty for the next evaluations (zero: off;
    // no effect without transverseStiffness). Returns whether the penalty is on.
    bool setTranslation(const Vector3& direction);
    const TransverseGradientPenalty& transversePenalty() const { return transverse_; }

    // Fits R*(u) into rotations (one per node) and returns Ẽ(u); u one displacement per node.
    double fitAndEnergy(std::span<const Vector3> displacement, std::vector<Matrix3>& rotations) const;
    // g = P ∇Ẽ at u with its fitted rotations.
    void gradient(std::span<const Vector3> displacement, std::span<const Matrix3> rotations, std::span<double> g) const;
    // H_δδ⁻¹ per node at (u, R*(u)): the data of applyHessian until the next call.
    void prepareHessian(std::span<const Vector3> displacement, std::span<const Matrix3> rotations);
    // y = P S P v.
    void applyHessian(std::span<const double> v, std::span<double> y);
    // Between solves: frees prepareHessian's data in 3D (about 250 bytes a node; the next
    // prepareHessian computes it again whatever is kept).
    void releaseHessian();
    // The rounding level of ‖P∇Ẽ‖ at u, ε ‖Σ_j w (|u_i| + |u_j| + |d|)‖ over the displacement
    // rows (RbmEnergy::gradientRoundoffNorm): a gradient at this level is as small as it gets.
    double gradientRoundoffNorm(std::span<const Vector3> displacement);

private:
    // A part's sum over all ranks (the value itself in a serial problem).
    double sumOverRanks(double value) const;

    const RbmProblem& problem_;
    std::unique_ptr<PlanarReducedKernels> planar_;  // 2D
    std::unique_ptr<ReducedHessian3D> hessian3D_;   // 3D: S from per-node data
    // Per unknown node Σ_j w and Σ_j w |d| of gradientRoundoffNorm: the weights do not change
    // during the solver's life, so these are summed once and not at every time step.
    std::vector<double> weightSums_, weightedLengths_;
    std::vector<double> projected_;  // work array
    TransverseGradientPenalty transverse_;
};

} // namespace rbm::motion

#pragma once
// Neighbourhoods that may scale as well as turn: the option `scaling` of
// rigidBodyMotionSolverCoeffs (docs/motionSolver.md, "Neighbourhood scaling").
//
// The RBM energy fits every node's neighbourhood with a rotation R_i (thesis eq. 2.9). Under a
// squeeze (a body translating towards a wall) its quadratic penalty makes a shortened
// neighbourhood cost as much as a sheared one, so the solution shears the cells beside the
// squeezed ones until they fold. With a scale s_i per node the fit is a similarity s_i R_i,
// and the scale pays its own penalty, μ W_i (s_i − 1)², W_i = Σ_j w_ij |d_ij|²:
//
//     E_i = min_{s, R} 1/2 [ Σ_j w |e_ij − s R d_ij|² + μ W_i (s − 1)² ].
//
// The best R is the rigid fit's (it does not depend on s > 0); with C_i = Σ_j w (R d)·e, the
// rigid fit's value (planar: |(Σ w d·e, Σ w d×e)|), the best scale is
//
//     s_i = (C_i + μ W_i) / ((1 + μ) W_i),
//
// so μ = ∞ is the rigid energy (s = 1), and μ = 0 the as-similar-as-possible one, which is
// quadratic in the displacements (C_i² is) and reproduces any similarity of the boundary exactly.
// At the best fit ∂E/∂s = ∂E/∂θ = 0 and ∂²E/∂s∂θ = 0 (the θ-derivative of C vanishes there), so
// the reduced Hessian gains one rank-one term per node, decoupled from the turn's:
//
//     H_ss,i = (1 + μ) W_i,   coupling with e_ij: −w R d_ij (unscaled),
//
// and the turn's terms are the rigid ones with R replaced by s R (PlanarReducedKernels.hpp).
// Planar problems only: the 3D kernels (ReducedHessian3D) fit rotations alone.

#include <limits>

namespace rbm::motion {

struct NeighbourhoodScaling {
    // μ: the scale's stiffness relative to the edges' (∞: rigid, the thesis' energy; 0: free).
    double stiffness = std::numeric_limits<double>::infinity();

    bool rigid() const { return stiffness == std::numeric_limits<double>::infinity(); }
    // s_i from the rigid fit's value C_i and W_i = Σ_j w |d|² (> 0).
    double scale(double rigidFit, double weightedSquaredLength) const
    {
        if (rigid()) return 1.0;
        return (rigidFit + stiffness * weightedSquaredLength) / ((1.0 + stiffness) * weightedSquaredLength);
    }
    // μ W (s − 1)², the scale's own term of 2 E_i.
    double penalty(double scale, double weightedSquaredLength) const
    {
        if (rigid()) return 0.0;
        return stiffness * weightedSquaredLength * (scale - 1.0) * (scale - 1.0);
    }
    // 1 / (s² H_ss) = 1 / (s² (1 + μ) W): the factor of the scale's rank-one Hessian term when
    // the per-edge data are kept scaled (s w R d); 0 when rigid.
    double inverseScaledCurvature(double scale, double weightedSquaredLength) const
    {
        if (rigid() || !(scale > 0.0) || !(weightedSquaredLength > 0.0)) return 0.0;
        return 1.0 / (scale * scale * (1.0 + stiffness) * weightedSquaredLength);
    }
};

} // namespace rbm::motion

#pragma once
// The reduced Newton solver's four kernels (ReducedNewtonSolver.hpp) written for planar (2D)
// problems: Ẽ(u) with the best-fit rotations, ∇Ẽ, the data of the reduced Hessian S at
// (u, R*(u)), and S v.
//
// Why a planar version: in 2D every rotation is an angle about z, so H_δδ,i is a scalar and
// the turn y_i of a node under a direction v is one number; the general kernels carry 3-vectors,
// 3×3 maps and cross products for it, and look up node kinds per edge. A warm time step of the
// 40k-node airfoil applies S about ten times, and in the general form each product cost as
// much as a back-substitution with K's factor (issue 12's profile). Here every edge of an
// unknown centre is one 32-byte record (d, w, the neighbour's node and compact index), read
// in order; a prescribed neighbour points at a zero slot instead of taking a branch.
//
// The formulas are those of ReducedNewtonSolver.hpp with n = z (q = R_i d, e = e_ij):
//   fit:  θ_i = atan2(Σ w d×e, Σ w d·e)  (LocalGlobalSolver's planar local step),
//   ∇Ẽ:   g_k = Σ_j w [(1 + t_j)(u_k − u_j − d) + R_k d + t_j R_j d],
//   H_δδ,i = Σ_j w q·e,
//   S v:  y_i = H_δδ,i⁻¹ Σ_j w q × (v_j − v_i),
//         (S v)_k = Σ_j w [(1 + t_j)(v_k − v_j) + y_k ẑ × q_kj − t_j y_j ẑ × q_jk].
// Determinism: every loop writes its own node's entries and sums run in node order.

#include "NeighbourhoodScaling.hpp"
#include "RbmEnergy.hpp"
#include "RbmProblem.hpp"

#include <span>
#include <vector>

namespace rbm::motion {

class PlanarReducedKernels {
public:
    // Keeps a reference to problem (dimension() must be 2). scaling: rigid neighbourhoods (the
    // default) or similarities (NeighbourhoodScaling.hpp).
    explicit PlanarReducedKernels(const RbmProblem& problem, NeighbourhoodScaling scaling = {});

    // Fits the best rotation of every unknown node into rotations (sized to the node count,
    // identity elsewhere) and returns Ẽ(u).
    double fitAndEnergy(std::span<const Vector3> displacement, std::vector<Matrix3>& rotations);
    // g = ∇Ẽ at u with its fitted rotations: 2 entries per unknown node, not projected.
    void gradient(std::span<const Vector3> displacement, std::span<const Matrix3> rotations, std::span<double> g) const;
    // q = R_i d per edge and H_δδ,i⁻¹ per unknown node (0 where H_δδ,i is not positive: S = K there).
    void prepareHessian(std::span<const Vector3> displacement, std::span<const Matrix3> rotations);
    // y = S v for compact vectors (2 entries per unknown node), not projected.
    void applyHessian(std::span<const double> v, std::span<double> y);

private:
    struct Edge {
        double dx, dy, weight;
        int node;     // the neighbour j
        int compact;  // its unknown index, or the zero slot (unknown node count) if prescribed
    };

    // body(a) for every unknown node a, threads over the nodes in order, each requesting the
    // edge records ahead of its node (ReadAhead.hpp): the loop of the fit, ∇Ẽ and the Hessian's data.
    template <typename Body>
    void forEachUnknownNode(Body&& body) const;
    // S v's two passes over padded_ (v with its zero slot) into y.
    template <bool scaled>
    void applyHessianPasses(std::span<double> y);

    const RbmProblem& problem_;
    int unknownCount_;
    NeighbourhoodScaling scaling_;
    std::vector<double> weightedSquaredLengths_;  // per unknown node W = Σ_j w |d|²
    std::vector<int> offsets_;   // edges of unknown node a: [offsets_[a], offsets_[a + 1])
    std::vector<Edge> edges_;
    // S v's data per edge a→j, set by prepareHessian and read in order by applyHessian (no
    // lookup of the reverse edge, no product with w per CG iteration): w q, w q_back (q_back
    // = R_j d_ji, zero for a prescribed j) and (1 + t_j) w. In single precision: S v reads 36
    // instead of 64 bytes per edge (its passes are bound by memory traffic, like K's
    // back-substitution); S is only Newton's model, so the step is off by ~1e-7 relatively,
    // while the gradient (double) decides convergence. w q of a→j and w q_back of j→a are the
    // same product rounded the same way, so S stays symmetric to round-off
    // (ReducedEnergy.HessianIsSymmetric).
    std::vector<float> weightedRotated_, weightedBackRotated_, laplacianWeight_;
    std::vector<int> compact_;             // per edge: the neighbour's unknown index or the zero slot
    std::vector<double> inverseCurvature_; // per unknown node H_δδ⁻¹
    std::vector<double> inverseStretchCurvature_;  // per unknown node 1 / (s² H_ss) (0: rigid)
    std::vector<double> nodeEnergy_;       // work: per-node energies, summed in order
    // work: (cos, sin) of every node's rotation, gathered from the 3×3 matrices once per pass,
    // so that the neighbours' rotations are read 16 bytes each instead of from 72-byte matrices
    mutable std::vector<double> cosineSine_;
    std::vector<double> padded_;           // work: v with a zero slot
    std::vector<double> turn_;             // work: y with a zero slot
    std::vector<double> stretch_;          // work: the scales' change with a zero slot
};

} // namespace rbm::motion

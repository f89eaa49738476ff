#pragma once
// A penalty on how the displacement varies ACROSS the direction a translating body moves in:
// the option `transverseStiffness λ` of rigidBodyMotionSolverCoeffs (docs/motionSolver.md,
// "Translations"). It is what OpenFOAM's `directional` diffusivity does in the tutorial
// movingCone (`velocityComponentLaplacian x`, `directional (1 200 0)`: the columns of points
// across the motion move as one, so that the cells ahead of the body shorten uniformly
// instead of shearing), put inside the RBM energy as one more term.
//
// Every node's neighbourhood is fitted, like the RBM energy's rotation fit, by the
// deformations that vary along the motion direction m only: Δu_ij ≈ (d_ij·m) g_i, g_i one
// vector per node (a stretch along m when g ∥ m, a displacement across m that changes along
// m otherwise), and the misfit is the penalty:
//
//     E_t(u) = λ/2 Σ_i min_g Σ_j w_ij |u_j − u_i − a_ij g|²,   a_ij = d_ij·m,           (T1)
//
// d_ij = x_j − x_i in the reference mesh (2D: in the plane), w_ij the problem's edge weights
// (stiffening included), the sum over EVERY node i, prescribed ones too (the RBM energy has
// no terms for prescribed nodes, so the cells next to a prescribed patch are held by one
// neighbourhood instead of two and give way first under a squeeze). The best fit is
// g_i = b_i / A_i with
//
//     A_i = Σ_j w_ij a_ij²,   b_i = Σ_j w_ij a_ij (u_j − u_i),                           (T2)
//
// so that per node E_i = Σ_j w |u_j − u_i|² − |b_i|²/A_i ≥ 0 (Cauchy–Schwarz; A_i = 0: the
// first sum alone). (T1) is quadratic in u and acts on each component alike. Any
// displacement that is locally a function of the position along m (a translation, a uniform
// compression of the columns ahead of the body, a uniform stretch behind it) costs nothing;
// what costs is differential motion across m (the columns shearing) and a change of the
// compression along m (a kink in the ramp: the cells next to a wall shortening more than
// the rest). The per-node fit is along the edges' own extent along m, so a column that
// moves as one costs nothing even where the cells beside it are skewed (a least-squares
// gradient of u, projected across m, would charge its kink there).
//
// Gradient, per component q (E_t = λ/2 Σ_i [Σ_j w (u_j − u_i)² − b_i²/A_i], σ_i = Σ_j w a_ij,
// each undirected edge in two neighbourhoods, w and a antisymmetric-free: w_ij = w_ji,
// a_ji = −a_ij):
//
//     ∂E_t/∂u_k = λ [ 2 Σ_j w_kj (u_k − u_j) + Σ_j w_kj a_kj b_j/A_j + σ_k b_k/A_k ],   (T3)
//
// and the Hessian product is (T3) with u replaced by v, the prescribed nodes' entries zero.
//
// The direction is set per solve (setDirection): the motion solver gives the common
// translation of the moving prescribed nodes where every fixed wall faces it
// (translationTowardsFixedWalls) and switches the term off (a zero direction) otherwise. Serial problems only (not one rank's part).

#include "RbmProblem.hpp"
#include "Vector3.hpp"

#include <span>
#include <vector>

namespace rbm::motion {

class TransverseGradientPenalty {
public:
    // λ ≥ 0 (0: the term is always off). Keeps a reference to problem.
    TransverseGradientPenalty(const RbmProblem& problem, double stiffness);

    double stiffness() const { return stiffness_; }
    // m: the motion direction (any length, normalised here; 2D: its z is dropped); a zero
    // vector switches the term off. The per-edge a_ij are computed again only when the
    // direction's line changes.
    void setDirection(const Vector3& direction);
    bool active() const { return active_; }
    const Vector3& direction() const { return direction_; }

    // E_t at u (one displacement per node, prescribed ones included), (T1). 0 when off.
    double energy(std::span<const Vector3> displacement) const;
    // g += ∇E_t at u, compact (dimension() entries per unknown node), (T3); unprojected.
    void addGradient(std::span<const Vector3> displacement, std::span<double> g) const;
    // y += ∇²E_t v, v and y compact (prescribed nodes' v is zero); unprojected.
    void addHessianProduct(std::span<const double> v, std::span<double> y) const;

    // The common displacement of the prescribed nodes that move (those with |u| above 1e-12
    // of the largest), if every one of them moves by it to 1e-9 of its length; the zero
    // vector otherwise (no motion, or not one translation).
    static Vector3 commonTranslation(const RbmProblem& problem, std::span<const Vector3> prescribedDisplacement);
    // Where the penalty applies: commonTranslation, when every edge between two prescribed
    // points that do not move lies across it (|ê·m| ≤ 0.01: the fixed walls face the motion, the
    // sides along it are free or slide, as in a body closing a gap in a channel); the zero
    // vector otherwise. A fixed wall along the motion holds its columns' ends still, and
    // columns moving as one are then wrong: the thesis' squares, an inner square translated
    // by (50, 25) inside a fixed outer one, end at 73.6° with the penalty against 10.75°.
    static Vector3 translationTowardsFixedWalls(const RbmProblem& problem,
                                                std::span<const Vector3> prescribedDisplacement);

private:
    // b_i / A_i of (T2) for every node from a node field (one Vector3 per node, componentwise).
    void fitAll(std::span<const Vector3> field) const;
    // (T3) into compact rows, from fitAll's fits of the same field.
    void addTransposed(std::span<const Vector3> field, std::span<double> y) const;

    const RbmProblem& problem_;
    double stiffness_;
    Vector3 direction_{};
    bool active_ = false;
    std::vector<double> along_;                // a_ij = d_ij·m per directed edge
    std::vector<double> inverseMoments_;       // 1 / A_i per node (0 where A_i = 0)
    std::vector<double> sums_;                 // σ_i = Σ_j w a_ij per node
    mutable std::vector<Vector3> fits_;        // g_i = b_i / A_i per node (work array)
    mutable std::vector<Vector3> field_;       // the Hessian product's v per node (work array)
};

} // namespace rbm::motion

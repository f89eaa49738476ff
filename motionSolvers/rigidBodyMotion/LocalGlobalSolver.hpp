#pragma once
// Local/global minimisation of the coupled RBM energy (docs/method.md §3; the ARAP
// alternation of Sorkine & Alexa 2007 on the cell-neighbour graph):
//   local step   every unknown node i takes the rotation that best maps its reference
//                edges d_ij = x_j − x_i onto its current edges e_ij = p_j − p_i
//                (2D: θ = atan2(Σ w d×e, Σ w d·e); 3D: Kabsch/SVD with the reflection fix);
//   global step  with the rotations fixed E is quadratic in the displacements; its
//                minimiser solves K u = b(R), where K is the weighted graph Laplacian over the
//                unknown nodes (prescribed neighbours moved to the right-hand side). K does
//                not depend on the rotations nor on the prescribed values: it is assembled and
//                factorised (or preconditioned) ONCE, in the constructor, and reused for x, y
//                and z, every iteration and every solve() call.
// Each step lowers E, so the iteration converges (linearly) to a minimum of E: the same
// one Newton reaches on the same case. Plain, it needs many iterations where the boundary
// holds the mesh loosely (thesis §3.1.3: 831); Anderson acceleration with an energy
// safeguard (on by default) cut that to 31. CoupledNewtonSolver remains the alternative.
//
// The same alternation with the decoupled Laplacian reaches the fixed point of the thesis'
// decoupled method (§2.3.1); see DecoupledSolver.hpp. LaggedRotationIteration below holds
// what both share.
//
// Sliding nodes make x, y and z interact, so when there are any K is assembled as a
// (dimension × dimension)-block matrix with the projection P K P + s (I − P); still once.
//
// Options prefix: rbm_laplacian_ (also rbm_ and the global options).
// Result: iterations = global solves; residualNorm = ‖P (K u − b(R))‖ after a final local
// step, which is ‖P ∇_u E‖ with the rotations optimal, i.e. the full first-order
// optimality of E; energy = E.

#include "PetscSupport.hpp"
#include "RbmEnergy.hpp"
#include "RbmProblem.hpp"

#include <cmath>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rbm::motion {

// The rotation R minimising Σ_k w_k |b_k − R a_k|² given the weighted covariance
// S = Σ_k w_k b_k a_kᵀ: R = U diag(1, 1, det(U Vᵀ)) Vᵀ for S = U Σ Vᵀ (Kabsch; the last
// factor keeps R a proper rotation when the best orthogonal fit is a reflection).
// Rank-deficient S (planar or collinear neighbourhoods) gives one of the optimal rotations.
Matrix3 bestRotation(const Matrix3& covariance);
// The same rotation for det S > 0 as the orthogonal polar factor of S, by Newton's iteration
// (bestRotation's fast path); false (rotation untouched) where that does not apply (det S ≤ 0,
// S nearly singular, no convergence), and bestRotation then takes the SVD.
bool polarRotation(const Matrix3& covariance, Matrix3& rotation);
// 2D: the angle (counter-clockwise) minimising Σ w |b − R(θ) a|², from Σ w a×b and Σ w a·b.
inline double bestPlanarAngle(double crossSum, double dotSum);

// Singular value decomposition S = U diag(σ) Vᵀ of a 3×3 matrix by one-sided Jacobi
// rotations, σ sorted descending, U and V orthogonal (det ±1).
struct SingularValueDecomposition {
    Matrix3 u;
    Vector3 singularValues;
    Matrix3 v;
};
SingularValueDecomposition singularValueDecomposition(const Matrix3& matrix);

// Local step: for every unknown node i, the rotation that best maps its reference edges
// x_j − x_i onto its current edges p_j − p_i (p = x + u, u given for all nodes); 2D
// rotations are about z. rotations is resized to nodeCount(); prescribed entries untouched.
void fitNodeRotations(const RbmProblem& problem, std::span<const Vector3> displacement,
                      std::vector<Matrix3>& rotations);

// Rotation parameters of a fitted rotation: 2D (0, 0, θ), 3D the rotation vector.
Vector3 rotationParameters(int dimension, const Matrix3& rotation);

enum class LaplacianForm {
    coupled,    // ∂E/∂u = 0 of the coupled energy: K_kk = Σ_j w_kj (1 + [j unknown]), K_kj = −2 w_kj
    decoupled,  // ∂F_k/∂u_k = 0 of every node's own F_k (eq 2.2): K_kk = Σ_j w_kj, K_kj = −w_kj
};

// Alternation of rotation fits and Laplacian solves (shared by LocalGlobalSolver and the
// nonlinear DecoupledSolver).
class LaggedRotationIteration {
public:
    struct Options {
        LinearSolverKind linearSolver = LinearSolverKind::automatic;
        double linearRelativeTolerance = 1e-12;
        int maximumIterations = 2000;
        // Converged when no node moves more than this × the shortest reference edge in an iteration.
        double displacementTolerance = 1e-11;
        // Anderson acceleration over this many previous iterations (0: the plain alternation).
        int accelerationDepth = 0;
    };

    LaggedRotationIteration(const RbmProblem& problem, LaplacianForm form, Options options, std::string_view solverName);

    // Local step: the best rotation of every unknown node for the displacements u (all
    // nodes). 2D rotations are about z. Entries of prescribed nodes are left unchanged.
    void fitRotations(std::span<const Vector3> displacement, std::vector<Matrix3>& rotations) const;

    // The whole iteration; see the file comment. Starts from initialGuess, or else from
    // the Laplacian (harmonic) interpolation of the prescribed displacements.
    RbmResult run(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess);

private:
    std::vector<Vector3> rightHandSide(std::span<const Vector3> prescribed, std::span<const Matrix3> rotations) const;
    // r = P (K u − b) over the unknown nodes (compact numbering); returns ‖r‖.
    double residualNorm(std::span<const Vector3> displacement, std::span<const Vector3> rightHandSide) const;
    // Global step; returns false (with the Krylov reason in failure) if a solve failed.
    bool solveDisplacements(std::span<const Vector3> rightHandSide, std::span<const Vector3> offset,
                            std::vector<Vector3>& displacement, int& linearIterations, std::string& failure);
    // The accelerated alternation from u (rotations fitted here); returns the last right-hand side.
    std::vector<Vector3> iterate(std::span<const Vector3> prescribedDisplacement, std::span<const Vector3> offset,
                                 std::vector<Vector3>& u, std::vector<Matrix3>& rotations, RbmResult& result);

    const RbmProblem& problem_;
    LaplacianForm form_;
    Options options_;
    std::vector<double> laplacian_;  // scalar K in blockPattern() order
    std::unique_ptr<BlockSystemSolver> system_;
    bool vectorSystem_ = false;      // sliding nodes: one (dimension)-block system instead of per-component solves
};

struct LocalGlobalOptions {
    LinearSolverKind linearSolver = LinearSolverKind::automatic;
    double linearRelativeTolerance = 1e-12;
    int maximumIterations = 2000;
    double displacementTolerance = 1e-11;  // × shortest reference edge
    // Anderson acceleration depth (0: plain local/global). Every accelerated point must
    // lower the energy. On the thesis' free-outer-boundary squares (§3.1.3) it cut 831
    // iterations to 31.
    int accelerationDepth = 5;
};

class LocalGlobalSolver : public RbmSolver {
public:
    explicit LocalGlobalSolver(const RbmProblem& problem, LocalGlobalOptions options = {});

    const RbmProblem& problem() const override { return problem_; }
    RbmResult solve(std::span<const Vector3> prescribedDisplacement, const RbmState* initialGuess = nullptr) override;

private:
    const RbmProblem& problem_;
    LaggedRotationIteration iteration_;
};

inline double bestPlanarAngle(double crossSum, double dotSum)
{
    return std::atan2(crossSum, dotSum);
}

} // namespace rbm::motion

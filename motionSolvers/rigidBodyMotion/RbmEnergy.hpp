#pragma once
// The coupled RBM energy with node-local rotations (docs/method.md §2; thesis F_total, eqs
// 2.2, 2.3, 2.10–2.13, 2.23, 2.78, 2.79 after the change of variables explained there):
//
//     E = 1/2 Σ_{i unknown} Σ_{j∈N(i)} w_ij |r_ij|²,   r_ij = (p_j − p_i) − R_i (x_j − x_i)
//
// with p = x + u. Prescribed nodes are never centres, they only appear as neighbours j.
// Its gradient (the thesis' Eq1–Eq3, eqs 2.27–2.29) and its exact Hessian (the analytic
// Jacobian of the thesis, eqs 2.30–2.47) over the compact block vector of unknowns (see
// RbmProblem.hpp for the layout and the sign conventions).
//
// Rotation models:
//   exact       2D: R(θ) = [cos θ −sin θ; sin θ cos θ] (counter-clockwise positive);
//               3D: R(ω) = exp([ω]×) (rotation vector, Rodrigues). The thesis uses Euler
//               angles R_z R_y R_x (eq 2.72); a rotation vector has no gimbal lock and the
//               same small-angle limit.
//   smallAngle  R ≈ I + [θ]× (thesis §2.4, eq 2.48, and §2.5.1, eq 2.92): E becomes
//               quadratic in the unknowns, its Hessian is the constant symmetric positive
//               definite matrix of the linearized method.
//
// No PETSc here: plain arrays in, plain arrays out.

#include "RbmProblem.hpp"
#include "Vector3.hpp"

#include <array>
#include <span>
#include <vector>

namespace rbm::motion {

enum class RotationModel { exact, smallAngle };

// A 3×3 matrix, row-major: m[row][column].
struct Matrix3 {
    std::array<std::array<double, 3>, 3> m{};

    static constexpr Matrix3 identity() { return {{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}}; }
    constexpr Vector3 operator*(const Vector3& v) const
    {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    constexpr Matrix3 operator*(const Matrix3& b) const
    {
        Matrix3 c;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) c.m[i][j] = m[i][0] * b.m[0][j] + m[i][1] * b.m[1][j] + m[i][2] * b.m[2][j];
        return c;
    }
    constexpr Matrix3 transposed() const
    {
        Matrix3 t;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) t.m[i][j] = m[j][i];
        return t;
    }
};

// [v]×: the matrix with [v]× a = v × a.
constexpr Matrix3 crossMatrix(const Vector3& v) { return {{{{0, -v.z, v.y}, {v.z, 0, -v.x}, {-v.y, v.x, 0}}}}; }

// Rotation about z by θ, counter-clockwise positive.
Matrix3 planarRotation(double angle);
// R = exp([ω]×) (Rodrigues): rotation by |ω| about ω/|ω|, right-hand rule.
Matrix3 rotationFromVector(const Vector3& rotationVector);
// The rotation vector of a proper rotation matrix (angle in [0, π]).
Vector3 rotationVectorFromMatrix(const Matrix3& rotation);

// A rotation and its first and second derivatives with respect to its parameters
// (2D: θ; 3D: ω_x, ω_y, ω_z), as used per centre node by the energy.
struct RotationDerivatives {
    Matrix3 rotation;
    std::array<Matrix3, 3> first;      // ∂R/∂φ_k
    std::array<Matrix3, 6> second;     // ∂²R/∂φ_k∂φ_l, index of (k, l), k ≤ l: 00 01 02 11 12 22
};
RotationDerivatives rotationDerivatives(int dimension, RotationModel model, const double* parameters);
constexpr int symmetricIndex(int k, int l)
{
    const int a = k < l ? k : l;
    const int b = k < l ? l : k;
    return a == 0 ? b : (a == 1 ? 2 + b : 5);
}

class RbmEnergy {
public:
    // The energy of problem for the given prescribed displacements (one per node; the
    // entries of unknown nodes are ignored). Keeps a reference to problem.
    RbmEnergy(const RbmProblem& problem, RotationModel model, std::span<const Vector3> prescribedDisplacement);

    const RbmProblem& problem() const { return problem_; }
    RotationModel model() const { return model_; }
    const std::vector<Vector3>& prescribedDisplacement() const { return prescribed_; }

    // E at the compact unknown vector (unknownCount() entries).
    double value(std::span<const double> unknowns) const;
    // ∇E into gradient (unknownCount() entries); returns E.
    double gradient(std::span<const double> unknowns, std::span<double> gradient) const;
    // The exact Hessian ∇²E as blocks of blockSize()² values (row-major within a block)
    // in the order of problem.blockPattern(). For smallAngle it does not depend on unknowns.
    // With includeCurvature = false: the Gauss–Newton matrix Σ w JᵀJ (positive
    // semi-definite), the Hessian without the term −w r·∂²(R d) of the rotation blocks.
    void hessian(std::span<const double> unknowns, std::span<double> blockValues, bool includeCurvature = true) const;

    // Euclidean norm of the sliding-projected gradient P∇E at unknowns (first-order optimality).
    double projectedGradientNorm(std::span<const double> unknowns) const;

    // The size of the rounding error in ∇E at unknowns: ε Σ_j w_ij (|u_i| + |u_j| + |d_ij|)
    // per displacement row (r_ij is formed from u_j − u_i and d_ij, each rounded to ε times
    // its magnitude), in the Euclidean norm. A gradient this small is zero as far as double
    // precision can tell; Newton stops near it instead of iterating on rounding noise (on a
    // boundary-layer mesh with 1/|d|² weights it is far above any fixed absolute tolerance).
    double gradientRoundoffNorm(std::span<const double> unknowns) const;

private:
    const RbmProblem& problem_;
    RotationModel model_;
    std::vector<Vector3> prescribed_;
};

} // namespace rbm::motion

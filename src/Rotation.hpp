#pragma once
// Rotations and rigid transformations with OpenFOAM v1912's conventions, so that motion laws
// read from OpenFOAM dictionaries mean what they mean in OpenFOAM
// (src/OpenFOAM/primitives/quaternion, src/OpenFOAM/primitives/septernion).
//
// Sign conventions (all angles in radians here; callers convert degrees):
//  - A rotation by a positive angle about an axis turns counter-clockwise when seen from the
//    tip of the axis looking back at the origin (right-hand rule): rotating (1,0,0) by +90°
//    about (0,0,1) gives (0,1,0).
//  - Quaternion q rotates a vector u to q u q* (OpenFOAM quaternion::transform), which is the
//    matrix q.matrix() (OpenFOAM quaternion::R()) applied to u.
//  - A product a*b of quaternions applies b first, then a.
//  - Euler sequences follow OpenFOAM's quaternion(rotationSequence, angles): XYZ is
//    q_x(angles.x) * q_y(angles.y) * q_z(angles.z), the matrix Rx·Ry·Rz, which turns a vector
//    about z first, then about (fixed) y, then about (fixed) x.
//  - Septernion (OpenFOAM's name) holds a translation t and a rotation r and maps a point x to
//    r (x − t): t is MINUS the displacement of the origin before rotation. A product A*B
//    applies B first, then A (see operator*= below, copied in meaning from septernionI.H).
//
// Example: rotation of 90° about the z axis through the point (1, 0, 0), OpenFOAM style:
//     Septernion(Vector3{-1,0,0}) * Quaternion::fromAxisAngle({0,0,1}, pi/2) * Septernion(Vector3{1,0,0})
//   maps (2,0,0) to (1,1,0).

#include "Vector3.hpp"

#include <array>
#include <cmath>

namespace rbm {

// Row-major 3×3 matrix: (M v)_i = Σ_j m[i][j] v_j.
struct Matrix3 {
    std::array<std::array<double, 3>, 3> m{};

    static constexpr Matrix3 identity()
    {
        Matrix3 r;
        r.m[0][0] = r.m[1][1] = r.m[2][2] = 1.0;
        return r;
    }
    constexpr double operator()(int row, int column) const { return m[row][column]; }
    constexpr Vector3 operator*(const Vector3& v) const
    {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    constexpr Matrix3 operator*(const Matrix3& b) const
    {
        Matrix3 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r.m[i][j] = m[i][0] * b.m[0][j] + m[i][1] * b.m[1][j] + m[i][2] * b.m[2][j];
        return r;
    }
    constexpr Matrix3 transposed() const
    {
        Matrix3 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r.m[i][j] = m[j][i];
        return r;
    }
};

// Rotation matrix of `angle` radians about `axis` (any length > 0; normalised here),
// Rodrigues' formula R = cos θ I + sin θ [a]× + (1 − cos θ) a aᵀ. Counter-clockwise about the
// axis for positive angles.
inline Matrix3 rotationMatrix(const Vector3& axis, double angle)
{
    const Vector3 a = axis / norm(axis);
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    const double k = 1.0 - c;
    Matrix3 r;
    r.m[0][0] = c + k * a.x * a.x;
    r.m[0][1] = k * a.x * a.y - s * a.z;
    r.m[0][2] = k * a.x * a.z + s * a.y;
    r.m[1][0] = k * a.y * a.x + s * a.z;
    r.m[1][1] = c + k * a.y * a.y;
    r.m[1][2] = k * a.y * a.z - s * a.x;
    r.m[2][0] = k * a.z * a.x - s * a.y;
    r.m[2][1] = k * a.z * a.y + s * a.x;
    r.m[2][2] = c + k * a.z * a.z;
    return r;
}

// OpenFOAM's quaternion::rotationSequence. The first letter is the axis of the leftmost factor
// (applied last); e.g. XYZ = q_x(a.x) q_y(a.y) q_z(a.z).
enum class RotationSequence { ZYX, ZYZ, ZXY, ZXZ, YXZ, YXY, YZX, YZY, XYZ, XYX, XZY, XZX };

struct Quaternion {
    double w = 1.0;
    Vector3 v{};

    static constexpr Quaternion identity() { return {1.0, {}}; }

    // OpenFOAM quaternion(d, θ): w = cos(θ/2), v = sin(θ/2) d/|d|.
    static Quaternion fromAxisAngle(const Vector3& axis, double angle)
    {
        return {std::cos(0.5 * angle), (std::sin(0.5 * angle) / rbm::norm(axis)) * axis};
    }

    // OpenFOAM quaternion(rotationSequence, angles) with angles in radians.
    static Quaternion fromEulerAngles(RotationSequence sequence, const Vector3& angles)
    {
        // Axis letters of each sequence, in the order of the factors (leftmost first).
        static constexpr std::array<std::array<int, 3>, 12> axes{{
            {2, 1, 0}, {2, 1, 2}, {2, 0, 1}, {2, 0, 2}, {1, 0, 2}, {1, 0, 1},
            {1, 2, 0}, {1, 2, 1}, {0, 1, 2}, {0, 1, 0}, {0, 2, 1}, {0, 2, 0},
        }};
        const auto& a = axes[static_cast<int>(sequence)];
        auto unit = [](int axis) {
            Vector3 e{};
            e[axis] = 1.0;
            return e;
        };
        Quaternion q = fromAxisAngle(unit(a[0]), angles.x);
        q *= fromAxisAngle(unit(a[1]), angles.y);
        q *= fromAxisAngle(unit(a[2]), angles.z);
        return q;
    }

    // Hamilton product, in place (OpenFOAM quaternion::operator*=): *this = *this * q.
    constexpr Quaternion& operator*=(const Quaternion& q)
    {
        const double w0 = w;
        w = w * q.w - dot(v, q.v);
        v = w0 * q.v + q.w * v + cross(v, q.v);
        return *this;
    }

    constexpr Quaternion conjugate() const { return {w, -v}; }
    double norm() const { return std::sqrt(w * w + dot(v, v)); }
    Quaternion normalized() const
    {
        const double n = norm();
        return {w / n, v / n};
    }

    // q u q*: the rotated vector (OpenFOAM quaternion::transform).
    constexpr Vector3 transform(const Vector3& u) const
    {
        // mulq0v(u) = (−v·u, w u + v×u), then times conjugate(q), keeping the vector part.
        const double pw = -dot(v, u);
        const Vector3 pv = w * u + cross(v, u);
        return pw * (-v) + w * pv + cross(pv, -v);
    }
    // q* u q: the inverse rotation (OpenFOAM quaternion::invTransform).
    constexpr Vector3 invTransform(const Vector3& u) const { return conjugate().transform(u); }

    // OpenFOAM quaternion::R(): the rotation matrix of a unit quaternion.
    constexpr Matrix3 matrix() const
    {
        const double w2 = w * w, x2 = v.x * v.x, y2 = v.y * v.y, z2 = v.z * v.z;
        const double txy = 2 * v.x * v.y, twz = 2 * w * v.z, txz = 2 * v.x * v.z;
        const double twy = 2 * w * v.y, tyz = 2 * v.y * v.z, twx = 2 * w * v.x;
        Matrix3 r;
        r.m = {{{w2 + x2 - y2 - z2, txy - twz, txz + twy},
                {txy + twz, w2 - x2 + y2 - z2, tyz - twx},
                {txz - twy, tyz + twx, w2 - x2 - y2 + z2}}};
        return r;
    }
};

constexpr Quaternion operator*(Quaternion a, const Quaternion& b) { return a *= b; }

// OpenFOAM's septernion: x' = r (x − t).
struct Septernion {
    Vector3 t{};
    Quaternion r{};

    constexpr Septernion() = default;
    constexpr Septernion(const Vector3& translation, const Quaternion& rotation) : t(translation), r(rotation) {}
    // OpenFOAM septernion(t): maps x to x − t (a shift by −t).
    explicit constexpr Septernion(const Vector3& translation) : t(translation) {}
    // OpenFOAM septernion(r): a rotation about the origin.
    explicit constexpr Septernion(const Quaternion& rotation) : r(rotation) {}

    constexpr Vector3 transformPoint(const Vector3& x) const { return r.transform(x - t); }
    constexpr Vector3 invTransformPoint(const Vector3& x) const { return t + r.invTransform(x); }

    // The same map written x' = R x + d: R = r.matrix(), d = −r.transform(t).
    constexpr Matrix3 rotationMatrix() const { return r.matrix(); }
    constexpr Vector3 translation() const { return -r.transform(t); }

    // OpenFOAM septernion::operator*=(tr): t = tr.t + tr.r.invTransform(t), r = r*tr.r.
    // Afterwards transformPoint(x) = (old this).transformPoint(tr.transformPoint(x)): tr first.
    constexpr Septernion& operator*=(const Septernion& tr)
    {
        t = tr.t + tr.r.invTransform(t);
        r *= tr.r;
        return *this;
    }
    // OpenFOAM septernion::operator*=(quaternion).
    constexpr Septernion& operator*=(const Quaternion& q)
    {
        t = q.invTransform(t);
        r *= q;
        return *this;
    }
};

// OpenFOAM operator*(septernion, septernion): as *=, with the rotation renormalised
// (quaternion::transform(quaternion) = normalize(q1*q2)).
inline Septernion operator*(const Septernion& a, const Septernion& b)
{
    return {b.r.invTransform(a.t) + b.t, (a.r * b.r).normalized()};
}
// OpenFOAM operator*(septernion, quaternion) and operator*(quaternion, septernion).
constexpr Septernion operator*(const Septernion& a, const Quaternion& q) { return {q.invTransform(a.t), a.r * q}; }
constexpr Septernion operator*(const Quaternion& q, const Septernion& a) { return {a.t, q * a.r}; }

// OpenFOAM inv(septernion).
constexpr Septernion inverse(const Septernion& s) { return {-s.r.transform(s.t), s.r.conjugate()}; }

} // namespace rbm

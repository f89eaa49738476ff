#pragma once
// A 3-component vector of doubles: points, displacements, face normals.
// 2D meshes keep z (the extrusion direction of OpenFOAM's pseudo-3D cases).

#include <cmath>
#include <ostream>

namespace rbm {

struct Vector3 {
    double x = 0.0;
    double y = 0.0;
    double z = 0.0;

    constexpr double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }

    constexpr Vector3& operator+=(const Vector3& b) { x += b.x; y += b.y; z += b.z; return *this; }
    constexpr Vector3& operator-=(const Vector3& b) { x -= b.x; y -= b.y; z -= b.z; return *this; }
    constexpr Vector3& operator*=(double s) { x *= s; y *= s; z *= s; return *this; }
    constexpr Vector3& operator/=(double s) { x /= s; y /= s; z /= s; return *this; }
    friend constexpr bool operator==(const Vector3&, const Vector3&) = default;
};

constexpr Vector3 operator+(Vector3 a, const Vector3& b) { return a += b; }
constexpr Vector3 operator-(Vector3 a, const Vector3& b) { return a -= b; }
constexpr Vector3 operator-(const Vector3& a) { return {-a.x, -a.y, -a.z}; }
constexpr Vector3 operator*(Vector3 a, double s) { return a *= s; }
constexpr Vector3 operator*(double s, Vector3 a) { return a *= s; }
constexpr Vector3 operator/(Vector3 a, double s) { return a /= s; }

constexpr double dot(const Vector3& a, const Vector3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vector3 cross(const Vector3& a, const Vector3& b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(const Vector3& a) { return std::sqrt(dot(a, a)); }
constexpr double normSquared(const Vector3& a) { return dot(a, a); }

inline std::ostream& operator<<(std::ostream& os, const Vector3& v)
{
    return os << '(' << v.x << ' ' << v.y << ' ' << v.z << ')';
}

} // namespace rbm

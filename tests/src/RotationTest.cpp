// Tests of src/Rotation.hpp: rotation matrices, quaternions, Euler sequences and septernions
// (OpenFOAM's conventions).

#include "FoamDictionary.hpp"
#include "Function1.hpp"
#include "InputError.hpp"
#include "PointPatchDisplacement.hpp"
#include "PolyMeshReader.hpp"
#include "Rotation.hpp"
#include "SolidBodyMotion.hpp"
#include "TestCases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

using namespace rbm::test::boundaryMotionCases;

using namespace rbm;

TEST(Rotation, QuaternionFromAxisAngleMatchesRodriguesMatrix)
{
    const Vector3 axis{0.3, -1.2, 0.7};
    const double angle = 0.83;
    const Quaternion q = Quaternion::fromAxisAngle(axis, angle);
    const Matrix3 r = rotationMatrix(axis, angle);
    for (const Vector3& v : {Vector3{1, 0, 0}, Vector3{0.2, 0.5, -0.9}, Vector3{-3, 2, 1}}) {
        expectNear(q.transform(v), r * v);
        expectNear(q.matrix() * v, r * v);
        expectNear(q.invTransform(q.transform(v)), v);
    }
}

TEST(Rotation, PositiveAngleTurnsCounterClockwiseAboutTheAxis)
{
    // Right-hand rule: +90° about z takes x to y, about x takes y to z, about y takes z to x.
    expectNear(Quaternion::fromAxisAngle({0, 0, 1}, pi / 2).transform({1, 0, 0}), {0, 1, 0});
    expectNear(Quaternion::fromAxisAngle({1, 0, 0}, pi / 2).transform({0, 1, 0}), {0, 0, 1});
    expectNear(Quaternion::fromAxisAngle({0, 1, 0}, pi / 2).transform({0, 0, 1}), {1, 0, 0});
}

TEST(Rotation, EulerSequenceXyzIsRxTimesRyTimesRz)
{
    const Vector3 angles{0.4, -0.7, 1.1};
    const Matrix3 expected = rotationMatrix({1, 0, 0}, angles.x) * rotationMatrix({0, 1, 0}, angles.y) *
                             rotationMatrix({0, 0, 1}, angles.z);
    const Quaternion q = Quaternion::fromEulerAngles(RotationSequence::XYZ, angles);
    for (const Vector3& v : {Vector3{1, 0, 0}, Vector3{0, 1, 0}, Vector3{0.3, 0.2, -0.8}}) expectNear(q.transform(v), expected * v);
    // ZYX is the reverse product.
    const Matrix3 zyx = rotationMatrix({0, 0, 1}, angles.x) * rotationMatrix({0, 1, 0}, angles.y) *
                        rotationMatrix({1, 0, 0}, angles.z);
    expectNear(Quaternion::fromEulerAngles(RotationSequence::ZYX, angles).transform({0.3, 0.2, -0.8}),
               zyx * Vector3{0.3, 0.2, -0.8});
}

TEST(Rotation, SepternionProductAppliesTheRightFactorFirst)
{
    // A = shift by (1,0,0) (OpenFOAM septernion(-d) maps x to x + d); B = 90° about z.
    const Septernion shift(Vector3{-1, 0, 0});
    const Septernion turn(Quaternion::fromAxisAngle({0, 0, 1}, pi / 2));
    const Vector3 x{1, 0, 0};
    expectNear(shift.transformPoint(x), {2, 0, 0});
    // shift*turn: turn (1,0,0) -> (0,1,0), then shift -> (1,1,0).
    expectNear((shift * turn).transformPoint(x), {1, 1, 0});
    Septernion compound = shift;
    compound *= turn;
    expectNear(compound.transformPoint(x), {1, 1, 0});
    // turn*shift: shift -> (2,0,0), then turn -> (0,2,0).
    expectNear((turn * shift).transformPoint(x), {0, 2, 0});
    // x' = R x + d form and the inverse.
    const Septernion s = shift * turn;
    expectNear(s.rotationMatrix() * x + s.translation(), {1, 1, 0});
    expectNear(inverse(s).transformPoint({1, 1, 0}), x);
}

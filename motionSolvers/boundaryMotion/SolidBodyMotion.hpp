#pragma once
// Solid-body motion laws: OpenFOAM v1912's solidBodyMotionFunctions
// (src/dynamicMesh/motionSolvers/displacement/solidBody/solidBodyMotionFunctions), each a rigid
// transformation of the reference points (points0) at time t. The transformation is returned
// as OpenFOAM's septernion (src/Rotation.hpp): x(t) = r (x0 − t_s), composed exactly as OpenFOAM
// composes it, so that the same dictionary moves the same points in both programs.
//
// Selection (SolidBodyMotion::New(dict)): `solidBodyMotionFunction <type>;` in `dict`; the
// coefficients are read from the sub-dictionary `<type>Coeffs` when present, else from `dict`
// itself (OpenFOAM: optionalSubDict(type + "Coeffs")).
//
//   linearMotion               velocity (vector, m/s):   x = x0 + velocity t
//   rotatingMotion             origin, axis, omega (scalar Function1, rad/s):
//                              angle = ∫_0^t omega, x = origin + R(axis, angle)(x0 − origin),
//                              positive angles counter-clockwise about the axis (right-hand rule)
//   oscillatingLinearMotion    amplitude (vector), omega (scalar, rad/s): x = x0 + amplitude sin(omega t)
//   oscillatingRotatingMotion  origin, amplitude (vector of Euler angles in DEGREES), omega (rad/s):
//                              angles = amplitude sin(omega t) (converted to radians),
//                              x = origin + Rx(ax) Ry(ay) Rz(az) (x0 − origin)  (z turn first)
//   multiMotion                every sub-dictionary of the coefficients, in file order, is a
//                              motion with its own solidBodyMotionFunction; OpenFOAM composes
//                              TR = S0 * S1 * ... * Sn (septernion product, right factor first),
//                              so the LAST listed motion is applied to the points first.
//   tabulated6DoFMotion        CofG (vector), timeDataFileName (file holding
//                              `( (t ((tx ty tz) (rx ry rz))) ... )`, rotations in DEGREES):
//                              x = CofG + T(t) + Rx Ry Rz (x0 − CofG). Interpolation between rows
//                              is OpenFOAM's interpolateSplineXY: a Catmull-Rom cubic through
//                              the rows (linear for a two-row table; a row repeated at the ends
//                              is extrapolated linearly). Times outside the table are an error.
//
// Example (constant/dynamicMeshDict, or a pointDisplacement patch with
// `type solidBodyMotionDisplacement;`):
//     solidBodyMotionFunction multiMotion;
//     multiMotionCoeffs
//     {
//         rotation            // applied second
//         {
//             solidBodyMotionFunction rotatingMotion;
//             rotatingMotionCoeffs { origin (0 0 0); axis (0 0 1); omega 6.2832; }
//         }
//         translation         // applied first (listed last)
//         {
//             solidBodyMotionFunction linearMotion;
//             linearMotionCoeffs { velocity (1 0 0); }
//         }
//     }
//
// Every error is an rbm::InputError naming the file, the line and the entry.

#include "FoamDictionary.hpp"
#include "Function1.hpp"
#include "Rotation.hpp"
#include "Vector3.hpp"

#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rbm::motion {

class SolidBodyMotion {
public:
    virtual ~SolidBodyMotion() = default;

    // OpenFOAM type name ("rotatingMotion", ...).
    virtual std::string_view type() const = 0;
    // The transformation at time t (OpenFOAM solidBodyMotionFunction::transformation()).
    virtual Septernion transformation(double t) const = 0;

    Vector3 transformPoint(double t, const Vector3& point0) const { return transformation(t).transformPoint(point0); }
    // points[i] = transformation(t) applied to points0[i] (same sizes).
    void transformPoints(double t, std::span<const Vector3> points0, std::span<Vector3> points) const;
    // displacement[i] = transformed points0[i] − points0[i] (same sizes).
    void displacements(double t, std::span<const Vector3> points0, std::span<Vector3> displacement) const;

    // Reads `solidBodyMotionFunction` and the coefficients from `dict` (see header comment).
    // `caseDirectory` resolves relative file names and $FOAM_CASE (tables, tabulated6DoFMotion).
    static std::unique_ptr<SolidBodyMotion> New(const io::Dictionary& dict,
                                                const std::filesystem::path& caseDirectory = {});
};

// The names SolidBodyMotion::New accepts, sorted.
std::vector<std::string> solidBodyMotionTypeNames();

class LinearMotion final : public SolidBodyMotion {
public:
    explicit LinearMotion(const Vector3& velocity) : velocity_(velocity) {}
    static std::unique_ptr<SolidBodyMotion> read(const io::Dictionary& coeffs, const std::filesystem::path& caseDirectory);
    std::string_view type() const override { return "linearMotion"; }
    Septernion transformation(double t) const override;

private:
    Vector3 velocity_;
};

class RotatingMotion final : public SolidBodyMotion {
public:
    // axis: any non-zero length; omega in rad/s.
    RotatingMotion(const Vector3& origin, const Vector3& axis, std::unique_ptr<Function1<double>> omega);
    static std::unique_ptr<SolidBodyMotion> read(const io::Dictionary& coeffs, const std::filesystem::path& caseDirectory);
    std::string_view type() const override { return "rotatingMotion"; }
    Septernion transformation(double t) const override;

private:
    Vector3 origin_;
    Vector3 axis_;
    std::unique_ptr<Function1<double>> omega_;
};

class OscillatingLinearMotion final : public SolidBodyMotion {
public:
    OscillatingLinearMotion(const Vector3& amplitude, double omega) : amplitude_(amplitude), omega_(omega) {}
    static std::unique_ptr<SolidBodyMotion> read(const io::Dictionary& coeffs, const std::filesystem::path& caseDirectory);
    std::string_view type() const override { return "oscillatingLinearMotion"; }
    Septernion transformation(double t) const override;

private:
    Vector3 amplitude_;
    double omega_;
};

class OscillatingRotatingMotion final : public SolidBodyMotion {
public:
    // amplitudeDegrees: Euler angles (XYZ sequence) in degrees; omega in rad/s.
    OscillatingRotatingMotion(const Vector3& origin, const Vector3& amplitudeDegrees, double omega)
        : origin_(origin), amplitude_(amplitudeDegrees), omega_(omega)
    {}
    static std::unique_ptr<SolidBodyMotion> read(const io::Dictionary& coeffs, const std::filesystem::path& caseDirectory);
    std::string_view type() const override { return "oscillatingRotatingMotion"; }
    Septernion transformation(double t) const override;

private:
    Vector3 origin_;
    Vector3 amplitude_;
    double omega_;
};

class MultiMotion final : public SolidBodyMotion {
public:
    // motions in OpenFOAM's listed order: the last one is applied first.
    explicit MultiMotion(std::vector<std::unique_ptr<SolidBodyMotion>> motions);
    static std::unique_ptr<SolidBodyMotion> read(const io::Dictionary& coeffs, const std::filesystem::path& caseDirectory);
    std::string_view type() const override { return "multiMotion"; }
    Septernion transformation(double t) const override;
    const std::vector<std::unique_ptr<SolidBodyMotion>>& motions() const { return motions_; }

private:
    std::vector<std::unique_ptr<SolidBodyMotion>> motions_;
};

class Tabulated6DoFMotion final : public SolidBodyMotion {
public:
    struct Row {
        double time = 0.0;
        Vector3 translation{};
        Vector3 rotationDegrees{};   // Euler angles, XYZ sequence
    };
    // rows: times strictly increasing. `source` names the data in error messages.
    Tabulated6DoFMotion(const Vector3& centreOfGravity, std::vector<Row> rows, std::string source);
    static std::unique_ptr<SolidBodyMotion> read(const io::Dictionary& coeffs, const std::filesystem::path& caseDirectory);
    // Reads the data file: `( (t ((tx ty tz) (rx ry rz))) ... )`, optionally `N ( ... )`, with
    // comments and an optional FoamFile header.
    static std::vector<Row> readDataFile(const std::filesystem::path& path);
    std::string_view type() const override { return "tabulated6DoFMotion"; }
    Septernion transformation(double t) const override;

private:
    Vector3 centreOfGravity_;
    std::vector<double> times_;
    std::vector<Vector3> translations_;
    std::vector<Vector3> rotationsDegrees_;
    std::string source_;
};

} // namespace rbm::motion

// OpenFOAM v1912 solid-body motion functions. Each transformation() mirrors the OpenFOAM
// expression in a comment so that the composition order can be checked line by line.

#include "SolidBodyMotion.hpp"

#include "InputError.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <sstream>

namespace rbm::motion {

namespace {

constexpr double degreesToRadians = std::numbers::pi / 180.0;

using Reader = std::function<std::unique_ptr<SolidBodyMotion>(const io::Dictionary&, const std::filesystem::path&)>;

// The selection table: plain map, filled on first use (no static registration).
const std::map<std::string, Reader, std::less<>>& motionReaders()
{
    static const std::map<std::string, Reader, std::less<>> readers{
        {"linearMotion", &LinearMotion::read},
        {"rotatingMotion", &RotatingMotion::read},
        {"oscillatingLinearMotion", &OscillatingLinearMotion::read},
        {"oscillatingRotatingMotion", &OscillatingRotatingMotion::read},
        {"multiMotion", &MultiMotion::read},
        {"tabulated6DoFMotion", &Tabulated6DoFMotion::read},
    };
    return readers;
}

std::string joinNames(const std::vector<std::string>& names)
{
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : " ") + n;
    return out;
}

// septernion(-origin)*R*septernion(origin): rotation R about `origin`.
Septernion rotationAbout(const Vector3& origin, const Quaternion& rotation)
{
    return Septernion(-origin) * rotation * Septernion(origin);
}

// OpenFOAM interpolateSplineXY (src/OpenFOAM/interpolations/interpolateSplineXY): values
// before the first / after the last time are the end values; two rows interpolate linearly;
// otherwise a Catmull-Rom cubic with the missing outer rows extrapolated linearly
// (y0 = 2 y1 − y2, y3 = 2 y2 − y1). OpenFOAM indexes row −1 when t equals the first time of a
// table of three or more rows; rbm returns the first row there (the cubic's own limit).
template <class T>
T interpolateSplineXY(double x, const std::vector<double>& xs, const std::vector<T>& ys)
{
    const std::size_t n = xs.size();
    if (n == 1 || x <= xs[0]) return ys[0];
    if (x > xs[n - 1]) return ys[n - 1];
    if (n == 2) return (x - xs[0]) / (xs[1] - xs[0]) * (ys[1] - ys[0]) + ys[0];
    std::size_t hi = 0;
    while (hi < n && xs[hi] < x) ++hi;
    const std::size_t lo = hi - 1;
    const T& y1 = ys[lo];
    const T& y2 = ys[hi];
    const T y0 = lo == 0 ? 2.0 * y1 - y2 : ys[lo - 1];
    const T y3 = hi + 1 == n ? 2.0 * y2 - y1 : ys[hi + 1];
    const double mu = (x - xs[lo]) / (xs[hi] - xs[lo]);
    return 0.5 * (2.0 * y1 +
                  mu * (-1.0 * y0 + y2 +
                        mu * ((2.0 * y0 - 5.0 * y1 + 4.0 * y2 - y3) + mu * (-1.0 * y0 + 3.0 * y1 - 3.0 * y2 + y3))));
}

} // namespace

// ---------------------------------------------------------------------------------------

void SolidBodyMotion::transformPoints(double t, std::span<const Vector3> points0, std::span<Vector3> points) const
{
    const Septernion transform = transformation(t);
    const std::size_t n = std::min(points0.size(), points.size());
    for (std::size_t i = 0; i < n; ++i) points[i] = transform.transformPoint(points0[i]);
}

void SolidBodyMotion::displacements(double t, std::span<const Vector3> points0, std::span<Vector3> displacement) const
{
    const Septernion transform = transformation(t);
    const std::size_t n = std::min(points0.size(), displacement.size());
    for (std::size_t i = 0; i < n; ++i) displacement[i] = transform.transformPoint(points0[i]) - points0[i];
}

std::unique_ptr<SolidBodyMotion> SolidBodyMotion::New(const io::Dictionary& dict, const std::filesystem::path& caseDirectory)
{
    const io::Entry* typeEntry = dict.find("solidBodyMotionFunction");
    if (!typeEntry)
        throw InputError(dict.file(), dict.line(),
                         "keyword 'solidBodyMotionFunction' is undefined in dictionary '" + dict.name() +
                             "'. Valid solidBodyMotionFunction types are: " + joinNames(solidBodyMotionTypeNames()));
    const std::string type = dict.get<std::string>("solidBodyMotionFunction");
    const auto& readers = motionReaders();
    const auto reader = readers.find(type);
    if (reader == readers.end())
        throw InputError(typeEntry->file(), typeEntry->line(),
                         "Unknown solidBodyMotionFunction type " + type + " in dictionary '" + dict.name() +
                             "'. Valid solidBodyMotionFunction types are: " + joinNames(solidBodyMotionTypeNames()));
    const io::Dictionary* coeffs = dict.findDictionary(type + "Coeffs");
    return reader->second(coeffs ? *coeffs : dict, caseDirectory);
}

std::vector<std::string> solidBodyMotionTypeNames()
{
    std::vector<std::string> names;
    for (const auto& [name, reader] : motionReaders()) names.push_back(name);
    return names;
}

// ---------------------------------------------------------------------------------------

std::unique_ptr<SolidBodyMotion> LinearMotion::read(const io::Dictionary& coeffs, const std::filesystem::path&)
{
    return std::make_unique<LinearMotion>(coeffs.get<Vector3>("velocity"));
}

Septernion LinearMotion::transformation(double t) const
{
    // septernion(-displacement)*quaternion(1)
    const Vector3 displacement = velocity_ * t;
    return Septernion(-displacement) * Quaternion::identity();
}

// ---------------------------------------------------------------------------------------

RotatingMotion::RotatingMotion(const Vector3& origin, const Vector3& axis, std::unique_ptr<Function1<double>> omega)
    : origin_(origin), axis_(axis), omega_(std::move(omega))
{
    if (!(norm(axis_) > 0.0)) throw std::invalid_argument("rotatingMotion: the axis must not be zero");
}

std::unique_ptr<SolidBodyMotion> RotatingMotion::read(const io::Dictionary& coeffs, const std::filesystem::path& caseDirectory)
{
    const Vector3 origin = coeffs.get<Vector3>("origin");
    const Vector3 axis = coeffs.get<Vector3>("axis");
    if (!(norm(axis) > 0.0)) {
        const io::Entry& entry = coeffs.lookup("axis");
        throw InputError(entry.file(), entry.line(), "rotatingMotion: 'axis' must be a non-zero vector");
    }
    return std::make_unique<RotatingMotion>(origin, axis, Function1<double>::New("omega", coeffs, caseDirectory));
}

Septernion RotatingMotion::transformation(double t) const
{
    // angle = omega->integrate(0, t); septernion(-origin)*quaternion(axis, angle)*septernion(origin)
    const double angle = omega_->integrate(0.0, t);
    return rotationAbout(origin_, Quaternion::fromAxisAngle(axis_, angle));
}

// ---------------------------------------------------------------------------------------

std::unique_ptr<SolidBodyMotion> OscillatingLinearMotion::read(const io::Dictionary& coeffs, const std::filesystem::path&)
{
    return std::make_unique<OscillatingLinearMotion>(coeffs.get<Vector3>("amplitude"), coeffs.get<double>("omega"));
}

Septernion OscillatingLinearMotion::transformation(double t) const
{
    // displacement = amplitude*sin(omega*t); septernion(-displacement)*quaternion(1)
    const Vector3 displacement = amplitude_ * std::sin(omega_ * t);
    return Septernion(-displacement) * Quaternion::identity();
}

// ---------------------------------------------------------------------------------------

std::unique_ptr<SolidBodyMotion> OscillatingRotatingMotion::read(const io::Dictionary& coeffs, const std::filesystem::path&)
{
    return std::make_unique<OscillatingRotatingMotion>(coeffs.get<Vector3>("origin"), coeffs.get<Vector3>("amplitude"),
                                                       coeffs.get<double>("omega"));
}

Septernion OscillatingRotatingMotion::transformation(double t) const
{
    // eulerAngles = amplitude*sin(omega*t) * pi/180; quaternion(quaternion::XYZ, eulerAngles);
    // septernion(-origin)*R*septernion(origin)
    const Vector3 eulerAngles = amplitude_ * std::sin(omega_ * t) * degreesToRadians;
    return rotationAbout(origin_, Quaternion::fromEulerAngles(RotationSequence::XYZ, eulerAngles));
}

// ---------------------------------------------------------------------------------------

MultiMotion::MultiMotion(std::vector<std::unique_ptr<SolidBodyMotion>> motions) : motions_(std::move(motions))
{
    if (motions_.empty()) throw std::invalid_argument("multiMotion needs at least one motion");
}

std::unique_ptr<SolidBodyMotion> MultiMotion::read(const io::Dictionary& coeffs, const std::filesystem::path& caseDirectory)
{
    // OpenFOAM: every dictionary entry of the coefficients, in order, is a motion.
    std::vector<std::unique_ptr<SolidBodyMotion>> motions;
    for (const io::Entry& entry : coeffs.entries())
        if (entry.isDictionary()) motions.push_back(SolidBodyMotion::New(entry.dictionary(), caseDirectory));
    if (motions.empty())
        throw InputError(coeffs.file(), coeffs.line(),
                         "multiMotion in dictionary '" + coeffs.name() +
                             "' holds no motion: expected sub-dictionaries, each with a solidBodyMotionFunction");
    return std::make_unique<MultiMotion>(std::move(motions));
}

Septernion MultiMotion::transformation(double t) const
{
    // TR = SBMFs_[0].transformation(); TR *= SBMFs_[i].transformation() for i = 1..n-1
    Septernion transform = motions_.front()->transformation(t);
    for (std::size_t i = 1; i < motions_.size(); ++i) transform *= motions_[i]->transformation(t);
    return transform;
}

// ---------------------------------------------------------------------------------------

Tabulated6DoFMotion::Tabulated6DoFMotion(const Vector3& centreOfGravity, std::vector<Row> rows, std::string source)
    : centreOfGravity_(centreOfGravity), source_(std::move(source))
{
    if (rows.empty()) throw InputError(source_, 0, "tabulated6DoFMotion: the time data table is empty");
    for (std::size_t i = 1; i < rows.size(); ++i)
        if (!(rows[i].time > rows[i - 1].time)) {
            std::ostringstream message;
            message << "tabulated6DoFMotion: times must increase strictly, but row " << i << " has time "
                    << rows[i].time << " after " << rows[i - 1].time;
            throw InputError(source_, 0, message.str());
        }
    for (const Row& row : rows) {
        times_.push_back(row.time);
        translations_.push_back(row.translation);
        rotationsDegrees_.push_back(row.rotationDegrees);
    }
}

std::vector<Tabulated6DoFMotion::Row> Tabulated6DoFMotion::readDataFile(const std::filesystem::path& path)
{
    const std::vector<io::Token> tokens = readListFileTokens(path);
    io::TokenStream stream(tokens, path.string());
    long long count = -1;
    if (!stream.atEnd() && stream.peek().kind == io::Token::Kind::Number) count = stream.readLabel();
    stream.expectPunctuation('(');
    std::vector<Row> rows;
    while (!stream.peek().isPunctuation(')')) {
        // (t ((tx ty tz) (rx ry rz)))
        Row row;
        stream.expectPunctuation('(');
        row.time = stream.readScalar();
        stream.expectPunctuation('(');
        row.translation = stream.readVector();
        row.rotationDegrees = stream.readVector();
        stream.expectPunctuation(')');
        stream.expectPunctuation(')');
        rows.push_back(row);
    }
    stream.expectPunctuation(')');
    if (count >= 0 && count != static_cast<long long>(rows.size()))
        stream.fail("the list says " + std::to_string(count) + " rows but holds " + std::to_string(rows.size()));
    if (!stream.atEnd()) stream.fail("unexpected '" + stream.peek().text + "' after the time data list");
    return rows;
}

std::unique_ptr<SolidBodyMotion> Tabulated6DoFMotion::read(const io::Dictionary& coeffs,
                                                          const std::filesystem::path& caseDirectory)
{
    const io::Entry& fileEntry = coeffs.lookup("timeDataFileName");
    const std::filesystem::path path = expandCaseFileName(coeffs.get<std::string>("timeDataFileName"), caseDirectory,
                                                          fileEntry.file(), fileEntry.line());
    const Vector3 centreOfGravity = coeffs.get<Vector3>("CofG");
    return std::make_unique<Tabulated6DoFMotion>(centreOfGravity, readDataFile(path), path.string());
}

Septernion Tabulated6DoFMotion::transformation(double t) const
{
    if (t < times_.front() || t > times_.back()) {
        std::ostringstream message;
        message << "tabulated6DoFMotion: time " << t << " is outside the time data table (" << times_.front() << " .. "
                << times_.back() << ")";
        throw InputError(source_, 0, message.str());
    }
    // TRV = interpolateSplineXY(t, times_, values_); TRV[1] *= pi/180;
    // septernion(-CofG_ + -TRV[0])*quaternion(quaternion::XYZ, TRV[1])*septernion(CofG_)
    const Vector3 translation = interpolateSplineXY(t, times_, translations_);
    const Vector3 angles = interpolateSplineXY(t, times_, rotationsDegrees_) * degreesToRadians;
    const Quaternion rotation = Quaternion::fromEulerAngles(RotationSequence::XYZ, angles);
    return Septernion(-centreOfGravity_ + -translation) * rotation * Septernion(centreOfGravity_);
}

} // namespace rbm::motion

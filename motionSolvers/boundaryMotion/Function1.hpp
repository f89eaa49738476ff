#pragma once
// Functions of time read from OpenFOAM dictionaries: OpenFOAM v1912's Function1<Type> for
// Type = scalar (double) and vector (rbm::Vector3), the types the boundary-motion laws use.
//
// Selection (Function1::New(entryName, dict), as v1912's Function1New.C):
//  1. `entryName { type <type>; <coefficients> }`  a sub-dictionary: its `type` names the
//     function, its other entries are the coefficients;
//  2. `entryName <number or vector>;`              a first token that is not a word: constant;
//  3. `entryName <type> <inline data>;`            constant, uniform, table, polynomial keep
//     their data in the entry itself;
//  4. `entryName <type>;`                          the coefficients are in the sub-dictionary
//     `<entryName>Coeffs` when present, else in `dict` itself.
//
// Types (v1912 semantics):
//   constant (alias uniform)  value; integrate = value (t2 − t1). The dictionary form reads
//                             `value` (later OpenFOAM versions' syntax; v1912 has no such form).
//   zero, one                 0 and 1 (the vector one is (1 1 1))
//   polynomial ((c0 e0) (c1 e1) ...)  Σ c_i t^e_i; for vectors c_i and e_i are vectors and the
//                             power is taken componentwise. Integral Σ c_i/(e_i+1) t^(e_i+1);
//                             an exponent of −1 cannot be integrated (OpenFOAM silently returns
//                             0; rbm throws).
//   sine                      amplitude(t) sin(2π frequency(t) (t − t0)) scale(t) + level(t);
//                             coefficients t0 (default 0), amplitude and frequency (scalar
//                             Function1s), scale and level (Function1s of the value type).
//   square                    as sine with sin(...) replaced by +1 when the fraction of the
//                             wave count w = frequency(t) (t − t0) (std::modf, so negative
//                             before t0) is below markSpace/(1 + markSpace) (markSpace default 1),
//                             else −1. Note: for t < t0 the fraction is negative, so the wave is
//                             +1 there, exactly as OpenFOAM.
//   table ((t0 v0) (t1 v1) ...)      linear interpolation; `outOfBounds clamp|error|warn|repeat`
//                             (default clamp) and `interpolationScheme linear` are read from the
//                             coefficient dictionary (4. above). An unknown outOfBounds name is an
//                             error (OpenFOAM warns and clamps); only linear interpolation exists.
//   tableFile                 coefficient `file "name"` naming a file that holds the same list;
//                             `$FOAM_CASE`, `<case>`, `<constant>`, `<system>` and environment
//                             variables are expanded, relative names are relative to the case
//                             folder (OpenFOAM: the working directory, which is the case folder).
// OpenFOAM v1912 does not implement integrate() for sine and square (fatal error) and fails
// when a table is integrated beyond its ends. rbm integrates them: sine and square exactly when
// their coefficient functions are constant, numerically (adaptive Simpson) otherwise; tables
// integrate the function that value() defines (held constant when clamped, periodic when
// repeated). Where OpenFOAM returns a value, rbm returns the same value.
//
// Example (dynamicMeshDict, rotatingMotion coefficients):
//     omega       6.2832;                          // constant, rad/s
//     omega       table ((0 0) (1 6.2832) (10 6.2832));
//     omega       polynomial ((1 0) (2 1));        // 1 + 2t
//     omega       sine;
//     omegaCoeffs { frequency 0.5; amplitude 1; scale 3.1416; level 0; }
//     omega       { type square; frequency 1; amplitude 1; scale 1; level 0; markSpace 3; }
//     omega       tableFile;
//     omegaCoeffs { file "$FOAM_CASE/constant/omega.dat"; outOfBounds repeat; }
//
// Every error is an rbm::InputError naming the file, the line and the entry.

#include "FoamDictionary.hpp"
#include "Vector3.hpp"

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace rbm::motion {

template <class T>
class Function1 {
public:
    explicit Function1(std::string name) : name_(std::move(name)) {}
    virtual ~Function1() = default;
    Function1(const Function1&) = delete;
    Function1& operator=(const Function1&) = delete;

    // The entry name the function was read from (e.g. "omega").
    const std::string& name() const { return name_; }
    // The OpenFOAM type name ("constant", "table", ...).
    virtual std::string_view type() const = 0;

    virtual T value(double t) const = 0;
    // ∫_{t1}^{t2} value(t) dt (negative when t2 < t1).
    virtual T integrate(double t1, double t2) const = 0;
    // True when value(t) does not depend on t (constant, zero, one).
    virtual bool isConstant() const { return false; }

    // Reads entry `entryName` of `dict` (see the header comment). `caseDirectory` resolves
    // relative file names and $FOAM_CASE (empty: the working directory).
    static std::unique_ptr<Function1> New(std::string_view entryName, const io::Dictionary& dict,
                                          const std::filesystem::path& caseDirectory = {});

private:
    std::string name_;
};

extern template class Function1<double>;
extern template class Function1<Vector3>;

// A constant function (what `name value;` reads to).
template <class T>
std::unique_ptr<Function1<T>> makeConstantFunction1(std::string name, const T& value);

// The type names Function1::New accepts, sorted.
std::vector<std::string> function1TypeNames();

// OpenFOAM's fileName::expand for names in case dictionaries: `$FOAM_CASE`, `${FOAM_CASE}`
// and `<case>` become `caseDirectory` (the working directory when empty), `<constant>` and
// `<system>` the case's constant/ and system/ folders, `$VAR`/`${VAR}` environment variables
// and a leading `~` the home folder; a relative result is taken relative to the case folder.
// Throws rbm::InputError (file, line) for an undefined variable.
std::filesystem::path expandCaseFileName(std::string_view name, const std::filesystem::path& caseDirectory,
                                         const std::string& file = {}, int line = 0);

// The tokens of a file that holds a bare OpenFOAM list (tableFile and tabulated6DoFMotion data):
// `//` and `/* */` comments allowed, an optional FoamFile header skipped, gzip read
// transparently. Throws rbm::InputError naming the file when it cannot be read or lexed.
std::vector<io::Token> readListFileTokens(const std::filesystem::path& path);

} // namespace rbm::motion

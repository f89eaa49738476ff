// OpenFOAM v1912 Function1 types for scalars and vectors. See Function1.hpp for the syntax and
// the deviations (integrals OpenFOAM does not implement).

#include "Function1.hpp"

#include "CompressedFile.hpp"
#include "FoamTokenizer.hpp"
#include "InputError.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cctype>
#include <cstdlib>
#include <iostream>
#include <numbers>
#include <sstream>
#include <utility>

namespace rbm::motion {

namespace {

using io::Token;
using io::TokenStream;

// ---------------------------------------------------------------------------------------
// Value-type helpers: the same code serves double and Vector3.

double magnitude(double v) { return std::abs(v); }
double magnitude(const Vector3& v) { return norm(v); }

template <class T> T zeroValue() { return T{}; }
template <class T> T oneValue();
template <> double oneValue<double>() { return 1.0; }
template <> Vector3 oneValue<Vector3>() { return {1.0, 1.0, 1.0}; }

template <class T> T readValue(TokenStream& stream);
template <> double readValue<double>(TokenStream& stream) { return stream.readScalar(); }
template <> Vector3 readValue<Vector3>(TokenStream& stream) { return stream.readVector(); }

template <class T> constexpr const char* valueTypeName();
template <> constexpr const char* valueTypeName<double>() { return "scalar"; }
template <> constexpr const char* valueTypeName<Vector3>() { return "vector"; }

// Componentwise c * x^e (OpenFOAM cmptMultiply(c, cmptPow(one*x, e))).
double powerTerm(double c, double x, double e) { return c * std::pow(x, e); }
Vector3 powerTerm(const Vector3& c, double x, const Vector3& e)
{
    return {c.x * std::pow(x, e.x), c.y * std::pow(x, e.y), c.z * std::pow(x, e.z)};
}
// Componentwise c/(e+1) (x2^(e+1) − x1^(e+1)).
double powerIntegral(double c, double e, double x1, double x2)
{
    return c / (e + 1.0) * (std::pow(x2, e + 1.0) - std::pow(x1, e + 1.0));
}
Vector3 powerIntegral(const Vector3& c, const Vector3& e, double x1, double x2)
{
    return {powerIntegral(c.x, e.x, x1, x2), powerIntegral(c.y, e.y, x1, x2), powerIntegral(c.z, e.z, x1, x2)};
}
// OpenFOAM: canIntegrate_ is false when mag(exponent + one) < ROOTVSMALL.
bool isMinusOne(double e) { return std::abs(e + 1.0) < 1e-150; }
bool isMinusOne(const Vector3& e) { return norm(e + oneValue<Vector3>()) < 1e-150; }

std::string joinNames(const std::vector<std::string>& names)
{
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : " ") + n;
    return out;
}

std::string validTypesText() { return "Valid Function1 types are: " + joinNames(function1TypeNames()); }

// Numerical ∫_a^b f, adaptive Simpson on `pieces` equal sub-intervals. Used only for sine and
// square waves whose coefficients vary in time (OpenFOAM cannot integrate those at all).
template <class T, class F>
T simpsonStep(const F& f, double a, double b, const T& fa, const T& fm, const T& fb, const T& whole,
              double tolerance, int depth)
{
    const double m = 0.5 * (a + b);
    const double lm = 0.5 * (a + m);
    const double rm = 0.5 * (m + b);
    const T flm = f(lm);
    const T frm = f(rm);
    const T left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
    const T right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    const T delta = left + right - whole;
    if (depth <= 0 || magnitude(delta) <= 15.0 * tolerance) return left + right + delta / 15.0;
    return simpsonStep<T>(f, a, m, fa, flm, fm, left, 0.5 * tolerance, depth - 1) +
           simpsonStep<T>(f, m, b, fm, frm, fb, right, 0.5 * tolerance, depth - 1);
}

template <class T, class F>
T integrateNumerically(const F& f, double a, double b, int pieces)
{
    if (a == b) return zeroValue<T>();
    const double h = (b - a) / pieces;
    T sum = zeroValue<T>();
    for (int k = 0; k < pieces; ++k) {
        const double x0 = a + k * h;
        const double x1 = (k + 1 == pieces) ? b : a + (k + 1) * h;
        const T f0 = f(x0);
        const T f1 = f(x1);
        const T fm = f(0.5 * (x0 + x1));
        const T whole = (x1 - x0) / 6.0 * (f0 + 4.0 * fm + f1);
        const double scale = std::max(1.0, magnitude(whole) / std::max(std::abs(x1 - x0), 1e-300));
        sum += simpsonStep<T>(f, x0, x1, f0, fm, f1, whole, 1e-13 * scale * std::abs(x1 - x0), 40);
    }
    return sum;
}

// ---------------------------------------------------------------------------------------
// constant, zero, one

template <class T>
class Constant final : public Function1<T> {
public:
    Constant(std::string name, const T& value, std::string_view typeName = "constant")
        : Function1<T>(std::move(name)), value_(value), type_(typeName)
    {}
    std::string_view type() const override { return type_; }
    T value(double) const override { return value_; }
    T integrate(double t1, double t2) const override { return (t2 - t1) * value_; }
    bool isConstant() const override { return true; }

private:
    T value_;
    std::string type_;
};

// ---------------------------------------------------------------------------------------
// polynomial

template <class T>
class Polynomial final : public Function1<T> {
public:
    Polynomial(std::string name, std::vector<std::pair<T, T>> coefficients, std::string file, int line)
        : Function1<T>(std::move(name)), coefficients_(std::move(coefficients)), file_(std::move(file)), line_(line)
    {
        for (const auto& [c, e] : coefficients_)
            if (isMinusOne(e)) canIntegrate_ = false;
    }
    std::string_view type() const override { return "polynomial"; }
    T value(double t) const override
    {
        T y = zeroValue<T>();
        for (const auto& [c, e] : coefficients_) y += powerTerm(c, t, e);
        return y;
    }
    T integrate(double t1, double t2) const override
    {
        if (!canIntegrate_)
            throw InputError(file_, line_,
                             "polynomial '" + this->name() +
                                 "' has an exponent of -1 and cannot be integrated (OpenFOAM would return 0)");
        T y = zeroValue<T>();
        for (const auto& [c, e] : coefficients_) y += powerIntegral(c, e, t1, t2);
        return y;
    }

private:
    std::vector<std::pair<T, T>> coefficients_;
    bool canIntegrate_ = true;
    std::string file_;
    int line_;
};

// ---------------------------------------------------------------------------------------
// sine and square: amplitude(t) * wave(t) * scale(t) + level(t)

template <class T>
class Wave final : public Function1<T> {
public:
    // markFraction < 0: sine; otherwise square with that mark fraction of each wave.
    Wave(std::string name, double t0, std::unique_ptr<Function1<double>> amplitude,
         std::unique_ptr<Function1<double>> frequency, std::unique_ptr<Function1<T>> scale,
         std::unique_ptr<Function1<T>> level, double markSpace, bool square)
        : Function1<T>(std::move(name)), t0_(t0), amplitude_(std::move(amplitude)), frequency_(std::move(frequency)),
          scale_(std::move(scale)), level_(std::move(level)), markSpace_(markSpace), square_(square)
    {}

    std::string_view type() const override { return square_ ? "square" : "sine"; }

    T value(double t) const override
    {
        return amplitude_->value(t) * wave(t, frequency_->value(t)) * scale_->value(t) + level_->value(t);
    }

    T integrate(double t1, double t2) const override
    {
        const bool constantCoefficients = amplitude_->isConstant() && frequency_->isConstant() &&
                                          scale_->isConstant() && level_->isConstant();
        const double markFraction = markSpace_ / (1.0 + markSpace_);
        if (constantCoefficients && (!square_ || (markFraction >= 0.0 && markFraction < 1.0))) {
            const double f = frequency_->value(t1);
            return amplitude_->value(t1) * waveIntegral(t1, t2, f) * scale_->value(t1) + (t2 - t1) * level_->value(t1);
        }
        // Enough pieces that every piece holds at most a quarter wave at the largest sampled frequency.
        double fMax = 0.0;
        for (int k = 0; k <= 16; ++k) fMax = std::max(fMax, std::abs(frequency_->value(t1 + (t2 - t1) * k / 16.0)));
        const double pieces = std::clamp(4.0 * fMax * std::abs(t2 - t1) + 16.0, 16.0, 1.0e6);
        return integrateNumerically<T>([this](double t) { return value(t); }, t1, t2, static_cast<int>(pieces));
    }

private:
    double wave(double t, double f) const
    {
        const double waves = f * (t - t0_);
        if (!square_) return std::sin(2.0 * std::numbers::pi * waves);
        double whole = 0.0;
        const double fraction = std::modf(waves, &whole);   // negative before t0, as OpenFOAM
        return fraction < markSpace_ / (1.0 + markSpace_) ? 1.0 : -1.0;
    }

    // ∫_{t1}^{t2} wave(t) dt for a constant frequency f.
    double waveIntegral(double t1, double t2, double f) const
    {
        if (f == 0.0) return (t2 - t1) * wave(t1, 0.0);
        const double u1 = f * (t1 - t0_);
        const double u2 = f * (t2 - t0_);
        if (!square_) {
            const double twoPi = 2.0 * std::numbers::pi;
            return (std::cos(twoPi * u1) - std::cos(twoPi * u2)) / (twoPi * f);
        }
        return (squareAntiderivative(u2) - squareAntiderivative(u1)) / f;
    }

    // G(u) = ∫_0^u w(v) dv for the square wave in wave-count units: +1 on [n, n+m), −1 on
    // [n+m, n+1) for u ≥ 0; +1 for u < 0 (std::modf's negative fraction is below m ≥ 0).
    double squareAntiderivative(double u) const
    {
        if (u < 0.0) return u;
        const double m = markSpace_ / (1.0 + markSpace_);
        const double n = std::floor(u);
        const double r = u - n;
        return n * (2.0 * m - 1.0) + (r < m ? r : 2.0 * m - r);
    }

    double t0_;
    std::unique_ptr<Function1<double>> amplitude_;
    std::unique_ptr<Function1<double>> frequency_;
    std::unique_ptr<Function1<T>> scale_;
    std::unique_ptr<Function1<T>> level_;
    double markSpace_;
    bool square_;
};

// ---------------------------------------------------------------------------------------
// table and tableFile (OpenFOAM TableBase with linearInterpolationWeights)

enum class Bounding { error, warn, clamp, repeat };

Bounding readBounding(const io::Dictionary& coeffs, const std::string& functionName)
{
    const io::Entry* entry = coeffs.find("outOfBounds");
    if (!entry) return Bounding::clamp;
    const std::string name = coeffs.get<std::string>("outOfBounds");
    if (name == "error") return Bounding::error;
    if (name == "warn") return Bounding::warn;
    if (name == "clamp") return Bounding::clamp;
    if (name == "repeat") return Bounding::repeat;
    throw InputError(entry->file(), entry->line(),
                     "outOfBounds '" + name + "' of table '" + functionName +
                         "' is not valid. Valid outOfBounds values are: clamp error repeat warn");
}

void checkInterpolationScheme(const io::Dictionary& coeffs, const std::string& functionName)
{
    const io::Entry* entry = coeffs.find("interpolationScheme");
    if (!entry) return;
    const std::string scheme = coeffs.get<std::string>("interpolationScheme");
    if (scheme != "linear")
        throw InputError(entry->file(), entry->line(),
                         "interpolationScheme '" + scheme + "' of table '" + functionName +
                             "' is not supported by rbm. Supported interpolation schemes are: linear");
}

// Reads `( (t value) ... )` or `N ( ... )`.
template <class T>
std::vector<std::pair<double, T>> readTable(TokenStream& stream)
{
    long long count = -1;
    if (stream.peek().kind == Token::Kind::Number) count = stream.readLabel();
    stream.expectPunctuation('(');
    std::vector<std::pair<double, T>> rows;
    while (!stream.peek().isPunctuation(')')) {
        stream.expectPunctuation('(');
        const double x = stream.readScalar();
        const T y = readValue<T>(stream);
        stream.expectPunctuation(')');
        rows.emplace_back(x, y);
    }
    stream.expectPunctuation(')');
    if (count >= 0 && count != static_cast<long long>(rows.size()))
        stream.fail("the list says " + std::to_string(count) + " elements but holds " + std::to_string(rows.size()));
    return rows;
}

template <class T>
class Table final : public Function1<T> {
public:
    Table(std::string name, std::string_view typeName, std::vector<std::pair<double, T>> rows, Bounding bounding,
          std::string file, int line)
        : Function1<T>(std::move(name)), type_(typeName), bounding_(bounding), file_(std::move(file)), line_(line)
    {
        if (rows.empty()) throw InputError(file_, line_, "table for entry '" + this->name() + "' is invalid (empty)");
        for (std::size_t i = 1; i < rows.size(); ++i)
            if (!(rows[i].first > rows[i - 1].first)) {
                std::ostringstream message;
                message << "table for entry '" << this->name() << "': out-of-order time " << rows[i].first
                        << " at index " << i << " (times must increase strictly)";
                throw InputError(file_, line_, message.str());
            }
        times_.reserve(rows.size());
        values_.reserve(rows.size());
        for (auto& [x, y] : rows) {
            times_.push_back(x);
            values_.push_back(y);
        }
        cumulative_.assign(times_.size(), zeroValue<T>());
        for (std::size_t i = 1; i < times_.size(); ++i)
            cumulative_[i] = cumulative_[i - 1] + 0.5 * (times_[i] - times_[i - 1]) * (values_[i] + values_[i - 1]);
    }

    std::string_view type() const override { return type_; }

    T value(double t) const override
    {
        const double first = times_.front();
        const double last = times_.back();
        if (t < first || t > last) {
            switch (bounding_) {
            case Bounding::error: outOfRange(t);
            case Bounding::warn: warnOnce(t); [[fallthrough]];
            case Bounding::clamp: return t < first ? values_.front() : values_.back();
            case Bounding::repeat: {
                const double span = last - first;
                if (span <= 0.0) return values_.front();
                double shifted = first + std::fmod(t - first, span);
                if (shifted < first) shifted += span;   // OpenFOAM clamps here instead (fmod < 0); see header
                return interpolate(shifted);
            }
            }
        }
        return interpolate(t);
    }

    T integrate(double t1, double t2) const override { return antiderivative(t2) - antiderivative(t1); }

private:
    T interpolate(double t) const
    {
        // Segment i with times_[i] <= t <= times_[i+1].
        if (times_.size() == 1) return values_.front();
        auto upper = std::upper_bound(times_.begin(), times_.end(), t);
        std::size_t i = static_cast<std::size_t>(std::distance(times_.begin(), upper));
        i = std::clamp<std::size_t>(i, 1, times_.size() - 1) - 1;
        const double w = (t - times_[i]) / (times_[i + 1] - times_[i]);
        return (1.0 - w) * values_[i] + w * values_[i + 1];
    }

    // ∫ from times_.front() to t of value(t) inside the table.
    T inside(double t) const
    {
        if (times_.size() == 1) return zeroValue<T>();
        auto upper = std::upper_bound(times_.begin(), times_.end(), t);
        std::size_t i = static_cast<std::size_t>(std::distance(times_.begin(), upper));
        i = std::clamp<std::size_t>(i, 1, times_.size() - 1) - 1;
        return cumulative_[i] + 0.5 * (t - times_[i]) * (values_[i] + interpolate(t));
    }

    // ∫ from times_.front() to t of value(t), with value() extended as the bounding says.
    T antiderivative(double t) const
    {
        const double first = times_.front();
        const double last = times_.back();
        if (t >= first && t <= last) return inside(t);
        switch (bounding_) {
        case Bounding::error: outOfRange(t);
        case Bounding::warn: warnOnce(t); [[fallthrough]];
        case Bounding::clamp:
            return t < first ? (t - first) * values_.front() : cumulative_.back() + (t - last) * values_.back();
        case Bounding::repeat: {
            const double span = last - first;
            if (span <= 0.0) return (t - first) * values_.front();
            const double periods = std::floor((t - first) / span);
            const double rest = std::clamp(t - first - periods * span, 0.0, span);
            return periods * cumulative_.back() + inside(first + rest);
        }
        }
        return zeroValue<T>();
    }

    [[noreturn]] void outOfRange(double t) const
    {
        std::ostringstream message;
        message << "time " << t << " is outside the table of '" << this->name() << "' (" << times_.front() << " .. "
                << times_.back() << ") and outOfBounds is error";
        throw InputError(file_, line_, message.str());
    }

    void warnOnce(double t) const
    {
        if (warned_.exchange(true)) return;
        std::cerr << "Warning: " << file_ << ':' << line_ << ": time " << t << " is outside the table of '"
                  << this->name() << "' (" << times_.front() << " .. " << times_.back()
                  << "); the end value is used (outOfBounds warn)\n";
    }

    std::string type_;
    std::vector<double> times_;
    std::vector<T> values_;
    std::vector<T> cumulative_;   // ∫ from times_[0] to times_[i]
    Bounding bounding_;
    std::string file_;
    int line_;
    mutable std::atomic<bool> warned_{false};
};

// ---------------------------------------------------------------------------------------
// Selection

// `inlineEntry`: the primitive entry whose first token is the type word (null for the
// dictionary form); `coeffs`: where the coefficients are.
template <class T>
std::unique_ptr<Function1<T>> construct(const std::string& type, const std::string& name, const io::Dictionary& coeffs,
                                        const io::Entry* inlineEntry, const std::string& file, int line,
                                        const std::filesystem::path& caseDirectory)
{
    // The inline data after the type word.
    auto inlineData = [&](const char* what) {
        if (!inlineEntry || inlineEntry->tokens().size() < 2)
            throw InputError(file, line,
                             "Function1 '" + name + "' of type " + type + " needs its " + what +
                                 " in the entry itself: '" + name + " " + type + " ...;'");
        TokenStream stream = inlineEntry->stream();
        stream.next();   // the type word
        return stream;
    };
    auto expectEnd = [&](TokenStream& stream) {
        if (!stream.atEnd()) stream.fail("unexpected '" + stream.peek().text + "' after the value of '" + name + "'");
    };

    if (type == "constant" || type == "uniform") {
        if (!inlineEntry) return std::make_unique<Constant<T>>(name, coeffs.get<T>("value"), type);
        TokenStream stream = inlineData("value");
        T value = readValue<T>(stream);
        expectEnd(stream);
        return std::make_unique<Constant<T>>(name, value, type);
    }
    if (type == "zero") return std::make_unique<Constant<T>>(name, zeroValue<T>(), "zero");
    if (type == "one") return std::make_unique<Constant<T>>(name, oneValue<T>(), "one");
    if (type == "polynomial") {
        TokenStream stream = inlineData("coefficient list ((coefficient exponent) ...)");
        std::vector<std::pair<T, T>> coefficients;
        stream.expectPunctuation('(');
        while (!stream.peek().isPunctuation(')')) {
            stream.expectPunctuation('(');
            T c = readValue<T>(stream);
            T e = readValue<T>(stream);
            stream.expectPunctuation(')');
            coefficients.emplace_back(c, e);
        }
        stream.expectPunctuation(')');
        expectEnd(stream);
        if (coefficients.empty())
            throw InputError(file, line, "polynomial coefficients for entry '" + name + "' are invalid (empty)");
        return std::make_unique<Polynomial<T>>(name, std::move(coefficients), file, line);
    }
    if (type == "sine" || type == "square") {
        const double t0 = coeffs.getOrDefault<double>("t0", 0.0);
        auto amplitude = Function1<double>::New("amplitude", coeffs, caseDirectory);
        auto frequency = Function1<double>::New("frequency", coeffs, caseDirectory);
        auto scale = Function1<T>::New("scale", coeffs, caseDirectory);
        auto level = Function1<T>::New("level", coeffs, caseDirectory);
        const double markSpace = type == "square" ? coeffs.getOrDefault<double>("markSpace", 1.0) : 1.0;
        return std::make_unique<Wave<T>>(name, t0, std::move(amplitude), std::move(frequency), std::move(scale),
                                         std::move(level), markSpace, type == "square");
    }
    if (type == "table") {
        TokenStream stream = inlineData("list ((time value) ...)");
        auto rows = readTable<T>(stream);
        expectEnd(stream);
        checkInterpolationScheme(coeffs, name);
        return std::make_unique<Table<T>>(name, "table", std::move(rows), readBounding(coeffs, name), file, line);
    }
    if (type == "tableFile") {
        const io::Entry* fileEntry = coeffs.find("file");
        if (!fileEntry)
            throw InputError(coeffs.file(), coeffs.line(),
                             "keyword 'file' is undefined in dictionary '" + coeffs.name() + "': tableFile '" + name +
                                 "' needs the name of its data file");
        const std::filesystem::path path =
            expandCaseFileName(coeffs.get<std::string>("file"), caseDirectory, fileEntry->file(), fileEntry->line());
        const std::vector<Token> tokens = readListFileTokens(path);
        TokenStream stream(tokens, path.string());
        auto rows = readTable<T>(stream);
        if (!stream.atEnd()) stream.fail("unexpected '" + stream.peek().text + "' after the table");
        checkInterpolationScheme(coeffs, name);
        return std::make_unique<Table<T>>(name, "tableFile", std::move(rows), readBounding(coeffs, name),
                                          path.string(), 0);
    }
    throw InputError(file, line, "Unknown Function1 type " + type + " for Function1 " + name + ". " + validTypesText());
}

} // namespace

// ---------------------------------------------------------------------------------------

template <class T>
std::unique_ptr<Function1<T>> Function1<T>::New(std::string_view entryName, const io::Dictionary& dict,
                                                const std::filesystem::path& caseDirectory)
{
    const std::string name(entryName);
    const io::Entry* entry = dict.find(entryName);
    if (!entry)
        throw InputError(dict.file(), dict.line(),
                         "keyword '" + name + "' is undefined in dictionary '" + dict.name() + "': expected a " +
                             valueTypeName<T>() + " Function1 (a value or a type). " + validTypesText());

    if (entry->isDictionary()) {
        const io::Dictionary& coeffs = entry->dictionary();
        const io::Entry* typeEntry = coeffs.find("type");
        if (!typeEntry)
            throw InputError(entry->file(), entry->line(),
                             "Function1 '" + name + "' is a dictionary without a 'type' entry. " + validTypesText());
        return construct<T>(coeffs.get<std::string>("type"), name, coeffs, nullptr, entry->file(), entry->line(),
                            caseDirectory);
    }

    const std::vector<Token>& tokens = entry->tokens();
    if (tokens.empty())
        throw InputError(entry->file(), entry->line(), "Function1 '" + name + "' has no value. " + validTypesText());
    if (tokens.front().kind != Token::Kind::Word) {
        TokenStream stream = entry->stream();
        T value = readValue<T>(stream);
        if (!stream.atEnd()) stream.fail("unexpected '" + stream.peek().text + "' after the value of '" + name + "'");
        return std::make_unique<Constant<T>>(name, value);
    }
    const io::Dictionary* coeffsDict = dict.findDictionary(name + "Coeffs");
    return construct<T>(tokens.front().text, name, coeffsDict ? *coeffsDict : dict, entry, entry->file(), entry->line(),
                        caseDirectory);
}

template class Function1<double>;
template class Function1<Vector3>;

template <class T>
std::unique_ptr<Function1<T>> makeConstantFunction1(std::string name, const T& value)
{
    return std::make_unique<Constant<T>>(std::move(name), value);
}
template std::unique_ptr<Function1<double>> makeConstantFunction1(std::string, const double&);
template std::unique_ptr<Function1<Vector3>> makeConstantFunction1(std::string, const Vector3&);

std::vector<std::string> function1TypeNames()
{
    return {"constant", "one", "polynomial", "sine", "square", "table", "tableFile", "uniform", "zero"};
}

std::vector<Token> readListFileTokens(const std::filesystem::path& path)
{
    const std::string text = io::readFileContents(path);
    io::FoamTokenizer tokenizer(text, path.string());
    std::vector<Token> tokens = tokenizer.readAll();
    if (tokens.size() >= 2 && tokens[0].isWord("FoamFile") && tokens[1].isPunctuation('{')) {
        std::size_t i = 2;
        int depth = 1;
        for (; i < tokens.size() && depth > 0; ++i) {
            if (tokens[i].isPunctuation('{')) ++depth;
            if (tokens[i].isPunctuation('}')) --depth;
        }
        tokens.erase(tokens.begin(), tokens.begin() + static_cast<std::ptrdiff_t>(i));
    }
    return tokens;
}

std::filesystem::path expandCaseFileName(std::string_view name, const std::filesystem::path& caseDirectory,
                                         const std::string& file, int line)
{
    const std::filesystem::path caseFolder = caseDirectory.empty() ? std::filesystem::current_path() : caseDirectory;
    std::string out;
    std::size_t i = 0;
    if (!name.empty() && name[0] == '~' && (name.size() == 1 || name[1] == '/')) {
        const char* home = std::getenv("HOME");
        if (!home) throw InputError(file, line, "cannot expand '~' in file name '" + std::string(name) + "': HOME is not set");
        out = home;
        i = 1;
    }
    auto startsWith = [&](std::string_view tag) { return name.substr(i, tag.size()) == tag; };
    while (i < name.size()) {
        if (startsWith("<case>")) {
            out += caseFolder.string();
            i += 6;
        } else if (startsWith("<constant>")) {
            out += (caseFolder / "constant").string();
            i += 10;
        } else if (startsWith("<system>")) {
            out += (caseFolder / "system").string();
            i += 8;
        } else if (name[i] == '$') {
            std::string variable;
            std::size_t j = i + 1;
            if (j < name.size() && name[j] == '{') {
                const std::size_t close = name.find('}', j);
                if (close == std::string_view::npos)
                    throw InputError(file, line, "unterminated '${' in file name '" + std::string(name) + "'");
                variable = std::string(name.substr(j + 1, close - j - 1));
                j = close + 1;
            } else {
                while (j < name.size() && (std::isalnum(static_cast<unsigned char>(name[j])) || name[j] == '_')) ++j;
                variable = std::string(name.substr(i + 1, j - i - 1));
            }
            if (variable == "FOAM_CASE") {
                out += caseFolder.string();
            } else {
                const char* value = variable.empty() ? nullptr : std::getenv(variable.c_str());
                if (!value)
                    throw InputError(file, line,
                                     "cannot expand '$" + variable + "' in file name '" + std::string(name) +
                                         "': the environment variable is not set");
                out += value;
            }
            i = j;
        } else {
            out += name[i++];
        }
    }
    std::filesystem::path path(out);
    if (path.is_relative() && !caseDirectory.empty()) path = caseDirectory / path;
    return path;
}

} // namespace rbm::motion

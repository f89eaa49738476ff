#include "Format.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace rbm::benchmark {

std::string fixed(double value, int digits)
{
    if (!std::isfinite(value)) return "–";
    std::ostringstream out;
    out << std::fixed << std::setprecision(digits) << value;
    return out.str();
}

std::string seconds(double value)
{
    if (!std::isfinite(value)) return "–";
    if (value < 0.0995) return fixed(value, 3);
    if (value < 0.995) return fixed(value, 3);
    if (value < 9.95) return fixed(value, 2);
    if (value < 99.5) return fixed(value, 1);
    return fixed(value, 0);
}

std::string count(double value)
{
    if (!std::isfinite(value)) return "–";
    std::string digits = std::to_string(static_cast<long long>(std::llround(value)));
    std::string out;
    for (std::size_t k = 0; k < digits.size(); ++k) {
        if (k > 0 && (digits.size() - k) % 3 == 0) out += ' ';
        out += digits[k];
    }
    return out;
}

std::string sizeLabel(double size)
{
    std::ostringstream out;
    const double exponent = std::floor(std::log10(size) + 1e-9);
    const double mantissa = size / std::pow(10.0, exponent);
    if (std::abs(mantissa - std::round(mantissa)) < 1e-9) {
        if (std::round(mantissa) == 1.0) out << "1e" << exponent;
        else out << std::round(mantissa) << "e" << exponent;
    } else {
        out << size;
    }
    return out.str();
}

} // namespace rbm::benchmark

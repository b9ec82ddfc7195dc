#include "app/cli/number_format.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace voxhap::cli {

std::string withCommas(std::uint64_t n) {
  const std::string digits = std::to_string(n);
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out.push_back(',');
    out.push_back(digits[i]);
  }
  return out;
}

std::string fixed(double value, int decimals) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << value;
  return s.str();
}

std::string scientific(double value, int digits) {
  if (value == 0.0 || !std::isfinite(value)) return fixed(value, 0);
  int exponent = static_cast<int>(std::floor(std::log10(std::fabs(value))));
  double mantissa = value / std::pow(10.0, exponent);
  // rounding may carry into the next power of ten (9.996e5 → "10.0e5")
  const double scale = std::pow(10.0, digits - 1);
  if (std::fabs(std::round(mantissa * scale) / scale) >= 10.0) {
    mantissa /= 10.0;
    ++exponent;
  }
  return fixed(mantissa, digits - 1) + "e" + std::to_string(exponent);
}

}  // namespace voxhap::cli

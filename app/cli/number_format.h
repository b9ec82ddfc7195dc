#pragma once
/// How `voxhap` prints numbers in its text tables (JSON and CSV keep full precision).

#include <cstdint>
#include <string>

namespace voxhap::cli {

/// `n` with thousands separators: 1234567 → "1,234,567".
std::string withCommas(std::uint64_t n);

/// `value` with exactly `decimals` digits after the point: (1.0 / 3, 2) → "0.33".
std::string fixed(double value, int decimals);

/// `value` as mantissa and power of ten with `digits` significant digits, as the
/// paper prints large counts: (4.59e8, 3) → "4.59e8".
std::string scientific(double value, int digits);

}  // namespace voxhap::cli

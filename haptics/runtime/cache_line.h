#pragma once
/// The cache-line size that keeps data written by different threads apart (false sharing).

#include <cstddef>

namespace voxhap {

/// Bytes per cache line on the x86-64 and ARMv8 machines we run on. A named constant
/// rather than std::hardware_destructive_interference_size, whose value GCC warns may
/// change with -mtune.
inline constexpr std::size_t kCacheLineBytes = 64;

}  // namespace voxhap

#pragma once
/// Progress reporting from long engine work (generation, loading, voxelizing).
///
/// The engine never prints; it calls a `ProgressFn` with the fraction done and
/// the command line decides whether and how to show it.

#include <functional>

namespace voxhap {

/// Called with the fraction of the work done, in [0, 1], from the calling thread.
/// May be empty; then nothing is reported.
using ProgressFn = std::function<void(double fractionDone)>;

}  // namespace voxhap

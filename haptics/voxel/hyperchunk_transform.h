#pragma once
/// The voxel-level chessboard distance transform of one hyperchunk (DESIGN §4.2 step 4).
///
/// Input: the feature bytes (feature_rasterizer.h bits) of the hyperchunk and a halo of
/// `range` voxels around it, N³ bytes with N = 64 + 2·range, x fastest. Output: for each
/// of the 64³ core voxels, the chessboard distance to the nearest voxel having a given
/// bit, capped at range + 1 ("far").
///
/// The chessboard distance to a set is min over its voxels of max(|dx|, |dy|, |dz|), so
/// three one-dimensional passes compute it exactly: along x, the distance to the nearest
/// flagged voxel of the row; then along y and along z, d'(u) = min over |k| ≤ range of
/// max(|k|, d(u + k)). Every pass is written as whole-row byte operations that the
/// compiler vectorizes, and rows or planes that hold nothing nearer than "far" are
/// skipped (they cannot lower any minimum). One object per thread; buffers are reused.

#include <cstdint>
#include <vector>

namespace voxhap {

class HyperchunkTransform {
public:
  /// For fields of range `range` voxels (1 … 16).
  explicit HyperchunkTransform(int range);

  int range() const { return range_; }
  /// N, the edge of the input box in voxels.
  int haloSize() const { return n_; }

  /// Writes into `out` (resized to 64³) the capped distance of each core voxel to the
  /// voxels of `bits` (N³) having `bit`. Returns false, leaving `out` untouched, when no
  /// voxel of the box has it: then every distance is far.
  bool run(const std::vector<std::uint8_t>& bits, std::uint8_t bit, std::vector<std::uint8_t>& out);

private:
  int range_;
  int n_;
  std::vector<std::uint8_t> a_;          // after the x pass: c × n × n
  std::vector<std::uint8_t> b_;          // after the y pass: c × c × n
  std::vector<std::uint8_t> rowNear_;    // per row of a_: holds a value below far
  std::vector<std::uint8_t> planeNear_;  // per z plane of b_: holds a value below far
};

}  // namespace voxhap

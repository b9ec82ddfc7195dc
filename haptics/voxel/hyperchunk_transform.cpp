#include "haptics/voxel/hyperchunk_transform.h"

#include <algorithm>
#include <cstddef>

#include "haptics/voxel/tree_shape.h"

namespace voxhap {
namespace {

constexpr int kCore = kHyperEdgeVoxels;

/// Index of (x, y, z) in a box nx × ny × … (x fastest); all arguments ≥ 0.
std::size_t at3(int x, int y, int z, int nx, int ny) {
  return static_cast<std::size_t>(x) +
         static_cast<std::size_t>(nx) *
             (static_cast<std::size_t>(y) + static_cast<std::size_t>(ny) * static_cast<std::size_t>(z));
}

/// out[i] = min(out[i], max(shift, in[i])) over `count` bytes: one step of a min–max pass.
void minMaxInto(std::uint8_t* out, const std::uint8_t* in, std::uint8_t shift, int count) {
  for (int i = 0; i < count; ++i) out[i] = std::min(out[i], std::max(shift, in[i]));
}

}  // namespace

HyperchunkTransform::HyperchunkTransform(int range) : range_(range), n_(kCore + 2 * range) {}

bool HyperchunkTransform::run(const std::vector<std::uint8_t>& bits, std::uint8_t bit,
                              std::vector<std::uint8_t>& out) {
  const int c = kCore;
  const int n = n_;
  const int r = range_;
  const auto far = static_cast<std::uint8_t>(r + 1);

  // x: per row, the distance to the nearest flagged voxel within r, for the core columns
  a_.resize(at3(0, 0, n, c, n));
  rowNear_.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 0);
  bool any = false;
  for (int z = 0; z < n; ++z) {
    for (int y = 0; y < n; ++y) {
      const std::uint8_t* row = &bits[at3(0, y, z, n, n)];
      std::uint8_t* outRow = &a_[at3(0, y, z, c, n)];
      std::uint8_t flagged = 0;
      for (int x = 0; x < n; ++x) flagged |= row[x];
      if (!(flagged & bit)) continue;  // left stale: rowNear_ says not to read it
      rowNear_[static_cast<std::size_t>(y) + static_cast<std::size_t>(n) * static_cast<std::size_t>(z)] = 1;
      any = true;
      std::fill(outRow, outRow + c, far);
      for (int k = -r; k <= r; ++k) {
        const auto shift = static_cast<std::uint8_t>(k < 0 ? -k : k);
        const std::uint8_t* in = row + r + k;
        for (int x = 0; x < c; ++x) outRow[x] = std::min(outRow[x], (in[x] & bit) ? shift : far);
      }
    }
  }
  if (!any) return false;

  // y: b(x, y, z) = min over |k| ≤ r of max(|k|, a(x, y + k, z)), skipping far rows
  b_.resize(at3(0, 0, n, c, c));
  planeNear_.assign(static_cast<std::size_t>(n), 0);
  for (int z = 0; z < n; ++z) {
    const std::uint8_t* near = &rowNear_[static_cast<std::size_t>(n) * static_cast<std::size_t>(z)];
    if (std::none_of(near, near + n, [](std::uint8_t f) { return f != 0; })) continue;
    planeNear_[static_cast<std::size_t>(z)] = 1;
    for (int y = 0; y < c; ++y) {
      std::uint8_t* outRow = &b_[at3(0, y, z, c, c)];
      std::fill(outRow, outRow + c, far);
      for (int k = -r; k <= r; ++k) {
        if (!near[y + r + k]) continue;
        minMaxInto(outRow, &a_[at3(0, y + r + k, z, c, n)], static_cast<std::uint8_t>(k < 0 ? -k : k), c);
      }
    }
  }

  // z: the same across planes of b, skipping far planes
  out.assign(at3(0, 0, c, c, c), far);
  for (int z = 0; z < c; ++z) {
    for (int k = -r; k <= r; ++k) {
      if (!planeNear_[static_cast<std::size_t>(z + r + k)]) continue;
      minMaxInto(&out[at3(0, 0, z, c, c)], &b_[at3(0, 0, z + r + k, c, c)],
                 static_cast<std::uint8_t>(k < 0 ? -k : k), c * c);
    }
  }
  return true;
}

}  // namespace voxhap

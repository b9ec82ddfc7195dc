#include "haptics/voxel/chunk_distance.h"

#include <algorithm>
#include <cassert>
#include <cstdlib>
#include <vector>

namespace voxhap {
namespace {

/// Lines transformed together in the y and z passes, so that their gathers and
/// scatters read whole cache lines (adjacent x).
constexpr int kBatch = 64;

/// One-dimensional pass: out[u] = min(cap, min_i max(|u − i|, in[i])) for u in [0, m),
/// element k of a line at k · stride. `s` and `t` are scratch of m ints each (Meijster's
/// stack of envelope owners and the first position each owns).
void transformLine(int m, const std::uint8_t* in, std::uint8_t* out, std::ptrdiff_t stride, int* s, int* t) {
  auto g = [&](int i) { return static_cast<int>(in[i * stride]); };
  auto f = [&](int x, int i) { return std::max(std::abs(x - i), g(i)); };
  // first position at which source u is at least as near as source i (i < u), minus one
  auto sep = [&](int i, int u) {
    const int mid = (i + u) / 2;
    return g(i) <= g(u) ? std::max(i + g(u), mid) : std::min(u - g(i), mid);
  };
  int q = 0;
  s[0] = 0;
  t[0] = 0;
  for (int u = 1; u < m; ++u) {
    while (q >= 0 && f(t[q], s[q]) > f(t[q], u)) --q;
    if (q < 0) {
      q = 0;
      s[0] = u;
    } else {
      const int w = 1 + sep(s[q], u);
      if (w < m) {
        ++q;
        s[q] = u;
        t[q] = w;
      }
    }
  }
  for (int u = m - 1; u >= 0; --u) {
    const int d = f(u, s[q]);
    if (u == t[q]) --q;
    out[u * stride] = static_cast<std::uint8_t>(std::min(d, int{kChunkDistanceCap}));
  }
}

}  // namespace

void chessboardChunkTransform(std::span<std::uint8_t> field, const glm::ivec3& dims) {
  const auto nx = static_cast<std::size_t>(dims.x);
  const auto ny = static_cast<std::size_t>(dims.y);
  const auto nz = static_cast<std::size_t>(dims.z);
  assert(field.size() == nx * ny * nz);
  if (field.empty()) return;
  for (std::uint8_t& v : field) v = v == 0 ? 0 : kChunkDistanceCap;

  const int longest = std::max({dims.x, dims.y, dims.z});
  std::vector<int> s(static_cast<std::size_t>(longest));
  std::vector<int> t(static_cast<std::size_t>(longest));
  // x: lines are contiguous
  std::vector<std::uint8_t> in(nx);
  for (std::size_t row = 0; row < ny * nz; ++row) {
    std::copy_n(&field[row * nx], nx, in.data());
    transformLine(dims.x, in.data(), &field[row * nx], 1, s.data(), t.data());
  }

  // y and z: gather kBatch adjacent lines into scratch[position][line], transform, scatter
  std::vector<std::uint8_t> scratch(static_cast<std::size_t>(longest) * kBatch);
  std::vector<std::uint8_t> result(scratch.size());
  auto pass = [&](std::size_t lines, std::size_t length, std::size_t lineStride, std::size_t outerCount,
                  std::size_t outerStride) {
    for (std::size_t outer = 0; outer < outerCount; ++outer) {
      for (std::size_t x0 = 0; x0 < lines; x0 += kBatch) {
        const std::size_t batch = std::min<std::size_t>(kBatch, lines - x0);
        std::uint8_t* base = &field[outer * outerStride + x0];
        for (std::size_t k = 0; k < length; ++k) {
          std::copy_n(base + k * lineStride, batch, &scratch[k * kBatch]);
        }
        for (std::size_t b = 0; b < batch; ++b) {
          transformLine(static_cast<int>(length), &scratch[b], &result[b], kBatch, s.data(), t.data());
        }
        for (std::size_t k = 0; k < length; ++k) {
          std::copy_n(&result[k * kBatch], batch, base + k * lineStride);
        }
      }
    }
  };
  pass(nx, ny, nx, nz, nx * ny);  // along y, one z layer at a time
  pass(nx * ny, nz, nx * ny, 1, 0);  // along z, the whole x–y plane as lines
}

}  // namespace voxhap

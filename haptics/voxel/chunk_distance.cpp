#include "haptics/voxel/chunk_distance.h"

#include <algorithm>
#include <cassert>
#include <cstdlib>
#include <vector>

#include "haptics/core/parallel.h"

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

void chessboardChunkTransform(std::span<std::uint8_t> field, const glm::ivec3& dims, int threads) {
  const auto nx = static_cast<std::size_t>(dims.x);
  const auto ny = static_cast<std::size_t>(dims.y);
  const auto nz = static_cast<std::size_t>(dims.z);
  assert(field.size() == nx * ny * nz);
  if (field.empty()) return;
  for (std::uint8_t& v : field) v = v == 0 ? 0 : kChunkDistanceCap;

  // per task: Meijster's stacks, and kBatch lines gathered as scratch[position][line]
  struct Scratch {
    std::vector<int> s, t;
    std::vector<std::uint8_t> in, out;
    explicit Scratch(int length)
        : s(static_cast<std::size_t>(length)),
          t(static_cast<std::size_t>(length)),
          in(static_cast<std::size_t>(length) * kBatch),
          out(static_cast<std::size_t>(length) * kBatch) {}
  };

  // x: lines are contiguous; one z layer per task
  parallelFor(nz, threads, [&](std::size_t z) {
    Scratch scratch(dims.x);
    for (std::size_t row = z * ny; row < (z + 1) * ny; ++row) {
      std::uint8_t* line = &field[row * nx];
      if (std::find(line, line + nx, 0) == line + nx) continue;  // no source: stays capped
      std::copy_n(line, nx, scratch.in.data());
      transformLine(dims.x, scratch.in.data(), line, 1, scratch.s.data(), scratch.t.data());
    }
  });

  // y and z: kBatch adjacent lines gathered, transformed and scattered back; lines that
  // hold nothing below the cap are left as they are
  auto batch = [&](std::uint8_t* base, std::size_t lines, std::size_t length, std::size_t lineStride,
                   Scratch& scratch) {
    bool near = false;
    for (std::size_t k = 0; k < length; ++k) {
      const std::uint8_t* from = base + k * lineStride;
      std::copy_n(from, lines, &scratch.in[k * kBatch]);
      near = near || std::any_of(from, from + lines, [](std::uint8_t v) { return v != kChunkDistanceCap; });
    }
    if (!near) return;
    for (std::size_t b = 0; b < lines; ++b) {
      transformLine(static_cast<int>(length), &scratch.in[b], &scratch.out[b], kBatch, scratch.s.data(),
                    scratch.t.data());
    }
    for (std::size_t k = 0; k < length; ++k)
      std::copy_n(&scratch.out[k * kBatch], lines, base + k * lineStride);
  };
  // along y: one z layer per task
  parallelFor(nz, threads, [&](std::size_t z) {
    Scratch scratch(dims.y);
    for (std::size_t x0 = 0; x0 < nx; x0 += kBatch) {
      batch(&field[z * nx * ny + x0], std::min<std::size_t>(kBatch, nx - x0), ny, nx, scratch);
    }
  });
  // along z: the x–y plane as lines, kBatch of them per task
  const std::size_t planeLines = nx * ny;
  parallelFor((planeLines + kBatch - 1) / kBatch, threads, [&](std::size_t task) {
    Scratch scratch(dims.z);
    const std::size_t first = task * kBatch;
    batch(&field[first], std::min<std::size_t>(kBatch, planeLines - first), nz, planeLines, scratch);
  });
}

}  // namespace voxhap

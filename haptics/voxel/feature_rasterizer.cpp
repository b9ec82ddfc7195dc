#include "haptics/voxel/feature_rasterizer.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "haptics/core/parallel.h"
#include "haptics/voxel/box_overlap.h"

namespace voxhap {
namespace {

/// Voxel boxes are grown by this fraction of a voxel on every side, so that a face or
/// an edge lying exactly on a voxel boundary marks the voxels on both sides whatever the
/// rounding of the boundary's coordinate (the boxes are closed).
constexpr double kTouchFraction = 1e-9;

enum class ItemKind : std::uint8_t { Triangle, Edge, Vertex };

/// One thing to rasterize, binned to a hyperchunk.
struct Item {
  std::uint32_t hyper;
  ItemKind kind;
  std::uint32_t part;
  std::uint32_t index;
};

/// Inclusive voxel box.
struct VoxelBox {
  glm::ivec3 lo;
  glm::ivec3 hi;
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
};

VoxelBox intersect(const VoxelBox& a, const VoxelBox& b) {
  return {glm::max(a.lo, b.lo), glm::min(a.hi, b.hi)};
}

class Rasterizer {
public:
  Rasterizer(const VoxelGrid& grid, HyperchunkBlocks<std::uint8_t>& out) : grid_(grid), out_(out) {}

  /// The voxels that may touch the box [lo, hi] (grown by kTouchFraction of a voxel).
  VoxelBox boxOf(const glm::dvec3& lo, const glm::dvec3& hi) const {
    const glm::ivec3 last = grid_.dimsVoxels() - 1;
    const double eps = kTouchFraction * grid_.voxelSizeM;
    return {glm::clamp(grid_.voxelOf(lo - eps), glm::ivec3(0), last),
            glm::clamp(grid_.voxelOf(hi + eps), glm::ivec3(0), last)};
  }

  void mark(const glm::ivec3& v, std::uint8_t bits) {
    out_.findOrCreate(v >> kChunkEdgeLog2, 0)[voxelInChunk(v)] |= bits;
  }

  /// Marks the voxels of `region` that the triangle overlaps, scanning columns along
  /// the axis closest to its normal and, per column, only the few voxels its plane crosses.
  void triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const VoxelBox& region) {
    const VoxelBox box = intersect(region, boxOf(glm::min(a, glm::min(b, c)), glm::max(a, glm::max(b, c))));
    if (box.empty()) return;
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const glm::dvec3 an = glm::abs(n);
    const int w = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
    const int u = (w + 1) % 3;
    const int v = (w + 2) % 3;
    const double s = grid_.voxelSizeM;
    const glm::dvec3 half(0.5 * s * (1.0 + kTouchFraction));
    const glm::dvec3 pts[3] = {a, b, c};
    for (int iu = box.lo[u]; iu <= box.hi[u]; ++iu) {
      const double u0 = grid_.originLocal[u] + (iu - kTouchFraction) * s;
      const double u1 = u0 + (1.0 + 2.0 * kTouchFraction) * s;
      // the projected triangle's extent along v within this slab of u
      double vMin = 1e300;
      double vMax = -1e300;
      for (int e = 0; e < 3; ++e) {
        const glm::dvec3& p = pts[e];
        const glm::dvec3& q = pts[(e + 1) % 3];
        double t0 = 0.0;
        double t1 = 1.0;
        const double du = q[u] - p[u];
        if (du == 0.0) {
          if (p[u] < u0 || p[u] > u1) continue;
        } else {
          double ta = (u0 - p[u]) / du;
          double tb = (u1 - p[u]) / du;
          if (ta > tb) std::swap(ta, tb);
          t0 = std::max(t0, ta);
          t1 = std::min(t1, tb);
          if (t0 > t1) continue;
        }
        const double va = p[v] + t0 * (q[v] - p[v]);
        const double vb = p[v] + t1 * (q[v] - p[v]);
        vMin = std::min({vMin, va, vb});
        vMax = std::max({vMax, va, vb});
      }
      if (vMin > vMax) continue;
      const int ivLo = std::max(
          box.lo[v], static_cast<int>(std::floor((vMin - grid_.originLocal[v]) / s - kTouchFraction)));
      const int ivHi = std::min(
          box.hi[v], static_cast<int>(std::floor((vMax - grid_.originLocal[v]) / s + kTouchFraction)));
      for (int iv = ivLo; iv <= ivHi; ++iv) {
        const double v0 = grid_.originLocal[v] + iv * s;
        // the plane's range along w over this column's footprint
        double wMin = box.hi[w] + 1.0;
        double wMax = box.lo[w] - 1.0;
        if (an[w] > 0.0) {
          const double d = glm::dot(n, a);
          wMin = 1e300;
          wMax = -1e300;
          for (int corner = 0; corner < 4; ++corner) {
            const double pu = u0 + (corner & 1) * s;
            const double pv = v0 + ((corner >> 1) & 1) * s;
            const double pw = (d - n[u] * pu - n[v] * pv) / n[w];
            wMin = std::min(wMin, pw);
            wMax = std::max(wMax, pw);
          }
          wMin = (wMin - grid_.originLocal[w]) / s - 2.0 * kTouchFraction;
          wMax = (wMax - grid_.originLocal[w]) / s + 2.0 * kTouchFraction;
        } else {
          wMin = box.lo[w];
          wMax = box.hi[w];
        }
        const int iwLo = std::max(box.lo[w], static_cast<int>(std::floor(wMin)));
        const int iwHi = std::min(box.hi[w], static_cast<int>(std::floor(wMax)));
        for (int iw = iwLo; iw <= iwHi; ++iw) {
          glm::ivec3 voxel;
          voxel[u] = iu;
          voxel[v] = iv;
          voxel[w] = iw;
          if (triangleOverlapsBox(a, b, c, grid_.voxelCentre(voxel), half)) mark(voxel, kSurfaceBit);
        }
      }
    }
  }

  /// Marks the voxels of `region` that the segment overlaps, slab by slab along its
  /// longest axis.
  void segment(const glm::dvec3& a, const glm::dvec3& b, const VoxelBox& region) {
    const VoxelBox box = intersect(region, boxOf(glm::min(a, b), glm::max(a, b)));
    if (box.empty()) return;
    const glm::dvec3 d = b - a;
    const glm::dvec3 ad = glm::abs(d);
    const int w = ad.x >= ad.y && ad.x >= ad.z ? 0 : (ad.y >= ad.z ? 1 : 2);
    const double s = grid_.voxelSizeM;
    const glm::dvec3 half(0.5 * s * (1.0 + kTouchFraction));
    for (int iw = box.lo[w]; iw <= box.hi[w]; ++iw) {
      VoxelBox slab = box;
      if (ad[w] > 0.0) {
        const double w0 = grid_.originLocal[w] + iw * s;
        const double t0 = std::clamp((w0 - a[w]) / d[w], 0.0, 1.0);
        const double t1 = std::clamp((w0 + s - a[w]) / d[w], 0.0, 1.0);
        const glm::dvec3 p = a + std::min(t0, t1) * d;
        const glm::dvec3 q = a + std::max(t0, t1) * d;
        slab = intersect(box, boxOf(glm::min(p, q) - 1e-9 * s, glm::max(p, q) + 1e-9 * s));
      }
      slab.lo[w] = slab.hi[w] = iw;
      for (int z = slab.lo.z; z <= slab.hi.z; ++z) {
        for (int y = slab.lo.y; y <= slab.hi.y; ++y) {
          for (int x = slab.lo.x; x <= slab.hi.x; ++x) {
            const glm::ivec3 voxel(x, y, z);
            if (segmentOverlapsBox(a, b, grid_.voxelCentre(voxel), half)) mark(voxel, kEdgeBit);
          }
        }
      }
    }
  }

  void vertex(const glm::dvec3& p, const VoxelBox& region) {
    const glm::ivec3 voxel = grid_.voxelOf(p);
    if (glm::all(glm::greaterThanEqual(voxel, region.lo)) && glm::all(glm::lessThanEqual(voxel, region.hi))) {
      mark(voxel, kVertexBit);
    }
  }

private:
  const VoxelGrid& grid_;
  HyperchunkBlocks<std::uint8_t>& out_;
};

}  // namespace

HyperchunkBlocks<std::uint8_t> rasterizeFeatures(const VoxelGrid& grid,
                                                 std::span<const FeatureGeometry> parts, int threads,
                                                 const ProgressFn& progress) {
  HyperchunkBlocks<std::uint8_t> out(grid.dimsHyper);
  Rasterizer rasterizer(grid, out);

  // bin every triangle, feature edge and feature vertex to the hyperchunks its box meets
  std::vector<Item> items;
  auto bin = [&](const glm::dvec3& lo, const glm::dvec3& hi, ItemKind kind, std::size_t part,
                 std::size_t index) {
    const VoxelBox box = rasterizer.boxOf(lo, hi);
    const glm::ivec3 hLo = box.lo >> (kChunkEdgeLog2 + kHyperEdgeLog2);
    const glm::ivec3 hHi = box.hi >> (kChunkEdgeLog2 + kHyperEdgeLog2);
    for (int z = hLo.z; z <= hHi.z; ++z) {
      for (int y = hLo.y; y <= hHi.y; ++y) {
        for (int x = hLo.x; x <= hHi.x; ++x) {
          items.push_back({static_cast<std::uint32_t>(out.hyperIndex({x, y, z})), kind,
                           static_cast<std::uint32_t>(part), static_cast<std::uint32_t>(index)});
        }
      }
    }
  };
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const TriangleMesh& mesh = *parts[p].mesh;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const glm::uvec3& tri = mesh.triangles[t];
      const glm::dvec3 a(mesh.positionsWorld[tri.x]);
      const glm::dvec3 b(mesh.positionsWorld[tri.y]);
      const glm::dvec3 c(mesh.positionsWorld[tri.z]);
      bin(glm::min(a, glm::min(b, c)), glm::max(a, glm::max(b, c)), ItemKind::Triangle, p, t);
    }
    if (!parts[p].features) continue;
    const MeshFeatures& features = *parts[p].features;
    for (std::size_t e = 0; e < features.featureEdges.size(); ++e) {
      const glm::dvec3 a(features.featureEdges[e][0]);
      const glm::dvec3 b(features.featureEdges[e][1]);
      bin(glm::min(a, b), glm::max(a, b), ItemKind::Edge, p, e);
    }
    for (std::size_t v = 0; v < features.featureVertices.size(); ++v) {
      const glm::dvec3 a(features.featureVertices[v]);
      bin(a, a, ItemKind::Vertex, p, v);
    }
  }
  std::stable_sort(items.begin(), items.end(),
                   [](const Item& x, const Item& y) { return x.hyper < y.hyper; });
  std::vector<std::size_t> begins;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i == 0 || items[i].hyper != items[i - 1].hyper) begins.push_back(i);
  }
  begins.push_back(items.size());

  parallelFor(
      begins.size() - 1, threads,
      [&](std::size_t g) {
        const std::uint32_t h = items[begins[g]].hyper;
        const glm::ivec3 dims = grid.dimsHyper;
        const glm::ivec3 ijkHyper(
            static_cast<int>(h % static_cast<std::uint32_t>(dims.x)),
            static_cast<int>((h / static_cast<std::uint32_t>(dims.x)) % static_cast<std::uint32_t>(dims.y)),
            static_cast<int>(h / static_cast<std::uint32_t>(dims.x * dims.y)));
        const VoxelBox region{ijkHyper * kHyperEdgeVoxels,
                              ijkHyper * kHyperEdgeVoxels + (kHyperEdgeVoxels - 1)};
        for (std::size_t i = begins[g]; i < begins[g + 1]; ++i) {
          const Item& item = items[i];
          if (item.kind == ItemKind::Triangle) {
            const TriangleMesh& mesh = *parts[item.part].mesh;
            const glm::uvec3& tri = mesh.triangles[item.index];
            rasterizer.triangle(glm::dvec3(mesh.positionsWorld[tri.x]),
                                glm::dvec3(mesh.positionsWorld[tri.y]),
                                glm::dvec3(mesh.positionsWorld[tri.z]), region);
          } else if (item.kind == ItemKind::Edge) {
            const auto& edge = parts[item.part].features->featureEdges[item.index];
            rasterizer.segment(glm::dvec3(edge[0]), glm::dvec3(edge[1]), region);
          } else {
            rasterizer.vertex(glm::dvec3(parts[item.part].features->featureVertices[item.index]), region);
          }
        }
      },
      progress);
  return out;
}

}  // namespace voxhap

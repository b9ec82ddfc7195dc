#include "haptics/geometry/mesh_topology.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <numeric>
#include <tuple>

#include <glm/geometric.hpp>

namespace voxhap {
namespace {

std::uint32_t positionKey(float v) {
  return std::bit_cast<std::uint32_t>(v == 0.0f ? 0.0f : v);  // -0 welds to +0
}

/// For each vertex, the index of the first vertex with the same position.
std::vector<std::uint32_t> weldByPosition(const std::vector<glm::vec3>& positions) {
  std::vector<std::uint32_t> order(positions.size());
  std::iota(order.begin(), order.end(), 0u);
  auto key = [&](std::uint32_t i) {
    const glm::vec3& p = positions[i];
    return std::tuple(positionKey(p.x), positionKey(p.y), positionKey(p.z));
  };
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const auto ka = key(a);
    const auto kb = key(b);
    return ka != kb ? ka < kb : a < b;
  });
  std::vector<std::uint32_t> canonical(positions.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    const bool sameAsPrevious = i > 0 && key(order[i]) == key(order[i - 1]);
    canonical[order[i]] = sameAsPrevious ? canonical[order[i - 1]] : order[i];
  }
  return canonical;
}

/// A directed edge packed for sorting: undirected key in the high bits, direction last.
struct DirectedEdge {
  std::uint32_t low;
  std::uint32_t high;
  bool forward;  // walked from low to high
};

}  // namespace

MeshTopology computeTopology(const TriangleMesh& mesh) {
  const std::vector<std::uint32_t> canonical = weldByPosition(mesh.positionsWorld);
  std::vector<DirectedEdge> edges;
  edges.reserve(mesh.triangles.size() * 3);
  for (const glm::uvec3& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = canonical[t[k]];
      const std::uint32_t b = canonical[t[(k + 1) % 3]];
      if (a == b) continue;  // collapsed edge of a degenerate triangle
      edges.push_back({std::min(a, b), std::max(a, b), a < b});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const DirectedEdge& x, const DirectedEdge& y) {
    return std::tie(x.low, x.high, x.forward) < std::tie(y.low, y.high, y.forward);
  });

  MeshTopology topology;
  for (std::size_t begin = 0; begin < edges.size();) {
    std::size_t end = begin + 1;
    while (end < edges.size() && edges[end].low == edges[begin].low && edges[end].high == edges[begin].high) {
      ++end;
    }
    const std::size_t uses = end - begin;
    if (uses == 2) {
      if (edges[begin].forward == edges[begin + 1].forward) ++topology.misorientedEdges;
    } else {
      ++(uses == 1 ? topology.boundaryEdges : topology.nonManifoldEdges);
      if (!topology.firstOpenEdgeWorld) {
        topology.firstOpenEdgeWorld =
            0.5f * (mesh.positionsWorld[edges[begin].low] + mesh.positionsWorld[edges[begin].high]);
      }
    }
    begin = end;
  }
  return topology;
}

double signedVolume(const TriangleMesh& mesh) {
  double sixTimesVolume = 0.0;
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 a(mesh.positionsWorld[t.x]);
    const glm::dvec3 b(mesh.positionsWorld[t.y]);
    const glm::dvec3 c(mesh.positionsWorld[t.z]);
    sixTimesVolume += glm::dot(a, glm::cross(b, c));
  }
  return sixTimesVolume / 6.0;
}

}  // namespace voxhap

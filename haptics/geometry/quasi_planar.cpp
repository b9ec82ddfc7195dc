#include "haptics/geometry/quasi_planar.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <glm/geometric.hpp>

namespace voxhap {
namespace {

using HalfEdgeMesh = OpenMesh::TriMesh_ArrayKernelT<>;

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

/// Two unit normals are "less than 90° apart" when their dot product exceeds this:
/// strictly below 90° with a margin (≈ 0.006°) for the rounding of float vertices, so
/// that the faces of a right-angled corner never merge, however it is rotated.
constexpr double kMinNormalDot = 1e-4;

std::uint32_t positionKey(float v) {
  return std::bit_cast<std::uint32_t>(v == 0.0f ? 0.0f : v);  // -0 welds to +0
}

/// Welded vertex id of every input vertex: vertices with bit-identical positions share
/// one id; ids are dense and numbered in order of first appearance.
std::vector<std::uint32_t> weldByPosition(const std::vector<glm::vec3>& positions,
                                          std::uint32_t& weldedCount) {
  struct Keyed {
    std::uint32_t x, y, z, index;
  };
  std::vector<Keyed> keyed(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const glm::vec3& p = positions[i];
    keyed[i] = {positionKey(p.x), positionKey(p.y), positionKey(p.z), static_cast<std::uint32_t>(i)};
  }
  const auto sameKey = [](const Keyed& a, const Keyed& b) { return a.x == b.x && a.y == b.y && a.z == b.z; };
  std::sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    if (a.z != b.z) return a.z < b.z;
    return a.index < b.index;
  });
  // first[i]: the lowest input index with the same position as vertex i
  std::vector<std::uint32_t> first(positions.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    const bool sameAsPrevious = i > 0 && sameKey(keyed[i], keyed[i - 1]);
    first[keyed[i].index] = sameAsPrevious ? first[keyed[i - 1].index] : keyed[i].index;
  }
  std::vector<std::uint32_t> welded(positions.size());
  weldedCount = 0;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    welded[i] = first[i] == i ? weldedCount++ : welded[first[i]];
  }
  return welded;
}

/// Whether `add_face` would accept the triangle: the same read-only tests as OpenMesh's
/// PolyConnectivity::add_face (complex vertex, complex edge, patch re-linking), made
/// beforehand because add_face reports a refusal on std::cerr and the engine never prints.
bool acceptsTriangle(const HalfEdgeMesh& m, const std::array<OpenMesh::VertexHandle, 3>& v) {
  std::array<OpenMesh::HalfedgeHandle, 3> inner;
  for (std::size_t i = 0; i < 3; ++i) {
    if (!m.is_boundary(v[i])) return false;  // the vertex's fan is closed
    inner[i] = m.find_halfedge(v[i], v[(i + 1) % 3]);
    if (inner[i].is_valid() && !m.is_boundary(inner[i])) return false;  // the edge is taken this way
  }
  for (std::size_t i = 0; i < 3; ++i) {
    const OpenMesh::HalfedgeHandle prev = inner[i];
    const OpenMesh::HalfedgeHandle next = inner[(i + 1) % 3];
    if (!prev.is_valid() || !next.is_valid() || m.next_halfedge_handle(prev) == next) continue;
    // add_face would move the fans between them elsewhere: it needs another gap at the vertex
    OpenMesh::HalfedgeHandle gap = m.opposite_halfedge_handle(next);
    do {
      gap = m.opposite_halfedge_handle(m.next_halfedge_handle(gap));
    } while (!m.is_boundary(gap));
    if (gap == prev) return false;
  }
  return true;
}

/// Unit normal of triangle abc (counter-clockwise), or zero when it has no area.
glm::dvec3 unitNormal(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double length = glm::length(n);
  return length > 0.0 ? n / length : glm::dvec3(0.0);
}

/// Less than 90° apart; a zero normal (no area, no orientation) contradicts nothing.
bool withinRightAngle(const glm::dvec3& a, const glm::dvec3& b) {
  return glm::dot(a, b) > kMinNormalDot || a == glm::dvec3(0.0) || b == glm::dvec3(0.0);
}

/// Per welded vertex: whether it touches three or more polygons (two are remembered).
class PolygonsAtVertex {
public:
  explicit PolygonsAtVertex(std::size_t vertexCount)
      : seen_(vertexCount, {kNone, kNone}), many_(vertexCount, 0) {}

  void add(std::uint32_t vertex, std::uint32_t polygon) {
    std::array<std::uint32_t, 2>& seen = seen_[vertex];
    if (seen[0] == polygon || seen[1] == polygon || many_[vertex]) return;
    if (seen[0] == kNone) {
      seen[0] = polygon;
    } else if (seen[1] == kNone) {
      seen[1] = polygon;
    } else {
      many_[vertex] = 1;
    }
  }
  bool threeOrMore(std::uint32_t vertex) const { return many_[vertex] != 0; }

private:
  std::vector<std::array<std::uint32_t, 2>> seen_;
  std::vector<std::uint8_t> many_;
};

}  // namespace

MeshFeatures extractFeatures(const TriangleMesh& mesh, double voxelSizeM) {
  assert(voxelSizeM > 0.0);
  const std::size_t triangleCount = mesh.triangles.size();
  assert(triangleCount < kNone && mesh.positionsWorld.size() < kNone);

  std::uint32_t vertexCount = 0;
  const std::vector<std::uint32_t> welded = weldByPosition(mesh.positionsWorld, vertexCount);
  std::vector<glm::dvec3> position(vertexCount);
  for (std::size_t i = 0; i < welded.size(); ++i) position[welded[i]] = glm::dvec3(mesh.positionsWorld[i]);

  // the half-edge mesh: OpenMesh vertex i is welded vertex i; faces in triangle order
  HalfEdgeMesh halfEdges;
  halfEdges.reserve(vertexCount, triangleCount * 3 / 2 + 3, triangleCount);
  for (const glm::dvec3& p : position) {
    halfEdges.add_vertex(
        HalfEdgeMesh::Point(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)));
  }
  std::vector<std::uint32_t> triangleOfFace;
  triangleOfFace.reserve(triangleCount);
  std::vector<std::uint8_t> inHalfEdgeMesh(triangleCount, 0);
  std::vector<std::uint32_t> refused;  // triangles with three distinct vertices OpenMesh cannot hold
  std::vector<glm::dvec3> normal(triangleCount, glm::dvec3(0.0));
  for (std::size_t t = 0; t < triangleCount; ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    const std::array<std::uint32_t, 3> w = {welded[tri.x], welded[tri.y], welded[tri.z]};
    if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0]) continue;  // collapsed by welding: no area, no edge
    normal[t] = unitNormal(position[w[0]], position[w[1]], position[w[2]]);
    const std::array<OpenMesh::VertexHandle, 3> v = {OpenMesh::VertexHandle(static_cast<int>(w[0])),
                                                     OpenMesh::VertexHandle(static_cast<int>(w[1])),
                                                     OpenMesh::VertexHandle(static_cast<int>(w[2]))};
    if (acceptsTriangle(halfEdges, v) && halfEdges.add_face(v[0], v[1], v[2]).is_valid()) {
      triangleOfFace.push_back(static_cast<std::uint32_t>(t));
      inHalfEdgeMesh[t] = 1;
    } else {
      refused.push_back(static_cast<std::uint32_t>(t));
    }
  }

  MeshFeatures features;
  features.refusedTriangles = refused.size();
  std::vector<std::uint32_t>& polygonOf = features.polygonOfTriangle;
  polygonOf.assign(triangleCount, kNone);
  const auto faceTriangle = [&](OpenMesh::FaceHandle f) {
    return triangleOfFace[static_cast<std::size_t>(f.idx())];
  };

  // Grow polygons breadth-first from the lowest unassigned triangle. The polygon's plane
  // is its seed triangle's plane, fixed while it grows: every vertex that enters is
  // tested against that one plane, so the whole polygon lies within ±s/2 of it, and a
  // curved surface stops growing where its sagitta over the polygon reaches s/2 however
  // finely it is tessellated (a running plane through the polygon would turn with the
  // curvature and let a fine cylinder creep round step by step). A flat face is exactly
  // on its seed's plane and becomes one polygon. Triangles without area have no plane
  // and only join polygons seeded elsewhere (second pass: whatever is left alone).
  const double halfVoxelM = 0.5 * voxelSizeM;
  std::vector<OpenMesh::FaceHandle> queue;
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t seed = 0; seed < triangleCount; ++seed) {
      if (polygonOf[seed] != kNone) continue;
      const std::uint32_t polygon = features.polygonCount;
      if (!inHalfEdgeMesh[seed] || pass == 1) {
        polygonOf[seed] = features.polygonCount++;  // refused, collapsed or without area: alone
        continue;
      }
      const glm::dvec3& planeNormal = normal[seed];
      if (planeNormal == glm::dvec3(0.0)) continue;
      ++features.polygonCount;
      const double planeOffsetM = glm::dot(planeNormal, position[welded[mesh.triangles[seed].x]]);
      polygonOf[seed] = polygon;
      queue.clear();
      const auto seedFace = std::lower_bound(triangleOfFace.begin(), triangleOfFace.end(), seed);
      queue.emplace_back(static_cast<int>(seedFace - triangleOfFace.begin()));
      for (std::size_t head = 0; head < queue.size(); ++head) {
        const OpenMesh::FaceHandle face = queue[head];
        const glm::dvec3& faceNormal = normal[faceTriangle(face)];
        OpenMesh::HalfedgeHandle h = halfEdges.halfedge_handle(face);
        for (int k = 0; k < 3; ++k, h = halfEdges.next_halfedge_handle(h)) {
          const OpenMesh::HalfedgeHandle across = halfEdges.opposite_halfedge_handle(h);
          const OpenMesh::FaceHandle neighbour = halfEdges.face_handle(across);
          if (!neighbour.is_valid()) continue;
          const std::uint32_t t = faceTriangle(neighbour);
          if (polygonOf[t] != kNone) continue;
          const auto farVertex = static_cast<std::size_t>(
              halfEdges.to_vertex_handle(halfEdges.next_halfedge_handle(across)).idx());
          if (std::abs(glm::dot(planeNormal, position[farVertex]) - planeOffsetM) >= halfVoxelM) continue;
          if (!withinRightAngle(normal[t], faceNormal) || !withinRightAngle(normal[t], planeNormal)) continue;
          polygonOf[t] = polygon;
          queue.push_back(neighbour);
        }
      }
    }
  }

  // feature edges: OpenMesh edges between polygons or on the boundary, then edges that
  // only refused triangles have; marks avoid listing an edge twice
  std::vector<std::uint8_t> featureEdgeMark(halfEdges.n_edges(), 0);
  for (const auto e : halfEdges.edges()) {
    const OpenMesh::FaceHandle f0 = halfEdges.face_handle(halfEdges.halfedge_handle(e, 0));
    const OpenMesh::FaceHandle f1 = halfEdges.face_handle(halfEdges.halfedge_handle(e, 1));
    if (!f0.is_valid() || !f1.is_valid() || polygonOf[faceTriangle(f0)] != polygonOf[faceTriangle(f1)]) {
      featureEdgeMark[static_cast<std::size_t>(e.idx())] = 1;
    }
  }
  std::vector<std::array<std::uint32_t, 2>> refusedOnlyEdges;
  for (const std::uint32_t t : refused) {
    const glm::uvec3& tri = mesh.triangles[t];
    const std::array<std::uint32_t, 3> w = {welded[tri.x], welded[tri.y], welded[tri.z]};
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = std::min(w[k], w[(k + 1) % 3]);
      const std::uint32_t b = std::max(w[k], w[(k + 1) % 3]);
      const OpenMesh::HalfedgeHandle h = halfEdges.find_halfedge(OpenMesh::VertexHandle(static_cast<int>(a)),
                                                                 OpenMesh::VertexHandle(static_cast<int>(b)));
      if (h.is_valid()) {
        featureEdgeMark[static_cast<std::size_t>(halfEdges.edge_handle(h).idx())] = 1;
      } else {
        refusedOnlyEdges.push_back({a, b});
      }
    }
  }
  std::sort(refusedOnlyEdges.begin(), refusedOnlyEdges.end());
  refusedOnlyEdges.erase(std::unique(refusedOnlyEdges.begin(), refusedOnlyEdges.end()),
                         refusedOnlyEdges.end());

  // per vertex: how many feature edges, and the far ends of the first two
  std::vector<std::uint32_t> featureEdgesAt(vertexCount, 0);
  std::vector<std::array<std::uint32_t, 2>> firstFarEnds(vertexCount, {kNone, kNone});
  const auto emitEdge = [&](std::uint32_t a, std::uint32_t b) {
    features.featureEdges.push_back({glm::vec3(position[a]), glm::vec3(position[b])});
    for (const auto [at, other] : {std::array{a, b}, std::array{b, a}}) {
      if (featureEdgesAt[at] < 2) firstFarEnds[at][featureEdgesAt[at]] = other;
      ++featureEdgesAt[at];
    }
  };
  for (const auto e : halfEdges.edges()) {
    if (!featureEdgeMark[static_cast<std::size_t>(e.idx())]) continue;
    const OpenMesh::HalfedgeHandle h = halfEdges.halfedge_handle(e, 0);
    emitEdge(static_cast<std::uint32_t>(halfEdges.from_vertex_handle(h).idx()),
             static_cast<std::uint32_t>(halfEdges.to_vertex_handle(h).idx()));
  }
  for (const auto& [a, b] : refusedOnlyEdges) emitEdge(a, b);

  // feature vertices: corners of the polygons
  PolygonsAtVertex polygonsAt(vertexCount);
  for (std::size_t t = 0; t < triangleCount; ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    const std::array<std::uint32_t, 3> w = {welded[tri.x], welded[tri.y], welded[tri.z]};
    if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0]) continue;
    for (const std::uint32_t v : w) polygonsAt.add(v, polygonOf[t]);
  }
  const double cornerMaxCos = std::cos(kFeatureCornerMaxAngleDeg * std::numbers::pi / 180.0);
  for (std::uint32_t v = 0; v < vertexCount; ++v) {
    bool corner = polygonsAt.threeOrMore(v) || (featureEdgesAt[v] != 0 && featureEdgesAt[v] != 2);
    if (!corner && featureEdgesAt[v] == 2) {
      const glm::dvec3 toA = glm::normalize(position[firstFarEnds[v][0]] - position[v]);
      const glm::dvec3 toB = glm::normalize(position[firstFarEnds[v][1]] - position[v]);
      corner = glm::dot(toA, toB) > cornerMaxCos;
    }
    if (corner) features.featureVertices.emplace_back(position[v]);
  }
  return features;
}

}  // namespace voxhap

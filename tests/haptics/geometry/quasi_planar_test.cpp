#include "haptics/geometry/quasi_planar.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "haptics/geometry/mesh_builder.h"
#include "haptics/geometry/mesh_topology.h"

namespace voxhap {
namespace {

/// Unit cube [0, 1]³ with outward, counter-clockwise triangles and shared vertices.
TriangleMesh cube() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) m.positionsWorld.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

/// Unit cube [0, 1]³ whose faces are n × n grids of quads (2n² triangles each), every
/// face with its own vertices (as an exporter writes them); positions come from an
/// integer lattice, so vertices on a cube edge are bit-identical on both faces.
TriangleMesh subdividedCube(int n) {
  struct Face {
    glm::ivec3 origin, u, v;  // u × v points outward
  };
  const Face faces[] = {{{0, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {{n, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                        {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, {{0, n, 0}, {0, 0, 1}, {1, 0, 0}},
                        {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}, {{0, 0, n}, {1, 0, 0}, {0, 1, 0}}};
  TriangleMesh m;
  for (const Face& f : faces) {
    const auto base = static_cast<unsigned>(m.positionsWorld.size());
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const glm::ivec3 lattice = f.origin + i * f.u + j * f.v;
        m.positionsWorld.push_back(glm::vec3(lattice) / static_cast<float>(n));
      }
    }
    const auto at = [&](int i, int j) { return base + static_cast<unsigned>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
        m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      }
    }
  }
  return m;
}

/// Every triangle with its own three vertices.
TriangleMesh splitVertices(const TriangleMesh& shared) {
  TriangleMesh split;
  for (const glm::uvec3& t : shared.triangles) {
    const auto base = static_cast<unsigned>(split.positionsWorld.size());
    for (int k = 0; k < 3; ++k) split.positionsWorld.push_back(shared.positionsWorld[t[k]]);
    split.triangles.emplace_back(base, base + 1, base + 2);
  }
  return split;
}

double totalEdgeLength(const MeshFeatures& f) {
  double length = 0.0;
  for (const auto& e : f.featureEdges) length += glm::distance(glm::dvec3(e[0]), glm::dvec3(e[1]));
  return length;
}

bool hasEdge(const MeshFeatures& f, const glm::vec3& a, const glm::vec3& b) {
  return std::any_of(f.featureEdges.begin(), f.featureEdges.end(),
                     [&](const auto& e) { return (e[0] == a && e[1] == b) || (e[0] == b && e[1] == a); });
}

/// Whether each coordinate of `p` is 0 or 1.
bool isUnitCubeCorner(const glm::vec3& p) {
  for (int k = 0; k < 3; ++k) {
    if (p[k] != 0.0f && p[k] != 1.0f) return false;
  }
  return true;
}

/// Number of coordinates of `p` that are 0 or 1 (3: corner, 2: on an edge).
int coordinatesOnCubeFaces(const glm::vec3& p) {
  int count = 0;
  for (int k = 0; k < 3; ++k) count += p[k] == 0.0f || p[k] == 1.0f;
  return count;
}

/// Distinct polygon ids of `triangles`.
std::set<std::uint32_t> polygonsOf(const MeshFeatures& f, const std::vector<std::size_t>& triangles) {
  std::set<std::uint32_t> ids;
  for (const std::size_t t : triangles) ids.insert(f.polygonOfTriangle[t]);
  return ids;
}

/// Runs `extractFeatures` and fails the test if anything was written to stderr.
MeshFeatures extractSilently(const TriangleMesh& mesh, double voxelSizeM) {
  testing::internal::CaptureStderr();
  MeshFeatures f = extractFeatures(mesh, voxelSizeM);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  return f;
}

TEST(QuasiPlanar, CubeHasSixPolygonsTwelveEdgesEightVertices) {
  const MeshFeatures f = extractFeatures(cube(), 0.01);
  EXPECT_EQ(f.polygonCount, 6u);
  ASSERT_EQ(f.polygonOfTriangle.size(), 12u);
  for (std::size_t face = 0; face < 6; ++face) {
    EXPECT_EQ(f.polygonOfTriangle[2 * face], f.polygonOfTriangle[2 * face + 1]) << face;
  }
  ASSERT_EQ(f.featureEdges.size(), 12u);
  for (const auto& e : f.featureEdges) {
    EXPECT_FLOAT_EQ(glm::distance(e[0], e[1]), 1.0f);  // cube edges, never face diagonals
  }
  ASSERT_EQ(f.featureVertices.size(), 8u);
  for (const glm::vec3& v : f.featureVertices) EXPECT_TRUE(isUnitCubeCorner(v));
  EXPECT_EQ(f.refusedTriangles, 0u);
}

TEST(QuasiPlanar, RotatedCubeFacesNeverMergeAtAnyVoxelSize) {
  TriangleMesh m;
  const glm::dmat4 frame = glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(3.1, -2.7, 4.9)), 0.7,
                                       glm::normalize(glm::dvec3(1.0, 2.0, 3.0)));
  appendBox(m, frame, glm::dvec3(0.05, 0.02, 0.03));
  for (const double voxelSizeM : {1e-6, 1e-3, 0.1, 10.0, 1e6}) {
    const MeshFeatures f = extractFeatures(m, voxelSizeM);
    EXPECT_EQ(f.polygonCount, 6u) << voxelSizeM;
    EXPECT_EQ(f.featureEdges.size(), 12u) << voxelSizeM;
    EXPECT_EQ(f.featureVertices.size(), 8u) << voxelSizeM;
  }
}

TEST(QuasiPlanar, SubdividedCubeFacesMergeIntoSixPolygons) {
  const TriangleMesh m = subdividedCube(7);
  ASSERT_TRUE(computeTopology(m).closed());
  ASSERT_TRUE(computeTopology(m).consistentlyOriented());
  for (const double voxelSizeM : {1e-6, 1e-3, 0.3, 100.0}) {
    const MeshFeatures f = extractFeatures(m, voxelSizeM);
    EXPECT_EQ(f.polygonCount, 6u) << voxelSizeM;
    for (std::size_t face = 0; face < 6; ++face) {
      const std::size_t perFace = 2 * 7 * 7;
      std::vector<std::size_t> triangles(perFace);
      for (std::size_t t = 0; t < perFace; ++t) triangles[t] = face * perFace + t;
      EXPECT_EQ(polygonsOf(f, triangles).size(), 1u) << "face " << face << " voxel " << voxelSizeM;
    }
  }
}

TEST(QuasiPlanar, SubdividedCubeEdgesAddUpToTwelveMetresOfCubeEdges) {
  const int n = 7;
  for (const double voxelSizeM : {0.01, 100.0}) {
    const MeshFeatures f = extractFeatures(subdividedCube(n), voxelSizeM);
    EXPECT_EQ(f.featureEdges.size(), static_cast<std::size_t>(12 * n)) << voxelSizeM;
    EXPECT_NEAR(totalEdgeLength(f), 12.0, 1e-5) << voxelSizeM;
    for (const auto& e : f.featureEdges) {  // pieces of the cube's edges, never across a face
      EXPECT_GE(coordinatesOnCubeFaces(e[0]), 2);
      EXPECT_GE(coordinatesOnCubeFaces(e[1]), 2);
      EXPECT_NEAR(glm::distance(e[0], e[1]), 1.0f / n, 1e-6f);
    }
  }
}

TEST(QuasiPlanar, SubdividedCubeVerticesAreOnlyTheCornersNotWhereCollinearSegmentsMeet) {
  for (const double voxelSizeM : {0.01, 100.0}) {
    const MeshFeatures f = extractFeatures(subdividedCube(7), voxelSizeM);
    ASSERT_EQ(f.featureVertices.size(), 8u) << voxelSizeM;
    std::set<std::array<float, 3>> corners;
    for (const glm::vec3& v : f.featureVertices) {
      EXPECT_TRUE(isUnitCubeCorner(v)) << v.x << " " << v.y << " " << v.z;
      corners.insert({v.x, v.y, v.z});
    }
    EXPECT_EQ(corners.size(), 8u) << voxelSizeM;
  }
}

TEST(QuasiPlanar, SplitVerticesAreWeldedBeforeMerging) {
  const MeshFeatures f = extractSilently(splitVertices(cube()), 0.01);
  EXPECT_EQ(f.polygonCount, 6u);
  EXPECT_EQ(f.featureEdges.size(), 12u);
  EXPECT_EQ(f.featureVertices.size(), 8u);
  EXPECT_EQ(f.refusedTriangles, 0u);
}

/// Geodesic sphere of radius `radiusM` centred at the origin: 8·4^subdivisions triangles.
TriangleMesh sphere(double radiusM, int subdivisions) {
  TriangleMesh m;
  appendGeodesicSphere(m, glm::dmat4(1.0), radiusM, subdivisions);
  return m;
}

/// Ball of the ball-and-socket scene: radius 25 mm, 2048 triangles.
TriangleMesh ball() {
  return sphere(0.025, 4);
}

glm::dvec3 triangleNormal(const TriangleMesh& m, std::size_t t) {
  const glm::uvec3& tri = m.triangles[t];
  const glm::dvec3 a(m.positionsWorld[tri.x]), b(m.positionsWorld[tri.y]), c(m.positionsWorld[tri.z]);
  return glm::normalize(glm::cross(b - a, c - a));
}

/// Whether every triangle's normal is less than 90° from the normal of its polygon's
/// first triangle: no polygon turns through a right angle.
bool everyPolygonTurnsLessThanRightAngle(const TriangleMesh& m, const MeshFeatures& f) {
  std::vector<glm::dvec3> firstNormal(f.polygonCount, glm::dvec3(0.0));
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const glm::dvec3 n = triangleNormal(m, t);
    glm::dvec3& first = firstNormal[f.polygonOfTriangle[t]];
    if (first == glm::dvec3(0.0)) first = n;
    if (glm::dot(first, n) <= 0.0) return false;
  }
  return true;
}

TEST(QuasiPlanar, FineVoxelsKeepASphereInManyPolygons) {
  const MeshFeatures f = extractFeatures(ball(), 0.00035);
  // a polygon within ±s/2 of a plane lies in a slab of thickness s, which cuts an area of
  // 2πR·s from the sphere (Archimedes), so the sphere's 4πR² needs at least 2R/s ≈ 143
  EXPECT_GT(f.polygonCount, 128u);
  EXPECT_LT(f.polygonCount, 2048u);  // neighbours under the sagitta do merge
}

TEST(QuasiPlanar, EveryPolygonOfASphereFitsInASlabOneVoxelThick) {
  const TriangleMesh m = ball();
  for (const double voxelSizeM : {0.00035, 0.002, 0.01}) {
    const MeshFeatures f = extractFeatures(m, voxelSizeM);
    // slab along the normal of each polygon's first triangle
    std::vector<glm::dvec3> normal(f.polygonCount, glm::dvec3(0.0));
    std::vector<double> low(f.polygonCount, 1e300);
    std::vector<double> high(f.polygonCount, -1e300);
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      const std::uint32_t p = f.polygonOfTriangle[t];
      const glm::uvec3& tri = m.triangles[t];
      const glm::dvec3 a(m.positionsWorld[tri.x]), b(m.positionsWorld[tri.y]), c(m.positionsWorld[tri.z]);
      if (normal[p] == glm::dvec3(0.0)) normal[p] = glm::normalize(glm::cross(b - a, c - a));
      for (const glm::dvec3& q : {a, b, c}) {
        low[p] = std::min(low[p], glm::dot(normal[p], q));
        high[p] = std::max(high[p], glm::dot(normal[p], q));
      }
    }
    for (std::uint32_t p = 0; p < f.polygonCount; ++p) {
      EXPECT_LT(high[p] - low[p], voxelSizeM) << "polygon " << p << " voxel " << voxelSizeM;
    }
  }
}

TEST(QuasiPlanar, NoPolygonOfASphereTurnsThroughARightAngle) {
  const TriangleMesh m = ball();
  for (const double voxelSizeM : {0.00035, 0.002, 0.01, 1.0}) {
    const MeshFeatures f = extractFeatures(m, voxelSizeM);
    EXPECT_TRUE(everyPolygonTurnsLessThanRightAngle(m, f)) << voxelSizeM;
  }
}

TEST(QuasiPlanar, SphereSmallerThanAVoxelIsNeverOnePolygon) {
  // diameter 0.16 mm, under s/2: every vertex is within s/2 of every triangle's plane,
  // so only the 90° criterion keeps the sphere from becoming one polygon (paper §4.1)
  const TriangleMesh m = sphere(0.00008, 3);
  const MeshFeatures f = extractSilently(m, 0.00035);
  EXPECT_GE(f.polygonCount, 2u);
  EXPECT_TRUE(everyPolygonTurnsLessThanRightAngle(m, f));
  EXPECT_FALSE(f.featureEdges.empty());
}

TEST(QuasiPlanar, CoarseVoxelsMergeASphereIntoFewPolygonsButNeverOne) {
  const MeshFeatures f = extractFeatures(ball(), 0.050);
  EXPECT_GE(f.polygonCount, 2u);
  EXPECT_LE(f.polygonCount, 8u);
  // however large the voxel, no polygon turns through 90°
  for (const double voxelSizeM : {1.0, 1e6}) EXPECT_GE(extractFeatures(ball(), voxelSizeM).polygonCount, 2u);
}

/// Cylinder of radius 10 mm and length 30 mm, 64 segments, along a tilted axis.
struct Cylinder {
  static constexpr double kRadiusM = 0.010;
  static constexpr double kLengthM = 0.030;
  static constexpr int kSegments = 64;
  glm::dvec3 origin{0.4, -0.3, 1.2};
  glm::dvec3 axis = glm::normalize(glm::dvec3(0.3, 0.5, 1.0));
  TriangleMesh mesh;

  Cylinder() { appendCylinder(mesh, frameAlongAxis(origin, axis), kRadiusM, kLengthM, kSegments); }
  /// Position along the axis, m.
  double height(const glm::vec3& p) const { return glm::dot(glm::dvec3(p) - origin, axis); }
  bool onCap(const glm::vec3& p, double capHeightM) const { return std::abs(height(p) - capHeightM) < 1e-6; }
  /// Triangles with all three vertices on the cap at that height.
  std::vector<std::size_t> capTriangles(double capHeightM) const {
    std::vector<std::size_t> result;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const glm::uvec3& tri = mesh.triangles[t];
      if (onCap(mesh.positionsWorld[tri.x], capHeightM) && onCap(mesh.positionsWorld[tri.y], capHeightM) &&
          onCap(mesh.positionsWorld[tri.z], capHeightM)) {
        result.push_back(t);
      }
    }
    return result;
  }
};

TEST(QuasiPlanar, CylinderCapsAreOnePolygonEachAtAnyVoxelSize) {
  const Cylinder c;
  const std::vector<std::size_t> bottom = c.capTriangles(0.0);
  const std::vector<std::size_t> top = c.capTriangles(Cylinder::kLengthM);
  ASSERT_EQ(bottom.size(), static_cast<std::size_t>(Cylinder::kSegments));
  ASSERT_EQ(top.size(), static_cast<std::size_t>(Cylinder::kSegments));
  // down to 10 µm: finer than that, the float rounding of positions 1.3 m from the origin
  // (ulp ≈ 0.1 µm) tilts the thin fan triangles of a cap out of a slab of that thickness
  for (const double voxelSizeM : {1e-5, 1e-4, 0.001, 0.05, 10.0}) {
    const MeshFeatures f = extractFeatures(c.mesh, voxelSizeM);
    const std::set<std::uint32_t> bottomIds = polygonsOf(f, bottom);
    const std::set<std::uint32_t> topIds = polygonsOf(f, top);
    ASSERT_EQ(bottomIds.size(), 1u) << voxelSizeM;
    ASSERT_EQ(topIds.size(), 1u) << voxelSizeM;
    // and no side triangle is part of a cap
    std::size_t inCaps = 0;
    for (const std::uint32_t p : f.polygonOfTriangle)
      inCaps += p == *bottomIds.begin() || p == *topIds.begin();
    EXPECT_EQ(inCaps, 2u * Cylinder::kSegments) << voxelSizeM;
  }
}

TEST(QuasiPlanar, CylinderRimsAreFeatureEdgesAndCapCentresAreNotVertices) {
  const Cylinder c;
  const double perimeterM =
      2.0 * Cylinder::kSegments * Cylinder::kRadiusM * std::sin(std::numbers::pi / Cylinder::kSegments);
  for (const double voxelSizeM : {1e-4, 0.001, 0.05, 10.0}) {
    const MeshFeatures f = extractFeatures(c.mesh, voxelSizeM);
    double bottomM = 0.0;
    double topM = 0.0;
    for (const auto& e : f.featureEdges) {
      const double lengthM = glm::distance(glm::dvec3(e[0]), glm::dvec3(e[1]));
      if (c.onCap(e[0], 0.0) && c.onCap(e[1], 0.0)) bottomM += lengthM;
      if (c.onCap(e[0], Cylinder::kLengthM) && c.onCap(e[1], Cylinder::kLengthM)) topM += lengthM;
    }
    EXPECT_NEAR(bottomM, perimeterM, 1e-6) << voxelSizeM;
    EXPECT_NEAR(topM, perimeterM, 1e-6) << voxelSizeM;
    for (const glm::vec3& v : f.featureVertices) {
      const glm::dvec3 fromAxis = glm::dvec3(v) - c.origin - c.height(v) * c.axis;
      EXPECT_GT(glm::length(fromAxis), 0.5 * Cylinder::kRadiusM) << voxelSizeM;
    }
  }
}

TEST(QuasiPlanar, ThirdTriangleOnAnEdgeHasFeatureEdgesAndPrintsNothing) {
  TriangleMesh m = cube();
  m.positionsWorld.emplace_back(0.5f, 2.0f, 0.5f);
  m.triangles.emplace_back(2, 3, 8);  // a fin on the top edge 2-3
  const MeshFeatures f = extractSilently(m, 0.01);
  EXPECT_EQ(f.refusedTriangles, 1u);
  ASSERT_EQ(f.polygonOfTriangle.size(), 13u);
  EXPECT_EQ(f.polygonCount, 7u);
  const auto& p = m.positionsWorld;
  EXPECT_TRUE(hasEdge(f, p[2], p[3]));
  EXPECT_TRUE(hasEdge(f, p[3], p[8]));
  EXPECT_TRUE(hasEdge(f, p[8], p[2]));
  EXPECT_EQ(f.featureEdges.size(), 14u);  // the cube's 12 (2-3 once) and the fin's two others
}

TEST(QuasiPlanar, BoxesTouchingAtACornerDoNotCrashAndKeepTheirEdges) {
  TriangleMesh m;
  appendBox(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.5)), glm::dvec3(0.5));
  appendBox(m, glm::translate(glm::dmat4(1.0), glm::dvec3(1.5)), glm::dvec3(0.5));
  const MeshFeatures f = extractSilently(m, 0.01);
  EXPECT_GT(f.refusedTriangles, 0u);  // the second fan closing on (1, 1, 1)
  EXPECT_GE(f.featureEdges.size(), 24u);
  EXPECT_TRUE(std::count(f.featureVertices.begin(), f.featureVertices.end(), glm::vec3(1.0f)) == 1);
}

TEST(QuasiPlanar, HoleInAClosedMeshIsBoundedByFeatureEdges) {
  TriangleMesh m = cube();
  m.triangles.pop_back();  // {1, 7, 5} on the x = 1 face
  const MeshFeatures f = extractSilently(m, 0.01);
  const auto& p = m.positionsWorld;
  EXPECT_TRUE(hasEdge(f, p[1], p[7]));  // the diagonal, inside a face until the hole opened
  EXPECT_TRUE(hasEdge(f, p[7], p[5]));
  EXPECT_TRUE(hasEdge(f, p[5], p[1]));
  EXPECT_EQ(f.featureEdges.size(), 13u);
}

TEST(QuasiPlanar, OpenSquareSheetHasFourBoundaryEdgesAndFourCorners) {
  TriangleMesh m;
  m.positionsWorld = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  const MeshFeatures f = extractSilently(m, 0.01);
  EXPECT_EQ(f.polygonCount, 1u);
  EXPECT_EQ(f.featureEdges.size(), 4u);
  EXPECT_NEAR(totalEdgeLength(f), 4.0, 1e-6);
  EXPECT_EQ(f.featureVertices.size(), 4u);
}

TEST(QuasiPlanar, ZeroAreaTriangleJoinsTheSheetItLiesOn) {
  TriangleMesh m;
  m.positionsWorld = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 0, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 4, 1}};  // the last is folded onto the edge 0-1
  const MeshFeatures f = extractSilently(m, 0.01);
  EXPECT_EQ(f.polygonCount, 1u);
  EXPECT_FALSE(hasEdge(f, m.positionsWorld[0], m.positionsWorld[1]));
  EXPECT_EQ(f.featureEdges.size(), 5u);  // the bottom side as 0-4 and 4-1
  EXPECT_NEAR(totalEdgeLength(f), 4.0, 1e-6);
  EXPECT_EQ(f.featureVertices.size(), 4u);  // the corners, not vertex 4 where the side goes on straight
}

TEST(QuasiPlanar, FlippedTriangleGetsFeatureEdgesAndPrintsNothing) {
  TriangleMesh m = cube();
  std::swap(m.triangles[5].y, m.triangles[5].z);  // {0, 5, 4} on the y = 0 face
  const MeshFeatures f = extractSilently(m, 0.01);
  EXPECT_GT(f.refusedTriangles, 0u);
  const auto& p = m.positionsWorld;
  EXPECT_TRUE(hasEdge(f, p[0], p[5]));
  EXPECT_TRUE(hasEdge(f, p[5], p[4]));
  EXPECT_TRUE(hasEdge(f, p[4], p[0]));
  EXPECT_EQ(f.polygonOfTriangle.size(), 12u);
}

TEST(QuasiPlanar, SameInputGivesIdenticalOutput) {
  TriangleMesh m = ball();
  appendMesh(m, Cylinder().mesh);
  appendMesh(m, subdividedCube(5));
  m.positionsWorld.emplace_back(0.5f, 2.0f, 0.5f);
  m.triangles.emplace_back(0u, 1u, static_cast<unsigned>(m.positionsWorld.size() - 1));
  const MeshFeatures a = extractFeatures(m, 0.002);
  const MeshFeatures b = extractFeatures(m, 0.002);
  EXPECT_EQ(a.polygonCount, b.polygonCount);
  EXPECT_EQ(a.polygonOfTriangle, b.polygonOfTriangle);
  EXPECT_EQ(a.featureEdges, b.featureEdges);
  EXPECT_EQ(a.featureVertices, b.featureVertices);
}

}  // namespace
}  // namespace voxhap

#include "haptics/geometry/mesh_builder.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "haptics/geometry/mesh_topology.h"

namespace voxhap {
namespace {

constexpr double kPi = std::numbers::pi;

/// Area of a regular polygon with `sides` vertices on a circle of radius r.
double polygonArea(double r, int sides) {
  return 0.5 * static_cast<double>(sides) * r * r * std::sin(2.0 * kPi / static_cast<double>(sides));
}

/// The mesh is closed, consistently oriented, outward (positive volume), shares its
/// vertices (no two at the same position, none unused) and has no degenerate triangle.
void expectWatertight(const TriangleMesh& mesh) {
  ASSERT_FALSE(mesh.triangles.empty());
  const MeshTopology topology = computeTopology(mesh);
  EXPECT_EQ(topology.boundaryEdges, 0u);
  EXPECT_EQ(topology.nonManifoldEdges, 0u);
  EXPECT_EQ(topology.misorientedEdges, 0u);
  EXPECT_GT(signedVolume(mesh), 0.0);

  std::set<std::tuple<float, float, float>> positions;
  for (const glm::vec3& p : mesh.positionsWorld) positions.emplace(p.x, p.y, p.z);
  EXPECT_EQ(positions.size(), mesh.positionsWorld.size()) << "duplicated vertex positions";

  std::vector<bool> used(mesh.positionsWorld.size(), false);
  std::size_t degenerate = 0;
  for (const glm::uvec3& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      ASSERT_LT(t[k], mesh.positionsWorld.size());
      used[t[k]] = true;
    }
    const glm::dvec3 a(mesh.positionsWorld[t.x]);
    const glm::dvec3 b(mesh.positionsWorld[t.y]);
    const glm::dvec3 c(mesh.positionsWorld[t.z]);
    if (t.x == t.y || t.y == t.z || t.z == t.x || glm::length(glm::cross(b - a, c - a)) == 0.0) {
      ++degenerate;
    }
  }
  EXPECT_EQ(degenerate, 0u);
  EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool u) { return u; })) << "unused vertices";
}

glm::dmat4 translation(const glm::dvec3& offset) {
  glm::dmat4 m(1.0);
  m[3] = glm::dvec4(offset, 1.0);
  return m;
}

TEST(MeshBuilder, BoxIsClosedWithExactVolume) {
  TriangleMesh mesh;
  appendBox(mesh, translation({1.0, -2.0, 0.5}), {0.5, 0.25, 0.125});
  expectWatertight(mesh);
  EXPECT_EQ(mesh.triangles.size(), 12u);
  EXPECT_NEAR(signedVolume(mesh), 1.0 * 0.5 * 0.25, 1e-6);
}

TEST(MeshBuilder, MirroringTransformKeepsNormalsOutward) {
  glm::dmat4 mirror(1.0);
  mirror[0][0] = -1.0;
  TriangleMesh box;
  appendBox(box, mirror, {0.5, 0.5, 0.5});
  expectWatertight(box);
  EXPECT_NEAR(signedVolume(box), 1.0, 1e-6);
  TriangleMesh lathe;
  appendCylinder(lathe, mirror, 1.0, 1.0, 32);
  expectWatertight(lathe);
}

TEST(MeshBuilder, GeodesicSphereHas8Times4PowKTrianglesOnTheSphere) {
  for (int k = 0; k <= 4; ++k) {
    TriangleMesh mesh;
    appendGeodesicSphere(mesh, glm::dmat4(1.0), 0.025, k);
    expectWatertight(mesh);
    const std::size_t faces = 8u << (2 * k);
    EXPECT_EQ(mesh.triangles.size(), faces);
    EXPECT_EQ(mesh.positionsWorld.size(), faces / 2 + 2);  // Euler: V = F/2 + 2
    for (const glm::vec3& p : mesh.positionsWorld) {
      EXPECT_NEAR(glm::length(glm::dvec3(p)), 0.025, 1e-8);
    }
  }
}

TEST(MeshBuilder, GeodesicSphereVolumeIsWithinTessellationError) {
  TriangleMesh mesh;
  appendGeodesicSphere(mesh, glm::dmat4(1.0), 0.025, 4);
  const double sphere = 4.0 / 3.0 * kPi * std::pow(0.025, 3.0);
  const double volume = signedVolume(mesh);
  // an inscribed polyhedron: smaller than the sphere; with 2048 faces (edges ≲ 3 mm on a
  // 25 mm sphere) its faces sit at most 0.1 mm (0.4 % of the radius) inside: volume within 1 %
  EXPECT_LT(volume, sphere);
  EXPECT_GT(volume, 0.99 * sphere);
}

TEST(MeshBuilder, CylinderVolumeIsThePolygonPrism) {
  TriangleMesh mesh;
  appendCylinder(mesh, frameAlongAxis({0.1, 0.2, 0.3}, {1.0, 1.0, 0.0}), 0.5, 2.0, 48);
  expectWatertight(mesh);
  EXPECT_EQ(mesh.triangles.size(), 4u * 48u);
  EXPECT_NEAR(signedVolume(mesh), polygonArea(0.5, 48) * 2.0, 1e-6);
}

TEST(MeshBuilder, HollowCylinderVolumeIsTheAnnulusPrism) {
  TriangleMesh mesh;
  appendHollowCylinder(mesh, glm::dmat4(1.0), 0.3, 0.5, 0.2, 64);
  expectWatertight(mesh);
  EXPECT_EQ(mesh.triangles.size(), 8u * 64u);
  EXPECT_NEAR(signedVolume(mesh), (polygonArea(0.5, 64) - polygonArea(0.3, 64)) * 0.2, 1e-6);
}

TEST(MeshBuilder, TorusVolumeIsNearPappus) {
  TriangleMesh mesh;
  appendTorus(mesh, translation({0.0, 0.0, 1.0}), 1.0, 0.25, 128, 48);
  expectWatertight(mesh);
  EXPECT_EQ(mesh.triangles.size(), 2u * 128u * 48u);
  const double pappus = 2.0 * kPi * kPi * 1.0 * 0.25 * 0.25;
  EXPECT_NEAR(signedVolume(mesh), pappus, 0.005 * pappus);
}

TEST(MeshBuilder, HexPrismHasTheHexagonArea) {
  TriangleMesh mesh;
  appendHexPrism(mesh, glm::dmat4(1.0), 0.017, 0.01);
  expectWatertight(mesh);
  EXPECT_EQ(mesh.triangles.size(), 48u);
  EXPECT_NEAR(signedVolume(mesh), std::sqrt(3.0) / 2.0 * 0.017 * 0.017 * 0.01, 1e-12);
  float maxX = 0.0f;
  for (const glm::vec3& p : mesh.positionsWorld) maxX = std::max(maxX, p.x);
  EXPECT_NEAR(maxX, 0.0085f, 1e-7f);  // flats face ±x
}

TEST(MeshBuilder, LatheWithPolygonRingsHasExactCorners) {
  // a square block (half width 1) with a round through hole, as a single lathe
  const double corner = std::sqrt(2.0);
  const ProfilePoint profile[] = {{corner, 0.0, 4}, {corner, 1.0, 4}, {0.5, 1.0}, {0.5, 0.0}};
  TriangleMesh mesh;
  appendLathe(mesh, glm::dmat4(1.0), profile, 64);
  expectWatertight(mesh);
  float maxX = 0.0f;
  float maxY = 0.0f;
  for (const glm::vec3& p : mesh.positionsWorld) {
    maxX = std::max(maxX, p.x);
    maxY = std::max(maxY, p.y);
  }
  EXPECT_NEAR(maxX, 1.0f, 1e-6f);
  EXPECT_NEAR(maxY, 1.0f, 1e-6f);
  EXPECT_NEAR(signedVolume(mesh), 4.0 - polygonArea(0.5, 64), 1e-5);
}

TEST(MeshBuilder, BlockWithHoleThroughAndBlind) {
  const HoledBlockSpec through{0.03, 0.04, 0.0102, 0.04};
  const HoledBlockSpec blind{0.03, 0.04, 0.0102, 0.03};
  for (const HoledBlockSpec& spec : {through, blind}) {
    TriangleMesh mesh;
    appendBlockWithHole(mesh, glm::dmat4(1.0), spec, 128);
    expectWatertight(mesh);
    EXPECT_EQ(mesh.triangles.size(), 8u * 128u);
    const double hole = polygonArea(spec.holeRadiusM, 128) * std::min(spec.holeDepthM, spec.heightM);
    EXPECT_NEAR(signedVolume(mesh), 0.06 * 0.06 * 0.04 - hole, 1e-9);
  }
}

TEST(MeshBuilder, SphericalSocketMatchesItsAnalyticVolume) {
  const double opening = 35.0 * kPi / 180.0;
  const SocketSpec spec{0.025, 0.040, 0.040, opening};
  TriangleMesh mesh;
  appendSphericalSocket(mesh, glm::dmat4(1.0), spec, 64, 15);
  expectWatertight(mesh);
  EXPECT_EQ(mesh.triangles.size(), 64u * (4u + 2u * 15u));
  // cylinder from -0.04 to the top minus the part of the ball below the top face
  const double top = 0.025 * std::sin(opening);
  const double capHeight = 0.025 - top;
  const double cavity =
      4.0 / 3.0 * kPi * std::pow(0.025, 3.0) - kPi * capHeight * capHeight * (3.0 * 0.025 - capHeight) / 3.0;
  const double analytic = kPi * 0.04 * 0.04 * (top + 0.04) - cavity;
  EXPECT_NEAR(signedVolume(mesh), analytic, 0.01 * analytic);
}

TEST(MeshBuilder, HelixTubeIsClosedWithTheSweptVolume) {
  const HelixSpec helix{0.04, 0.02, 5.5, 0.006};
  TriangleMesh mesh;
  appendHelixTube(mesh, frameAlongAxis({1.0, 2.0, 3.0}, {0.0, 1.0, 0.0}), helix, 64, 16);
  expectWatertight(mesh);
  const std::size_t spans = static_cast<std::size_t>(std::ceil(5.5 * 64));
  EXPECT_EQ(mesh.triangles.size(), 2u * 16u * spans + 2u * 16u);
  const double turnLength = std::hypot(2.0 * kPi * 0.04, 0.02);
  const double swept = polygonArea(0.006, 16) * turnLength * 5.5;
  EXPECT_NEAR(signedVolume(mesh), swept, 0.01 * swept);
}

TEST(MeshBuilder, PathTubeAlongFilletedPolylineIsClosed) {
  const glm::dvec3 corners[] = {
      {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {1.0, 1.0, 0.0}, {1.0, 1.0, 1.0}, {0.2, 1.0, 0.4}};
  const std::vector<glm::dvec3> path = filletedPolyline(corners, 0.1, 12);
  EXPECT_EQ(path.size(), 2u + 3u * 13u);
  EXPECT_EQ(path.front(), corners[0]);
  EXPECT_EQ(path.back(), corners[4]);
  TriangleMesh mesh;
  appendPathTube(mesh, glm::dmat4(1.0), path, 0.02, 24);
  expectWatertight(mesh);
  EXPECT_EQ(mesh.triangles.size(), 2u * 24u * (path.size() - 1) + 2u * 24u);
  double length = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) length += glm::length(path[i] - path[i - 1]);
  const double swept = polygonArea(0.02, 24) * length;
  EXPECT_NEAR(signedVolume(mesh), swept, 0.02 * swept);
}

TEST(MeshBuilder, FilletArcsAreTangentAndOfTheRequestedRadius) {
  const glm::dvec3 corners[] = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {1.0, 2.0, 0.0}};
  const std::vector<glm::dvec3> path = filletedPolyline(corners, 0.25, 8);
  ASSERT_EQ(path.size(), 2u + 9u);
  // a quarter circle from (0.75, 0) to (1, 0.25) about (0.75, 0.25)
  EXPECT_NEAR(path[1].x, 0.75, 1e-12);
  EXPECT_NEAR(path[9].y, 0.25, 1e-12);
  for (std::size_t i = 1; i <= 9; ++i) {
    EXPECT_NEAR(glm::length(path[i] - glm::dvec3(0.75, 0.25, 0.0)), 0.25, 1e-12);
  }
}

TEST(MeshBuilder, FrameAlongAxisIsRigidAndMapsZToTheAxis) {
  for (const glm::dvec3& axis :
       {glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 0), glm::dvec3(0, -2, 0), glm::dvec3(0.3, -0.4, 0.5)}) {
    const glm::dmat4 frame = frameAlongAxis({1.0, 2.0, 3.0}, axis);
    const glm::dvec3 x(frame[0]);
    const glm::dvec3 y(frame[1]);
    const glm::dvec3 z(frame[2]);
    EXPECT_NEAR(glm::length(z - glm::normalize(axis)), 0.0, 1e-12);
    EXPECT_NEAR(glm::dot(x, y), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(glm::cross(x, y) - z), 0.0, 1e-12);
    EXPECT_EQ(glm::dvec3(frame[3]), glm::dvec3(1.0, 2.0, 3.0));
  }
}

TEST(MeshBuilder, SeveralComponentsInOneMeshStayClosed) {
  TriangleMesh mesh;
  appendBox(mesh, translation({-1.0, 0.0, 0.0}), {0.1, 0.1, 0.1});
  appendTorus(mesh, glm::dmat4(1.0), 0.5, 0.1, 32, 12);
  appendGeodesicSphere(mesh, translation({1.0, 0.0, 0.0}), 0.1, 2);
  TriangleMesh copy;
  appendMesh(copy, mesh);
  appendMesh(copy, TriangleMesh{});
  expectWatertight(copy);
  EXPECT_EQ(copy.triangles, mesh.triangles);
}

}  // namespace
}  // namespace voxhap

#include "haptics/scene/builtin/builtin_scenes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <numbers>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "haptics/geometry/mesh_topology.h"
#include "haptics/scene/builtin/landing_gear_parts.h"
#include "support/sanitizers.h"

namespace voxhap {
namespace {

constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------
// Exact distances between triangle meshes (ground truth for clearances)

struct Triangle {
  glm::dvec3 a;
  glm::dvec3 b;
  glm::dvec3 c;
};

/// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
glm::dvec3 closestPointOnTriangle(const glm::dvec3& p, const Triangle& t) {
  const glm::dvec3 ab = t.b - t.a;
  const glm::dvec3 ac = t.c - t.a;
  const glm::dvec3 ap = p - t.a;
  const double d1 = glm::dot(ab, ap);
  const double d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return t.a;
  const glm::dvec3 bp = p - t.b;
  const double d3 = glm::dot(ab, bp);
  const double d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return t.b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return t.a + (d1 / (d1 - d3)) * ab;
  const glm::dvec3 cp = p - t.c;
  const double d5 = glm::dot(ab, cp);
  const double d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return t.c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return t.a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    return t.b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (t.c - t.b);
  }
  const double denom = 1.0 / (va + vb + vc);
  return t.a + ab * (vb * denom) + ac * (vc * denom);
}

/// Distance between segments p1q1 and p2q2 (Ericson 5.1.9).
double segmentDistance(const glm::dvec3& p1, const glm::dvec3& q1, const glm::dvec3& p2,
                       const glm::dvec3& q2) {
  const glm::dvec3 d1 = q1 - p1;
  const glm::dvec3 d2 = q2 - p2;
  const glm::dvec3 r = p1 - p2;
  const double a = glm::dot(d1, d1);
  const double e = glm::dot(d2, d2);
  const double f = glm::dot(d2, r);
  double s = 0.0;
  double t = 0.0;
  if (a <= 1e-30 && e <= 1e-30) return glm::length(r);
  if (a <= 1e-30) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = glm::dot(d1, r);
    if (e <= 1e-30) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = glm::dot(d1, d2);
      const double denom = a * e - b * b;
      s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return glm::length((p1 + d1 * s) - (p2 + d2 * t));
}

/// Whether segment pq crosses triangle t (Möller–Trumbore; parallel segments never do,
/// their contacts are found by the edge and vertex distances).
bool segmentCrossesTriangle(const glm::dvec3& p, const glm::dvec3& q, const Triangle& t) {
  const glm::dvec3 d = q - p;
  const glm::dvec3 e1 = t.b - t.a;
  const glm::dvec3 e2 = t.c - t.a;
  const glm::dvec3 h = glm::cross(d, e2);
  const double det = glm::dot(e1, h);
  if (std::abs(det) < 1e-30) return false;
  const double inv = 1.0 / det;
  const glm::dvec3 s = p - t.a;
  const double u = glm::dot(s, h) * inv;
  if (u < 0.0 || u > 1.0) return false;
  const glm::dvec3 qv = glm::cross(s, e1);
  const double v = glm::dot(d, qv) * inv;
  if (v < 0.0 || u + v > 1.0) return false;
  const double along = glm::dot(e2, qv) * inv;
  return along >= 0.0 && along <= 1.0;
}

/// Exact distance between two triangles (0 when they intersect).
double triangleDistance(const Triangle& s, const Triangle& t) {
  const std::array<glm::dvec3, 3> sv = {s.a, s.b, s.c};
  const std::array<glm::dvec3, 3> tv = {t.a, t.b, t.c};
  for (int i = 0; i < 3; ++i) {
    if (segmentCrossesTriangle(sv[i], sv[(i + 1) % 3], t)) return 0.0;
    if (segmentCrossesTriangle(tv[i], tv[(i + 1) % 3], s)) return 0.0;
  }
  double best = 1e300;
  for (int i = 0; i < 3; ++i) {
    best = std::min(best, glm::length(sv[i] - closestPointOnTriangle(sv[i], t)));
    best = std::min(best, glm::length(tv[i] - closestPointOnTriangle(tv[i], s)));
    for (int j = 0; j < 3; ++j) {
      best = std::min(best, segmentDistance(sv[i], sv[(i + 1) % 3], tv[j], tv[(j + 1) % 3]));
    }
  }
  return best;
}

struct Aabb {
  glm::dvec3 min{1e300};
  glm::dvec3 max{-1e300};

  void add(const glm::dvec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  bool within(const Aabb& other, double gap) const {
    return min.x <= other.max.x + gap && other.min.x <= max.x + gap && min.y <= other.max.y + gap &&
           other.min.y <= max.y + gap && min.z <= other.max.z + gap && other.min.z <= max.z + gap;
  }
};

Aabb boundsOf(const Triangle& t) {
  Aabb b;
  b.add(t.a);
  b.add(t.b);
  b.add(t.c);
  return b;
}

void collectTriangles(const Part& part, std::vector<Triangle>& out) {
  const auto& p = part.mesh.positionsWorld;
  for (const glm::uvec3& t : part.mesh.triangles) {
    out.push_back({glm::dvec3(p[t.x]), glm::dvec3(p[t.y]), glm::dvec3(p[t.z])});
  }
}

std::vector<Triangle> trianglesOf(const Scene& scene, ObjectRole role) {
  std::vector<Triangle> out;
  for (const SceneObject& object : scene.objects) {
    if (object.settings.role != role) continue;
    for (const Part& part : object.parts) collectTriangles(part, out);
  }
  return out;
}

/// Distances from a moving triangle set (held in a uniform grid) to fixed triangles, for
/// translations of the moving set.
class MovingMeshDistance {
public:
  MovingMeshDistance(std::vector<Triangle> moving, double cellM)
      : moving_(std::move(moving)), cellM_(cellM), stamp_(moving_.size(), 0) {
    for (const Triangle& t : moving_) {
      const Aabb b = boundsOf(t);
      bounds_.add(b.min);
      bounds_.add(b.max);
    }
    for (std::uint32_t i = 0; i < moving_.size(); ++i) {
      const Aabb b = boundsOf(moving_[i]);
      forCells(b, 0.0, [&](std::int64_t key) { cells_[key].push_back(i); });
    }
  }

  /// Bounds of the moving set when translated by `offset`.
  Aabb boundsAt(const glm::dvec3& offset) const { return {bounds_.min + offset, bounds_.max + offset}; }

  /// The smallest distance, below `reachM`, between the moving set translated by `offset`
  /// and `fixed`; `reachM` when no pair is closer.
  double minDistance(const std::vector<Triangle>& fixed, const glm::dvec3& offset, double reachM) {
    double best = reachM;
    const Aabb moved = boundsAt(offset);
    for (const Triangle& f : fixed) {
      const Aabb fb = boundsOf(f);
      if (!fb.within(moved, reachM)) continue;
      const Triangle local{f.a - offset, f.b - offset, f.c - offset};
      const Aabb lb = boundsOf(local);
      ++query_;
      forCells(lb, reachM, [&](std::int64_t key) {
        const auto found = cells_.find(key);
        if (found == cells_.end()) return;
        for (const std::uint32_t i : found->second) {
          if (stamp_[i] == query_) continue;
          stamp_[i] = query_;
          if (!boundsOf(moving_[i]).within(lb, best)) continue;
          best = std::min(best, triangleDistance(moving_[i], local));
        }
      });
      if (best == 0.0) return 0.0;
    }
    return best;
  }

private:
  template <class Visit>
  void forCells(const Aabb& b, double margin, Visit visit) const {
    const glm::dvec3 lo = glm::floor((b.min - margin) / cellM_);
    const glm::dvec3 hi = glm::floor((b.max + margin) / cellM_);
    for (auto x = static_cast<std::int64_t>(lo.x); x <= static_cast<std::int64_t>(hi.x); ++x) {
      for (auto y = static_cast<std::int64_t>(lo.y); y <= static_cast<std::int64_t>(hi.y); ++y) {
        for (auto z = static_cast<std::int64_t>(lo.z); z <= static_cast<std::int64_t>(hi.z); ++z) {
          visit(((x + (1 << 20)) << 42) | ((y + (1 << 20)) << 21) | (z + (1 << 20)));
        }
      }
    }
  }

  std::vector<Triangle> moving_;
  double cellM_;
  Aabb bounds_;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> cells_;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t query_ = 0;
};

/// The fixed triangles that come within `reachM` of the box.
std::vector<Triangle> trianglesNear(const std::vector<Triangle>& all, const Aabb& box, double reachM) {
  std::vector<Triangle> near;
  for (const Triangle& t : all) {
    if (boundsOf(t).within(box, reachM)) near.push_back(t);
  }
  return near;
}

// ---------------------------------------------------------------------------------------
// Helpers

void expectEveryPartClosedAndOutward(const Scene& scene) {
  for (const SceneObject& object : scene.objects) {
    for (const Part& part : object.parts) {
      SCOPED_TRACE(object.name + "/" + part.name);
      EXPECT_FALSE(part.mesh.triangles.empty());
      EXPECT_EQ(part.degenerateTrianglesDropped, 0u);
      EXPECT_TRUE(part.topology.closed());
      EXPECT_TRUE(part.topology.consistentlyOriented());
      EXPECT_GT(signedVolume(part.mesh), 0.0);
    }
  }
}

/// Landing gears generated by this test process, one per seed (generation is costly).
const Scene& landingGear(std::uint64_t seed) {
  static std::map<std::uint64_t, std::unique_ptr<Scene>> cache;
  std::unique_ptr<Scene>& scene = cache[seed];
  if (!scene) scene = std::make_unique<Scene>(makeLandingGear(seed));
  return *scene;
}

// ---------------------------------------------------------------------------------------
// Names and dispatch

TEST(BuiltinScenes, ListsTheFiveScenes) {
  EXPECT_EQ(builtinSceneNames(),
            (std::vector<std::string>{"ball-and-socket", "small-ball-and-socket", "peg-in-hole",
                                      "landing-gear", "landing-gear-crew"}));
}

TEST(BuiltinScenes, UnknownNameThrowsAnErrorListingTheKnownOnes) {
  try {
    makeBuiltinScene("landing-gears", 1);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("landing-gears"), std::string::npos) << message;
    for (const std::string& name : builtinSceneNames()) {
      EXPECT_NE(message.find(name), std::string::npos) << message;
    }
  }
}

TEST(BuiltinScenes, DispatchesByNameAndRecordsTheGeneratorName) {
  EXPECT_EQ(makeBuiltinScene("ball-and-socket", 0).sourceName, "ball-and-socket");
  EXPECT_EQ(makeBuiltinScene("small-ball-and-socket", 0).sourceName, "small-ball-and-socket");
  EXPECT_EQ(makeBuiltinScene("peg-in-hole", 0).sourceName, "peg-in-hole");
}

// ---------------------------------------------------------------------------------------
// Ball and socket

// the paper's 25 mm ball and the 12.5 mm one of its Table 1: every length scales
class BallAndSocket : public ::testing::TestWithParam<double> {};

TEST_P(BallAndSocket, BallIsADynamicSphereOf2048Triangles) {
  const double r = GetParam();
  const Scene scene = makeBallAndSocket(r);
  const SceneObject* ball = scene.find("ball");
  ASSERT_NE(ball, nullptr);
  EXPECT_EQ(ball->settings.role, ObjectRole::Dynamic);
  EXPECT_EQ(ball->triangleCount(), 2048u);
  EXPECT_DOUBLE_EQ(ball->settings.pointOffsetM.value_or(0.0), -0.02 * r);  // 0.5 mm inward at 25 mm
  for (const Part& part : ball->parts) {
    for (const glm::vec3& p : part.mesh.positionsWorld) {
      EXPECT_NEAR(glm::length(glm::dvec3(p)), r, 1e-8);
    }
  }
}

TEST_P(BallAndSocket, SocketCavityMatesWithTheBallAndCapturesIt) {
  const double r = GetParam();
  const Scene scene = makeBallAndSocket(r);
  const SceneObject* socket = scene.find("socket");
  ASSERT_NE(socket, nullptr);
  EXPECT_EQ(socket->settings.role, ObjectRole::Static);
  EXPECT_EQ(socket->triangleCount(), 2176u);
  // the cavity's vertices lie on the ball's sphere, centred on the ball's centre
  std::size_t cavityVertices = 0;
  for (const Part& part : socket->parts) {
    for (const glm::vec3& p : part.mesh.positionsWorld) {
      const double d = glm::length(glm::dvec3(p));
      if (d < 1.2 * r) {
        EXPECT_NEAR(d, r, 1e-8);
        ++cavityVertices;
      }
    }
  }
  EXPECT_GT(cavityVertices, 500u);
  // the socket wraps past the equator: its top face is above the ball's centre and the
  // opening is narrower than the ball
  const Bounds b = socket->bounds();
  EXPECT_GT(b.max.z, r * std::sin(30.0 * kPi / 180.0));
  EXPECT_LT(b.max.z, r * std::sin(45.0 * kPi / 180.0));
  double openingRadius = 1.0;
  for (const Part& part : socket->parts) {
    for (const glm::vec3& p : part.mesh.positionsWorld) {
      if (std::abs(static_cast<double>(p.z) - b.max.z) < 1e-7) {
        openingRadius = std::min(openingRadius, std::hypot(double{p.x}, double{p.y}));
      }
    }
  }
  EXPECT_LT(openingRadius, 0.88 * r);
}

TEST_P(BallAndSocket, EveryPartIsClosedAndOutward) {
  expectEveryPartClosedAndOutward(makeBallAndSocket(GetParam()));
}

INSTANTIATE_TEST_SUITE_P(Radius, BallAndSocket, ::testing::Values(0.025, 0.0125));

TEST(BuiltinScenes, TheSmallBallAndSocketIsHalfTheSize) {
  const Bounds small = makeBuiltinScene("small-ball-and-socket", 0).bounds();
  const Bounds paper = makeBuiltinScene("ball-and-socket", 0).bounds();
  EXPECT_NEAR(small.max.x, 0.5 * paper.max.x, 1e-7);
  EXPECT_NEAR(small.min.z, 0.5 * paper.min.z, 1e-7);
}

// ---------------------------------------------------------------------------------------
// Peg in hole

TEST(PegInHole, PegHangsAtTheMouthOfTheHoleWithoutTouching) {
  const Scene scene = makePegInHole();
  const SceneObject* peg = scene.find("peg");
  const SceneObject* block = scene.find("block");
  ASSERT_NE(peg, nullptr);
  ASSERT_NE(block, nullptr);
  EXPECT_EQ(peg->settings.role, ObjectRole::Dynamic);
  EXPECT_EQ(block->settings.role, ObjectRole::Static);
  const Bounds pegBounds = peg->bounds();
  const Bounds blockBounds = block->bounds();
  EXPECT_GT(pegBounds.min.z, blockBounds.max.z);
  EXPECT_LT(pegBounds.min.z, blockBounds.max.z + 0.002);
  EXPECT_NEAR(pegBounds.extent().x, 0.020, 1e-6);
  EXPECT_NEAR(pegBounds.extent().z, 0.060, 1e-6);
  // coaxial
  EXPECT_NEAR(pegBounds.min.x + pegBounds.max.x, 0.0, 1e-6);
  EXPECT_NEAR(blockBounds.min.x + blockBounds.max.x, 0.0, 1e-6);
  EXPECT_NEAR(blockBounds.min.y + blockBounds.max.y, 0.0, 1e-6);
}

TEST(PegInHole, InsertedPegKeepsAbout0p2MmRadialClearance) {
  const Scene scene = makePegInHole();
  const std::vector<Triangle> block = trianglesOf(scene, ObjectRole::Static);
  std::vector<Triangle> peg = trianglesOf(scene, ObjectRole::Dynamic);
  const glm::dvec3 inserted(0.0, 0.0, -0.021);  // 20 mm into the 30 mm hole
  // as built (vertices facing vertices), then turned by half a segment (vertices facing the
  // middle of the hole's facets, the least clearance: 10.2·cos(π/128) - 10 = 0.1969 mm)
  for (const double turn : {0.0, kPi / 128.0}) {
    std::vector<Triangle> turned = peg;
    for (Triangle& t : turned) {
      for (glm::dvec3* v : {&t.a, &t.b, &t.c}) {
        *v = {v->x * std::cos(turn) - v->y * std::sin(turn), v->x * std::sin(turn) + v->y * std::cos(turn),
              v->z};
      }
    }
    MovingMeshDistance distance(std::move(turned), 0.002);
    const double clearance = distance.minDistance(block, inserted, 0.001);
    EXPECT_GE(clearance, 0.00018) << "turn " << turn;
    EXPECT_LE(clearance, 0.00020 + 1e-7) << "turn " << turn;
  }
}

TEST(PegInHole, EveryPartIsClosedAndOutward) {
  expectEveryPartClosedAndOutward(makePegInHole());
}

// ---------------------------------------------------------------------------------------
// Landing gear

TEST(LandingGear, FiguresMatchTheReferenceScene) {
  const Scene& scene = landingGear(1);
  EXPECT_EQ(scene.sourceName, "landing-gear");
  const glm::dvec3 extent = scene.bounds().extent();
  EXPECT_NEAR(extent.x, 4.1, 0.03 * 4.1);
  EXPECT_NEAR(extent.y, 1.9, 0.03 * 1.9);
  EXPECT_NEAR(extent.z, 4.8, 0.03 * 4.8);
  EXPECT_NEAR(scene.bounds().min.z, 0.0, 1e-3);  // standing on the ground, z up
  EXPECT_NEAR(static_cast<double>(scene.triangleCount(ObjectRole::Static)), 2.7e6, 0.05 * 2.7e6);

  std::set<std::string> staticNames;
  std::size_t dynamicObjects = 0;
  for (const SceneObject& object : scene.objects) {
    EXPECT_FALSE(object.parts.empty()) << object.name;
    if (object.settings.role == ObjectRole::Static) staticNames.insert(object.name);
    if (object.settings.role == ObjectRole::Dynamic) ++dynamicObjects;
  }
  EXPECT_EQ(dynamicObjects, 1u);
  for (const char* name : {"main-strut", "drag-brace", "side-brace", "wheel-and-brake", "hydraulic-lines",
                           "brackets", "bolts"}) {
    EXPECT_EQ(staticNames.count(name), 1u) << name;
  }

  const SceneObject* actuator = scene.find("actuator");
  ASSERT_NE(actuator, nullptr);
  EXPECT_EQ(actuator->settings.role, ObjectRole::Dynamic);
  EXPECT_NEAR(static_cast<double>(actuator->triangleCount()), 40000.0, 0.05 * 40000.0);
  const glm::dvec3 box = actuator->bounds().extent();
  EXPECT_NEAR(box.x, 0.9, 0.05 * 0.9);
  EXPECT_NEAR(box.y, 0.2, 0.05 * 0.2);
  EXPECT_NEAR(box.z, 0.2, 0.05 * 0.2);
  // merged from several parts of several colours
  std::set<std::array<float, 4>> colours;
  for (const Part& part : actuator->parts) {
    colours.insert({part.baseColor.r, part.baseColor.g, part.baseColor.b, part.baseColor.a});
  }
  EXPECT_GE(actuator->parts.size(), 5u);
  EXPECT_GE(colours.size(), 3u);
}

TEST(LandingGear, EveryPartIsClosedOrientedAndOutward) {
  expectEveryPartClosedAndOutward(landingGear(1));
}

TEST(LandingGear, ReportsProgressRisingToOne) {
  std::vector<double> fractions;
  const Scene scene = makeLandingGear(5, [&](double f) { fractions.push_back(f); });
  ASSERT_GE(fractions.size(), 10u);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_GE(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
  EXPECT_FALSE(scene.objects.empty());
}

bool sameScene(const Scene& a, const Scene& b) {
  if (a.objects.size() != b.objects.size()) return false;
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    const SceneObject& x = a.objects[i];
    const SceneObject& y = b.objects[i];
    if (x.name != y.name || x.settings.role != y.settings.role || x.parts.size() != y.parts.size()) {
      return false;
    }
    for (std::size_t j = 0; j < x.parts.size(); ++j) {
      const Part& p = x.parts[j];
      const Part& q = y.parts[j];
      if (p.name != q.name || p.baseColor != q.baseColor || p.mesh.positionsWorld != q.mesh.positionsWorld ||
          p.mesh.triangles != q.mesh.triangles) {
        return false;
      }
    }
  }
  return true;
}

// Release only: what it compares is numbers, and under ASan its three scenes took 64 s;
// the other LandingGear tests generate the scene there.
TEST(LandingGear, SameSeedSameSceneOtherSeedOtherScene) {
  if (test::kSanitizer) GTEST_SKIP() << "Release only (see the note above)";
  const Scene first = makeLandingGear(7);
  const Scene again = makeLandingGear(7);
  const Scene other = makeLandingGear(8);
  EXPECT_TRUE(sameScene(first, again));
  EXPECT_FALSE(sameScene(first, other));
  // the seed moves pieces around but does not change how many there are
  EXPECT_EQ(first.triangleCount(), other.triangleCount());
  // nor the actuator
  ASSERT_NE(first.find("actuator"), nullptr);
  ASSERT_NE(other.find("actuator"), nullptr);
  EXPECT_EQ(first.find("actuator")->parts.size(), other.find("actuator")->parts.size());
  for (std::size_t j = 0; j < first.find("actuator")->parts.size(); ++j) {
    EXPECT_EQ(first.find("actuator")->parts[j].mesh.positionsWorld,
              other.find("actuator")->parts[j].mesh.positionsWorld);
  }
}

/// Installed clearance and the extraction path, checked against the exact meshes: along
/// the path, translations are sampled every 4 mm and each sample must keep more than
/// 2 mm, so the motion between samples (distance changes at most as fast as the motion)
/// is collision-free too.
TEST(LandingGear, ActuatorClearsStaticPartsAndCanBeExtractedForSeveralSeeds) {
  constexpr double kStepM = 0.004;
  const std::vector<glm::dvec3> path = landing_gear::extractionPathM();
  // one seed under a sanitizer (the three took 76 s under ASan): the others differ in numbers
  std::vector<std::uint64_t> seeds{1, 2, 0x9E3779B97F4A7C15};
  if (test::kSanitizer) seeds.resize(1);
  for (const std::uint64_t seed : seeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Scene scene = makeLandingGear(seed);
    MovingMeshDistance actuator(trianglesOf(scene, ObjectRole::Dynamic), 0.01);
    Aabb swept;
    for (const glm::dvec3& offset : path) {
      swept.add(actuator.boundsAt(offset).min);
      swept.add(actuator.boundsAt(offset).max);
    }
    const std::vector<Triangle> nearby = trianglesNear(trianglesOf(scene, ObjectRole::Static), swept, 0.02);
    ASSERT_FALSE(nearby.empty());

    const double installed = actuator.minDistance(nearby, glm::dvec3(0.0), 0.02);
    EXPECT_GE(installed, 0.002) << "installed clearance " << installed * 1e3 << " mm";

    double least = 1.0;
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
      const double length = glm::length(path[i + 1] - path[i]);
      const auto steps = static_cast<int>(std::ceil(length / kStepM));
      for (int k = 0; k <= steps; ++k) {
        const glm::dvec3 offset = path[i] + (path[i + 1] - path[i]) * (static_cast<double>(k) / steps);
        const double d = actuator.minDistance(nearby, offset, 0.0025);
        least = std::min(least, d);
        ASSERT_GT(d, 0.5 * kStepM) << "at offset " << offset.x << ", " << offset.y << ", " << offset.z;
      }
    }
    EXPECT_GT(least, 0.5 * kStepM);
    // at the end of the path the actuator is clear of the whole gear
    const Aabb out = actuator.boundsAt(path.back());
    const Bounds gear = scene.bounds();
    EXPECT_TRUE(out.max.y < gear.min.y || out.min.y > gear.max.y);
  }
}

/// The crew's scene: the gear's static objects unchanged (so its voxels and their cache
/// are the gear's), and two spares that wait clear of it, with gaps to where the actuator
/// comes out that their scripts (crew-spare-lift.txt, crew-hose-lower.txt: 0.22 m each)
/// close, and a gap between them that they close without it: bounding boxes apart are
/// meshes apart.
TEST(LandingGear, TheCrewsSparesWaitClearOfTheGearAndOfTheActuatorsWayOut) {
  const Scene crew = makeLandingGearCrew(1);
  const Scene& gear = landingGear(1);
  EXPECT_EQ(crew.sourceName, "landing-gear-crew");
  Bounds staticBounds;
  std::size_t compared = 0;
  for (const SceneObject& object : gear.objects) {
    const SceneObject* same = crew.find(object.name);
    ASSERT_NE(same, nullptr) << object.name;
    ASSERT_EQ(same->parts.size(), object.parts.size()) << object.name;
    for (std::size_t i = 0; i < object.parts.size(); ++i) {
      EXPECT_EQ(same->parts[i].mesh.positionsWorld, object.parts[i].mesh.positionsWorld) << object.name;
      EXPECT_EQ(same->parts[i].mesh.triangles, object.parts[i].mesh.triangles) << object.name;
      ++compared;
    }
    if (object.settings.role == ObjectRole::Static) staticBounds.add(object.bounds());
  }
  EXPECT_GT(compared, 40u);
  const SceneObject* spare = crew.find("spare-actuator");
  const SceneObject* hose = crew.find("spare-hose");
  ASSERT_NE(spare, nullptr);
  ASSERT_NE(hose, nullptr);
  EXPECT_EQ(spare->settings.role, ObjectRole::Dynamic);
  EXPECT_EQ(hose->settings.role, ObjectRole::Dynamic);
  Scene spares;
  spares.objects = {*spare, *hose};
  expectEveryPartClosedAndOutward(spares);

  // beyond the gear's -y side
  EXPECT_LT(spare->bounds().max.y, staticBounds.min.y - 0.1);
  EXPECT_LT(hose->bounds().max.y, staticBounds.min.y - 0.1);
  // the actuator at the end of its way out: the spare below it, the hose above it
  Bounds out = crew.find("actuator")->bounds();
  out.min += landing_gear::extractionPathM().back();
  out.max += landing_gear::extractionPathM().back();
  const double spareGapM = out.min.z - spare->bounds().max.z;
  const double hoseGapM = hose->bounds().min.z - out.max.z;
  EXPECT_NEAR(spareGapM, 0.10, 1e-6);
  EXPECT_GT(hoseGapM, 0.08);
  EXPECT_LT(hoseGapM, 0.13);
  EXPECT_LT(hose->bounds().min.z - spare->bounds().max.z, 2 * 0.22);
  for (const Bounds& b : {spare->bounds(), hose->bounds()}) {
    EXPECT_LT(std::max(b.min.x, out.min.x), std::min(b.max.x, out.max.x));  // they overlap in x
    EXPECT_LT(std::max(b.min.y, out.min.y), std::min(b.max.y, out.max.y));  // and in y
  }
}

TEST(LandingGear, NoStraightPullAlongAnAxisFreesTheActuator) {
  const Scene& scene = landingGear(1);
  MovingMeshDistance actuator(trianglesOf(scene, ObjectRole::Dynamic), 0.01);
  const std::vector<Triangle> all = trianglesOf(scene, ObjectRole::Static);
  constexpr double kStepM = 0.004;
  constexpr double kPullM = 1.5;
  for (const glm::dvec3& direction : {glm::dvec3(1, 0, 0), glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0),
                                      glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1)}) {
    Aabb swept = actuator.boundsAt(glm::dvec3(0.0));
    swept.add(actuator.boundsAt(kPullM * direction).min);
    swept.add(actuator.boundsAt(kPullM * direction).max);
    const std::vector<Triangle> nearby = trianglesNear(all, swept, 0.001);
    bool blocked = false;
    for (double s = kStepM; s <= kPullM && !blocked; s += kStepM) {
      blocked = actuator.minDistance(nearby, s * direction, 0.0005) < 0.0005;
    }
    EXPECT_TRUE(blocked) << "free pull along " << direction.x << ", " << direction.y << ", " << direction.z;
  }
}

}  // namespace
}  // namespace voxhap

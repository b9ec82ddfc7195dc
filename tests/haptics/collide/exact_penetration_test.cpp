#include "haptics/collide/exact_penetration.h"

#include <cmath>
#include <string>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "haptics/geometry/mesh_builder.h"
#include "haptics/sim/scene_model.h"
#include "support/contact_scenes.h"

namespace voxhap {
namespace {

constexpr double kVoxel = 0.001;
constexpr double kSpacing = kVoxel / kProbesPerVoxel;  // 0.25 mm
const double kSqrt2 = std::sqrt(2.0);
/// Probes on edges and at vertices sit exactly on them: depths there are exact but for
/// the meshes' float coordinates.
constexpr double kExactM = 1e-6;

Voxmap voxmapOf(const SceneObject& object) {
  VoxelizeOptions options;
  options.voxelSizeM = kVoxel;
  const SceneObject* objects[] = {&object};
  return voxelizeObjects(objects, options, {});
}

ExactBody bodyOf(const SceneObject& object, const Voxmap* voxmap) {
  ExactBody body;
  for (const Part& part : object.parts) body.meshesLocal.push_back(&part.mesh);
  body.voxmapLocal = voxmap;
  return body;
}

/// A box of half extents `halfM` placed by `placement` in its local frame.
SceneObject box(const std::string& name, const glm::dmat4& placement, const glm::dvec3& halfM,
                ObjectRole role = ObjectRole::Dynamic) {
  return test::meshObject(name, role, [&](TriangleMesh& m) { appendBox(m, placement, halfM); });
}

glm::dquat about(double degrees, const glm::dvec3& axis) {
  return glm::angleAxis(glm::radians(degrees), glm::normalize(axis));
}

/// Every mesh vertex of `object` placed by `toOtherLocal` lies outside body `other`:
/// probing vertices only would find nothing.
void expectVerticesOutside(ExactPenetration& truth, std::size_t other, const SceneObject& object,
                           const Pose& toOtherLocal) {
  for (const Part& part : object.parts) {
    for (const glm::vec3& v : part.mesh.positionsWorld) {
      EXPECT_FALSE(truth.inside(other, apply(toOtherLocal, glm::dvec3(v))))
          << v.x << " " << v.y << " " << v.z;
    }
  }
}

/// The ways a measurement may go: filtered by voxmaps or by bounding boxes, the side of a
/// probe near a surface by pseudo-normals or by the ray vote.
ExactPenetrationLimits voting() {
  ExactPenetrationLimits limits;
  limits.maxPseudoNormalTriangles = 0;
  return limits;
}
const std::pair<bool, ExactPenetrationLimits> kWays[] = {
    {true, {}}, {false, {}}, {true, voting()}, {false, voting()}};
std::string wayName(bool filtered, const ExactPenetrationLimits& limits) {
  return std::string(filtered ? "voxmaps filter" : "bounding boxes filter") +
         (limits.maxPseudoNormalTriangles == 0 ? ", rays vote" : ", pseudo-normals");
}

/// The 100 × 100 × 10 mm plate (top face z = 0), static, with its voxmap.
struct Plate {
  SceneObject object = test::plate();
  Voxmap voxmap = voxmapOf(object);
};

TEST(ExactPenetration, SeesAnEdgeCuttingIntoAFaceBetweenItsVertices) {
  const Plate plate;
  // a 120 mm rod of square section turned 45° about its axis: its lowest edge runs
  // across the whole plate, its vertices beyond the plate's sides
  const SceneObject rod =
      box("rod", glm::rotate(glm::dmat4(1.0), glm::radians(45.0), glm::dvec3(1, 0, 0)), {0.06, 0.005, 0.005});
  Pose pose;
  pose.position = {0.0013, 0.0021, 0.005 * kSqrt2 - 0.0003};  // the edge 0.3 mm below the top face

  for (const auto& [filtered, limits] : kWays) {
    SCOPED_TRACE(wayName(filtered, limits));
    ExactPenetration truth(bodyOf(rod, nullptr), bodyOf(plate.object, filtered ? &plate.voxmap : nullptr),
                           kSpacing, limits);
    EXPECT_TRUE(truth.probedWhole(0));
    EXPECT_TRUE(truth.probedWhole(1));
    expectVerticesOutside(truth, 1, rod, pose);

    const PenetrationSample s = truth.measure(pose, Pose{});
    EXPECT_NEAR(s.depthM, 0.0003, kExactM);
    EXPECT_EQ(s.direction, PenetrationDirection::AIntoB);
    EXPECT_NEAR(s.deepestWorld.z, -0.0003, kExactM);
    EXPECT_NEAR(s.deepestWorld.y, 0.0021, kExactM);
    EXPECT_LT(std::abs(s.deepestWorld.x), 0.05);
    EXPECT_GT(s.inside, 0u);
    EXPECT_GE(s.candidates, s.inside);
    EXPECT_GE(s.nearProbes, s.candidates);
    EXPECT_GE(s.probes, s.nearProbes);
  }
}

TEST(ExactPenetration, SeesAStaticCornerPokingIntoAMovingFace) {
  // the plate turned 45° about z: a vertical corner edge at x = 50√2 mm, y = 0
  const SceneObject diamond = box("diamond",
                                  glm::rotate(glm::dmat4(1.0), glm::radians(45.0), glm::dvec3(0, 0, 1)) *
                                      glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, -0.005)),
                                  {0.05, 0.05, 0.005}, ObjectRole::Static);
  const Voxmap diamondVoxmap = voxmapOf(diamond);
  // a 40 mm cube (local frame centred on it), turned a quarter about z, its face 0.5 mm
  // past the corner; every vertex of the cube is above or below the plate
  const SceneObject cube = box("cube", glm::dmat4(1.0), {0.02, 0.02, 0.02});
  const Voxmap cubeVoxmap = voxmapOf(cube);
  const double cornerX = 0.05 * kSqrt2;
  const Pose pose{{cornerX - 0.0005 + 0.02, 0.0031, -0.005}, about(90.0, {0, 0, 1})};

  PenetrationSample whole;
  for (const double maxWhole : {kMaxWholeProbes, 1000.0}) {
    SCOPED_TRACE(maxWhole);
    ExactPenetrationLimits limits;
    limits.maxWholeProbes = maxWhole;
    ExactPenetration truth(bodyOf(cube, &cubeVoxmap), bodyOf(diamond, &diamondVoxmap), kSpacing, limits);
    EXPECT_TRUE(truth.probedWhole(0));
    EXPECT_EQ(truth.probedWhole(1), maxWhole == kMaxWholeProbes);
    expectVerticesOutside(truth, 1, cube, pose);

    const PenetrationSample s = truth.measure(pose, Pose{});
    EXPECT_NEAR(s.depthM, 0.0005, kExactM);
    EXPECT_EQ(s.direction, PenetrationDirection::BIntoA);
    EXPECT_NEAR(s.deepestWorld.x, cornerX, kExactM);
    EXPECT_NEAR(s.deepestWorld.y, 0.0, kExactM);
    EXPECT_GE(s.deepestWorld.z, -0.01 - kExactM);
    EXPECT_LE(s.deepestWorld.z, kExactM);
    if (maxWhole == kMaxWholeProbes) {
      whole = s;
    } else {
      // on demand, only the plate's blocks near the cube are probed; the answer is the same
      EXPECT_EQ(s.depthM, whole.depthM);
      EXPECT_EQ(s.deepestWorld, whole.deepestWorld);
      EXPECT_EQ(s.inside, whole.inside);
      EXPECT_LT(s.probes, whole.probes);
      EXPECT_GT(truth.probeCount(1), 0u);
      // again, from the cache
      const PenetrationSample again = truth.measure(pose, Pose{});
      EXPECT_EQ(again.depthM, s.depthM);
      EXPECT_EQ(again.probes, s.probes);
    }
  }
}

TEST(ExactPenetration, TwoMovingBodiesAnEdgeOfOneIntoAFaceOfTheOther) {
  const SceneObject cube = box("cube", glm::dmat4(1.0), {0.01, 0.01, 0.01});
  const SceneObject post = box("post", glm::dmat4(1.0), {0.01, 0.01, 0.02});
  const Voxmap cubeVoxmap = voxmapOf(cube);
  const Voxmap postVoxmap = voxmapOf(post);
  // the post turned 45° about z: its vertical edge 0.4 mm into the cube's +x face, its
  // ends above and below the cube; both carried by the same rigid motion
  const Pose motion{{0.1, -0.2, 0.3}, about(30.0, {1, 2, 3})};
  const Pose postInCube{{0.01 - 0.0004 + 0.01 * kSqrt2, 0.0017, 0.0009}, about(45.0, {0, 0, 1})};
  const Pose cubeToWorld = motion;
  const Pose postToWorld = compose(motion, postInCube);

  for (const auto& [filtered, limits] : kWays) {
    SCOPED_TRACE(wayName(filtered, limits));
    ExactPenetration truth(bodyOf(cube, filtered ? &cubeVoxmap : nullptr),
                           bodyOf(post, filtered ? &postVoxmap : nullptr), kSpacing, limits);
    expectVerticesOutside(truth, 0, post, postInCube);
    expectVerticesOutside(truth, 1, cube, inverse(postInCube));

    const PenetrationSample s = truth.measure(cubeToWorld, postToWorld);
    EXPECT_NEAR(s.depthM, 0.0004, kExactM);
    EXPECT_EQ(s.direction, PenetrationDirection::BIntoA);
    const glm::dvec3 inCube = apply(inverse(cubeToWorld), s.deepestWorld);
    EXPECT_NEAR(inCube.x, 0.0096, kExactM);
    EXPECT_NEAR(inCube.y, 0.0017, kExactM);
    EXPECT_LE(std::abs(inCube.z), 0.01);

    // the same pair the other way round
    ExactPenetration swapped(bodyOf(post, filtered ? &postVoxmap : nullptr),
                             bodyOf(cube, filtered ? &cubeVoxmap : nullptr), kSpacing, limits);
    const PenetrationSample t = swapped.measure(postToWorld, cubeToWorld);
    EXPECT_NEAR(t.depthM, 0.0004, kExactM);
    EXPECT_EQ(t.direction, PenetrationDirection::AIntoB);
  }
}

TEST(ExactPenetration, WithoutContactDepthIsZeroAndTheClearanceExact) {
  const Plate plate;
  const SceneObject cube = box("cube", glm::dmat4(1.0), {0.01, 0.01, 0.01});
  for (const auto& [filtered, limits] : kWays) {
    SCOPED_TRACE(wayName(filtered, limits));
    ExactPenetration truth(bodyOf(cube, nullptr), bodyOf(plate.object, filtered ? &plate.voxmap : nullptr),
                           kSpacing, limits);
    // 2 mm above the top face (2 voxels; within the clearance range either way)
    Pose above;
    above.position = {0.0013, 0.0021, 0.012};
    const PenetrationSample s = truth.measure(above, Pose{});
    EXPECT_EQ(s.depthM, 0.0);
    EXPECT_EQ(s.inside, 0u);
    EXPECT_EQ(s.direction, PenetrationDirection::None);
    EXPECT_NEAR(s.clearanceM, 0.002, kExactM);
    EXPECT_GT(s.probes, 0u);

    // 20 mm above: beyond the clearance range, every probe skipped in groups
    above.position.z = 0.030;
    const PenetrationSample far = truth.measure(above, Pose{});
    EXPECT_EQ(far.depthM, 0.0);
    EXPECT_TRUE(std::isinf(far.clearanceM));
    EXPECT_EQ(far.nearProbes, 0u);
  }
}

TEST(ExactPenetration, MeasuresDeepPenetrationThroughInteriorVoxels) {
  const Plate plate;
  const SceneObject cube = box("cube", glm::dmat4(1.0), {0.01, 0.01, 0.01});
  ExactPenetration truth(bodyOf(cube, nullptr), bodyOf(plate.object, &plate.voxmap), kSpacing);
  Pose sunk;
  sunk.position = {0.0013, 0.0021, 0.01 - 0.003};  // the bottom face 3 mm below the top face
  const PenetrationSample s = truth.measure(sunk, Pose{});
  EXPECT_NEAR(s.depthM, 0.003, kExactM);
  EXPECT_GT(s.inside, s.candidates / 2);  // most are in interior voxels, without a vote
}

TEST(ExactPenetration, InsideAnyOfOverlappingPartsIsInside) {
  // a plus of two overlapping bars; the cube sits inside the second bar only, where the
  // nearest surface is the first bar's face buried in the second: outside that part,
  // inside the union
  SceneObject plus;
  plus.name = "plus";
  plus.parts.push_back(box("bar x", glm::dmat4(1.0), {0.010, 0.002, 0.002}, ObjectRole::Static).parts[0]);
  plus.parts.push_back(box("bar y", glm::dmat4(1.0), {0.002, 0.010, 0.002}, ObjectRole::Static).parts[0]);
  const Voxmap plusVoxmap = voxmapOf(plus);
  const SceneObject cube = box("cube", glm::dmat4(1.0), {0.0005, 0.0005, 0.0005});
  Pose pose;
  pose.position = {0.0, 0.003, 0.0};  // y from 2.5 to 3.5 mm, inside the second bar
  for (const auto& [filtered, limits] : kWays) {
    SCOPED_TRACE(wayName(filtered, limits));
    ExactPenetration truth(bodyOf(cube, nullptr), bodyOf(plus, filtered ? &plusVoxmap : nullptr), kSpacing,
                           limits);
    const PenetrationSample s = truth.measure(pose, Pose{});
    EXPECT_EQ(s.direction, PenetrationDirection::AIntoB);
    EXPECT_GT(s.inside, 0u);
    // the depth is the distance to the nearest part's surface, the buried face included
    EXPECT_NEAR(s.depthM, 0.0015, kExactM);
  }
}

TEST(ExactPenetration, MeasuringAgainGivesWhatAFreshMeasurementGives) {
  // drifting keeps each probe's last distance for the next measurements: it may spare
  // queries, never change the answer; the cube comes down towards the plate, turning
  const Plate plate;
  const SceneObject cube = box("cube", glm::dmat4(1.0), {0.01, 0.01, 0.01});
  ExactPenetration reused(bodyOf(cube, nullptr), bodyOf(plate.object, &plate.voxmap), kSpacing);
  for (int step = 0; step <= 12; ++step) {
    SCOPED_TRACE(step);
    const Pose pose{{0.0013, 0.0021, 0.0135 - 0.0003 * step}, about(2.0 * step, {1, 0.3, 0})};
    ExactPenetration fresh(bodyOf(cube, nullptr), bodyOf(plate.object, &plate.voxmap), kSpacing);
    const PenetrationSample expected = fresh.measure(pose, Pose{});
    const PenetrationSample s = reused.measure(pose, Pose{}, step % 3 != 1);  // some without the clearance
    EXPECT_EQ(s.depthM, expected.depthM);
    EXPECT_EQ(s.inside, expected.inside);
    if (step % 3 != 1) {
      EXPECT_EQ(s.clearanceM, expected.clearanceM);
    } else {
      EXPECT_TRUE(std::isinf(s.clearanceM));
    }
  }
}

TEST(ExactPenetration, TheInsideVoteAndBadSpacing) {
  const Plate plate;
  const SceneObject cube = box("cube", glm::dmat4(1.0), {0.01, 0.01, 0.01});
  ExactPenetration truth(bodyOf(cube, nullptr), bodyOf(plate.object, &plate.voxmap), kSpacing);
  EXPECT_TRUE(truth.inside(1, {0.0, 0.0, -0.005}));
  EXPECT_FALSE(truth.inside(1, {0.0, 0.0, 0.005}));
  EXPECT_FALSE(truth.inside(1, {0.0, 0.06, -0.005}));  // beside the plate
  EXPECT_TRUE(truth.inside(0, {0.009, -0.009, 0.0}));
  EXPECT_EQ(truth.probeSpacingM(), kSpacing);
  EXPECT_STREQ(penetrationDirectionName(PenetrationDirection::BIntoA), "b-into-a");
  EXPECT_THROW(ExactPenetration(bodyOf(cube, nullptr), bodyOf(plate.object, nullptr), 0.0), Error);
}

}  // namespace
}  // namespace voxhap

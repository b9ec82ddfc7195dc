// The pair wrench of tangentPlaneWrench when both objects of the pair move and turn: a
// pure equal-and-opposite force pair acting at each contact point (angular momentum
// about a fixed point conserved), and damping from the true relative velocity of the two
// bodies at that point.
#include "haptics/collide/tangent_plane_force.h"

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "support/contact_scenes.h"

namespace voxhap {
namespace {

constexpr double kVoxelM = 0.001;

using test::at;

/// A 20 × 20 × 10 mm voxmap box and a 6 × 6 × 4 mm pointshell box, both moving and
/// turning, the small one posed with its bottom inside the big one's near layers.
struct MovingPair {
  Voxmap voxmap;
  Pointshell shell;
  BodyMotion shellMotion;
  BodyMotion voxmapMotion;
  ContactParams params;
  std::vector<PointContact> contacts;

  MovingPair() {
    const SceneObject big = test::meshObject("big", ObjectRole::Dynamic, [](TriangleMesh& m) {
      appendBox(m, at(0.0, 0.0, 0.0), glm::dvec3(0.01, 0.01, 0.005));
    });
    const SceneObject small = test::meshObject("small", ObjectRole::Dynamic, [](TriangleMesh& m) {
      appendBox(m, at(0.0, 0.0, 0.0), glm::dvec3(0.003, 0.003, 0.002));
    });
    VoxelizeOptions voxelOptions;
    voxelOptions.voxelSizeM = kVoxelM;
    const SceneObject* objects[] = {&big};
    voxmap = voxelizeObjects(objects, voxelOptions, {});
    PointshellOptions shellOptions;
    shellOptions.pointSpacingM = kVoxelM;
    shell = pointshellOf(small, shellOptions, {});

    // the voxmap object off the origin and turned; the shell tilted over its top face,
    // its lowest points a voxel into the force layer
    voxmapMotion.poseWorld =
        Pose{glm::dvec3(0.03, -0.02, 0.01), quatFromRotationVector(glm::dvec3(0.3, -0.2, 0.5))};
    voxmapMotion.comLocal = glm::dvec3(0.0005, -0.0003, 0.0002);
    voxmapMotion.linearVelocityWorld = glm::dvec3(0.02, -0.01, 0.03);
    voxmapMotion.angularVelocityWorld = glm::dvec3(1.5, -2.0, 0.7);
    const Pose shellInVoxmap{glm::dvec3(0.001, -0.002, 0.005 + 0.002 + 0.0005),
                             quatFromRotationVector(glm::dvec3(0.15, 0.1, 0.4))};
    shellMotion.poseWorld = compose(voxmapMotion.poseWorld, shellInVoxmap);
    shellMotion.comLocal = glm::dvec3(-0.0002, 0.0004, 0.0001);
    shellMotion.linearVelocityWorld = glm::dvec3(-0.01, 0.025, -0.02);
    shellMotion.angularVelocityWorld = glm::dvec3(-0.8, 2.5, -1.2);

    params.geometricalAwareness = true;
    params.pointStiffnessNPerM = 1000.0;
    params.pointDampingNsPerM = 0.0;
    contacts.resize(shell.size());
    const auto found = samplePoints(shell, voxmap, VoxelTransform::make(shellInVoxmap, voxmap.grid()),
                                    fieldShiftsByFeature(true, voxmap.encoding()),
                                    params.sampledLayer(voxmap.encoding().maxValue()), 0,
                                    static_cast<std::uint32_t>(shell.size()), contacts.data());
    contacts.resize(found);
  }

  glm::dvec3 pointWorld(const PointContact& c) const {
    return apply(shellMotion.poseWorld, glm::dvec3(shell.positionsLocal[c.point]));
  }
  PairWrench wrenchOf(std::span<const PointContact> some) const {
    return tangentPlaneWrench(shell, voxmap, params, shellMotion, voxmapMotion, some);
  }
};

glm::dvec3 comWorld(const BodyMotion& m) {
  return apply(m.poseWorld, m.comLocal);
}

/// Velocity of the material point of `m` at `xWorld`.
glm::dvec3 velocityAt(const BodyMotion& m, const glm::dvec3& xWorld) {
  return m.linearVelocityWorld + glm::cross(m.angularVelocityWorld, xWorld - comWorld(m));
}

TEST(TangentPlaneForce, EachContactIsAnEqualAndOppositeForcePairAtItsPoint) {
  const MovingPair pair;
  ASSERT_GE(pair.contacts.size(), 4u);
  int pushing = 0;
  for (const PointContact& c : pair.contacts) {
    const PairWrench w = pair.wrenchOf(std::span(&c, 1));
    if (w.pushingPoints == 0) continue;
    ++pushing;
    const glm::dvec3 x = pair.pointWorld(c);
    const double scaleNm = glm::length(w.forceOnShellWorld) * 0.02;
    EXPECT_NEAR(glm::length(w.forceOnShellWorld + w.forceOnVoxmapWorld), 0.0, 1e-12);
    // both torques are those of the one force acting at the point
    const glm::dvec3 shellTorque = glm::cross(x - comWorld(pair.shellMotion), w.forceOnShellWorld);
    const glm::dvec3 voxmapTorque = glm::cross(x - comWorld(pair.voxmapMotion), w.forceOnVoxmapWorld);
    EXPECT_NEAR(glm::length(w.torqueOnShellWorld - shellTorque), 0.0, 1e-6 * scaleNm) << "point " << c.point;
    EXPECT_NEAR(glm::length(w.torqueOnVoxmapWorld - voxmapTorque), 0.0, 1e-6 * scaleNm)
        << "point " << c.point;
  }
  EXPECT_GE(pushing, 4);
}

TEST(TangentPlaneForce, PairWrenchConservesAngularMomentumAboutAFixedPoint) {
  const MovingPair pair;
  const PairWrench w = pair.wrenchOf(pair.contacts);
  ASSERT_GT(w.pushingPoints, 0u);
  const glm::dvec3 fixedPoint(-0.3, 0.7, 0.2);
  const glm::dvec3 total =
      w.torqueOnShellWorld + glm::cross(comWorld(pair.shellMotion) - fixedPoint, w.forceOnShellWorld) +
      w.torqueOnVoxmapWorld + glm::cross(comWorld(pair.voxmapMotion) - fixedPoint, w.forceOnVoxmapWorld);
  EXPECT_NEAR(glm::length(total), 0.0, 1e-9 * glm::length(w.forceOnShellWorld));
}

// Stiffness off and unit damping: each contact pushes with max(0, v_rel·u) along −u,
// v_rel the shell's material velocity at the point minus the voxmap object's there.
TEST(TangentPlaneForce, DampingUsesTheRelativeVelocityOfBothMovingAndTurningBodiesAtThePoint) {
  MovingPair pair;
  pair.params.pointStiffnessNPerM = 0.0;
  pair.params.pointDampingNsPerM = 1.0;
  int checked = 0;
  for (int flip = 0; flip < 2; ++flip) {
    for (const PointContact& c : pair.contacts) {
      const PairWrench w = pair.wrenchOf(std::span(&c, 1));
      const glm::dvec3 x = pair.pointWorld(c);
      const glm::dvec3 relative = velocityAt(pair.shellMotion, x) - velocityAt(pair.voxmapMotion, x);
      if (w.pushingPoints == 0) continue;
      const double pushN = glm::length(w.forceOnShellWorld);
      const glm::dvec3 u = -w.forceOnShellWorld / pushN;
      EXPECT_NEAR(pushN, glm::dot(relative, u), 1e-9) << "point " << c.point;
      ++checked;
    }
    // the same with every velocity reversed: the points that separated now approach
    for (BodyMotion* m : {&pair.shellMotion, &pair.voxmapMotion}) {
      m->linearVelocityWorld = -m->linearVelocityWorld;
      m->angularVelocityWorld = -m->angularVelocityWorld;
    }
  }
  EXPECT_EQ(checked, static_cast<int>(pair.contacts.size()))
      << "every contact approaches one way or the other";
}

}  // namespace
}  // namespace voxhap

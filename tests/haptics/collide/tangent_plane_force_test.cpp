// The pair wrench of tangentPlaneWrench when both objects of the pair move and turn: a
// pure equal-and-opposite force pair acting at each contact point (angular momentum
// about a fixed point conserved), and damping from the true relative velocity of the two
// bodies at that point; and the sums of a frame with many contacts, in two halves, alike
// with and without a frame helper.
#include "haptics/collide/tangent_plane_force.h"

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "haptics/runtime/frame_helper.h"
#include "support/contact_scenes.h"
#include "support/helper_thread.h"

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

bool sameRow(const DepthRow& a, const DepthRow& b) {
  return a.pointWorld == b.pointWorld && a.intoVoxmapWorld == b.intoVoxmapWorld && a.depthM == b.depthM &&
         a.floorM == b.floorM && a.surfacePlane == b.surfacePlane;
}

// A frame of kHalvedContacts contacts or more (here the pair's, repeated) is summed in two
// halves: every contact's force counted once, scaled as one frame's; the depth rows in
// contact order; and the same bits when a frame helper sums the second half.
TEST(TangentPlaneForce, ManyContactsAreSummedInTwoHalvesAlikeWithAndWithoutAHelper) {
  const MovingPair pair;
  std::vector<PointContact> many;
  // each contact, and a copy of it one layer beyond the force layer, which gives no row (nor,
  // without damping, any push)
  while (many.size() < 3 * kHalvedContacts + 1) {
    for (PointContact c : pair.contacts) {
      many.push_back(c);
      c.value = static_cast<std::uint8_t>(pair.params.forceLayer + 1);
      many.push_back(c);
    }
  }
  constexpr double kRowFloorM = 0.0;  // the rows of the contacts that push
  // each contact alone: its force unscaled (one push), its row
  glm::dvec3 forceSumN(0.0);
  std::uint32_t pushing = 0;
  std::vector<DepthRow> expectedRows;
  for (const PointContact& c : many) {
    DepthRow row;
    const DepthRowSink one{std::span(&row, 1), kRowFloorM};
    const PairWrench w = tangentPlaneWrench(pair.shell, pair.voxmap, pair.params, pair.shellMotion,
                                            pair.voxmapMotion, std::span(&c, 1), &one);
    forceSumN += w.forceOnShellWorld;
    pushing += w.pushingPoints;
    if (w.depthRows == 1) expectedRows.push_back(row);
  }
  ASSERT_GT(pushing, static_cast<std::uint32_t>(kStiffContacts));
  ASSERT_GT(expectedRows.size(), kHalvedContacts / 2);
  ASSERT_EQ(2 * expectedRows.size(), many.size()) << "a row from every contact in the force layer";

  const auto sum = [&](FrameHelper* helper, std::vector<DepthRow>& rows) {
    rows.assign(many.size(), DepthRow{});
    const DepthRowSink sink{rows, kRowFloorM};
    const PairWrench w = tangentPlaneWrench(pair.shell, pair.voxmap, pair.params, pair.shellMotion,
                                            pair.voxmapMotion, many, &sink, helper);
    rows.resize(w.depthRows);
    return w;
  };
  std::vector<DepthRow> rowsAlone;
  const PairWrench alone = sum(nullptr, rowsAlone);
  EXPECT_EQ(alone.pushingPoints, pushing);
  const double scale = double(kStiffContacts) / double(pushing);
  EXPECT_NEAR(glm::length(alone.forceOnShellWorld - scale * forceSumN), 0.0,
              1e-12 * scale * glm::length(forceSumN));
  ASSERT_EQ(rowsAlone.size(), expectedRows.size());
  for (std::size_t r = 0; r < rowsAlone.size(); ++r) EXPECT_TRUE(sameRow(rowsAlone[r], expectedRows[r])) << r;

  test::onAThreadOfItsOwn([&] {
    FrameHelper helper;
    std::vector<DepthRow> rowsHelped;
    const PairWrench helped = sum(&helper, rowsHelped);
    EXPECT_EQ(helped.forceOnShellWorld, alone.forceOnShellWorld);
    EXPECT_EQ(helped.torqueOnShellWorld, alone.torqueOnShellWorld);
    EXPECT_EQ(helped.torqueOnVoxmapWorld, alone.torqueOnVoxmapWorld);
    EXPECT_EQ(helped.contactPoints, alone.contactPoints);
    EXPECT_EQ(helped.pushingPoints, alone.pushingPoints);
    EXPECT_EQ(helped.maxDepthM, alone.maxDepthM);
    ASSERT_EQ(rowsHelped.size(), rowsAlone.size());
    for (std::size_t r = 0; r < rowsHelped.size(); ++r)
      EXPECT_TRUE(sameRow(rowsHelped[r], rowsAlone[r])) << r;
  });
}

}  // namespace
}  // namespace voxhap

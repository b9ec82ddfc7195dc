// Picking against a plate (top face z = 0) and a 20 mm box resting 10 mm above it.

#include "app/view/scene_picker.h"

#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "haptics/geometry/mesh_builder.h"
#include "support/contact_scenes.h"

namespace voxhap::view {
namespace {

class ScenePickerTest : public ::testing::Test {
protected:
  ScenePickerTest() {
    scene_.objects.push_back(test::plate());
    scene_.objects.push_back(test::meshObject("box", ObjectRole::Dynamic, [](TriangleMesh& m) {
      appendBox(m, test::at(0.0, 0.0, 0.02), glm::dvec3(0.01));  // z from 0.01 to 0.03
    }));
  }
  Scene scene_;
  std::vector<Pose> poses_ = std::vector<Pose>(2);
};

TEST_F(ScenePickerTest, TheFirstObjectAlongTheRayIsPickedWhereItIsMet) {
  const ScenePicker picker(scene_);
  const auto down = picker.pick({0.0, 0.0, 1.0}, {0.0, 0.0, -2.0}, poses_);  // a direction of any length
  ASSERT_TRUE(down);
  EXPECT_EQ(down->object, 1u);                  // the box's top, before the plate
  EXPECT_NEAR(down->pointWorld.z, 0.03, 1e-6);  // Embree works in float
  EXPECT_NEAR(down->distanceM, 0.97, 1e-6);
  const auto beside = picker.pick({0.03, 0.0, 1.0}, {0.0, 0.0, -1.0}, poses_);
  ASSERT_TRUE(beside);
  EXPECT_EQ(beside->object, 0u);
  EXPECT_NEAR(beside->pointWorld.z, 0.0, 1e-6);
  EXPECT_FALSE(picker.pick({0.2, 0.0, 1.0}, {0.0, 0.0, -1.0}, poses_));  // past the plate's edge
}

TEST_F(ScenePickerTest, AMovedObjectIsPickedWhereItIsNow) {
  const ScenePicker picker(scene_);
  poses_[1].position = glm::dvec3(0.03, 0.0, 0.0);  // the box slid 30 mm in x
  poses_[1].orientation = glm::angleAxis(0.4, glm::dvec3(0.0, 0.0, 1.0));
  const auto atOldPlace = picker.pick({0.0, 0.0, 1.0}, {0.0, 0.0, -1.0}, poses_);
  ASSERT_TRUE(atOldPlace);
  EXPECT_EQ(atOldPlace->object, 0u);  // only the plate is there now
  const auto atNewPlace = picker.pick({0.03, 0.0, 1.0}, {0.0, 0.0, -1.0}, poses_);
  ASSERT_TRUE(atNewPlace);
  EXPECT_EQ(atNewPlace->object, 1u);
  EXPECT_NEAR(atNewPlace->pointWorld.z, 0.03, 1e-6);
  EXPECT_THROW(picker.pick({0.0, 0.0, 1.0}, {0.0, 0.0, -1.0}, std::span(poses_).first(1)), Error);
}

}  // namespace
}  // namespace voxhap::view

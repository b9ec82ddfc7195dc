#include "render/proximity_ramp.h"

#include <limits>

#include <gtest/gtest.h>

namespace voxhap::render {
namespace {

constexpr glm::vec4 kBlue{0.1f, 0.2f, 0.9f, 0.5f};
constexpr float kRangeM = 0.005f;

TEST(ProximityRamp, TouchingIsRedAndFarIsThePartsOwnColour) {
  EXPECT_EQ(proximityColour(0.0f, kRangeM, kBlue), glm::vec4(1.0f, 0.0f, 0.0f, 0.5f));
  EXPECT_EQ(proximityColour(-0.001f, kRangeM, kBlue), glm::vec4(1.0f, 0.0f, 0.0f, 0.5f));  // inside
  EXPECT_EQ(proximityColour(std::numeric_limits<float>::infinity(), kRangeM, kBlue), kBlue);
  EXPECT_EQ(proximityColour(std::numeric_limits<float>::quiet_NaN(), kRangeM, kBlue), kBlue);
  EXPECT_EQ(proximityColour(kRangeM, kRangeM, kBlue), kBlue);
}

TEST(ProximityRamp, GoesThroughOrangeAndYellowAndGetsCoolerWithDistance) {
  const glm::vec4 orange = proximityColour(kRangeM / 3.0f, kRangeM, kBlue);
  EXPECT_NEAR(orange.r, 1.0f, 1e-5f);
  EXPECT_NEAR(orange.g, 0.5f, 1e-5f);
  EXPECT_NEAR(orange.b, 0.0f, 1e-5f);
  const glm::vec4 yellow = proximityColour(2.0f * kRangeM / 3.0f, kRangeM, kBlue);
  EXPECT_NEAR(yellow.g, 0.9f, 1e-5f);
  // red falls (or holds) and blue rises (or holds) as the distance grows: never warmer
  float lastRed = 2.0f, lastBlue = -1.0f;
  for (int i = 0; i <= 100; ++i) {
    const glm::vec4 c = proximityColour(kRangeM * float(i) / 100.0f, kRangeM, kBlue);
    EXPECT_LE(c.r, lastRed + 1e-6f);
    EXPECT_GE(c.b, lastBlue - 1e-6f);
    lastRed = c.r;
    lastBlue = c.b;
  }
}

TEST(ProximityRamp, Rgba8RoundsAndClamps) {
  const Rgba8 c = toRgba8(glm::vec4(1.2f, 0.5f, -0.1f, 1.0f));
  EXPECT_EQ(c.r, 255);
  EXPECT_EQ(c.g, 128);
  EXPECT_EQ(c.b, 0);
  EXPECT_EQ(c.a, 255);
}

}  // namespace
}  // namespace voxhap::render

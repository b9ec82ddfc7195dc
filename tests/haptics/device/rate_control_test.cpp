#include "haptics/device/rate_control.h"

#include <cmath>
#include <cstring>
#include <numbers>

#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "support/allocation_counter.h"

namespace voxhap {
namespace {

using Deflection = std::array<double, kAxisCount>;

constexpr double kDtS = 1e-3;

RateControlParams params() {
  RateControlParams p;
  p.deadZone = 0.1;
  p.linearGainMPerS = 0.2;
  p.angularGainRadPerS = 1.5;
  return p;
}

Pose startPose() {
  return Pose{glm::dvec3(1.0, -2.0, 0.5), glm::normalize(quatWxyz(0.9, 0.1, -0.3, 0.2))};
}

TEST(RateControl, DeadZoneGivesNoMotion) {
  RateController control(params(), startPose());
  const Deflection inside{0.1, -0.1, 0.05, -0.09, 0.1, 0.0};
  for (int i = 0; i < 1000; ++i) control.step(inside, kDtS);
  EXPECT_EQ(control.handleWorld().position, startPose().position);
  EXPECT_EQ(control.handleWorld().orientation, glm::normalize(startPose().orientation));
  EXPECT_EQ(control.velocityWorld().linearWorld, glm::dvec3(0.0));
  EXPECT_EQ(control.velocityWorld().angularWorld, glm::dvec3(0.0));
}

TEST(RateControl, ShapingIsContinuousAtTheDeadZoneAndFullAtFullDeflection) {
  RateControlParams p = params();
  EXPECT_EQ(shapeDeflection(0.1, p), 0.0);
  EXPECT_NEAR(shapeDeflection(0.1 + 1e-9, p), 0.0, 1e-8);
  EXPECT_DOUBLE_EQ(shapeDeflection(1.0, p), 1.0);
  EXPECT_DOUBLE_EQ(shapeDeflection(-1.0, p), -1.0);
  EXPECT_DOUBLE_EQ(shapeDeflection(0.55, p), 0.5);
  p.cubicShaping = 1.0;
  EXPECT_DOUBLE_EQ(shapeDeflection(0.55, p), 0.125);
  EXPECT_DOUBLE_EQ(shapeDeflection(1.0, p), 1.0);
  p.cubicShaping = 0.5;
  EXPECT_DOUBLE_EQ(shapeDeflection(-0.55, p), -(0.25 + 0.0625));
  EXPECT_EQ(shapeDeflection(std::nan(""), p), 0.0);
}

TEST(RateControl, FullDeflectionGivesTheGain) {
  RateController control(params(), Pose{});
  const Deflection right{1.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  for (int i = 0; i < 1000; ++i) control.step(right, kDtS);
  EXPECT_NEAR(control.velocityWorld().linearWorld.x, 0.2, 1e-15);
  EXPECT_NEAR(control.handleWorld().position.x, 0.2, 1e-12);  // 1 s at 0.2 m/s
  EXPECT_NEAR(control.handleWorld().position.y, 0.0, 1e-15);

  RateController turning(params(), Pose{});
  const Deflection twist{0.0, 0.0, 0.0, 0.0, -1.0, 0.0};
  for (int i = 0; i < 1000; ++i) turning.step(twist, kDtS);
  EXPECT_NEAR(turning.velocityWorld().angularWorld.y, -1.5, 1e-15);
  const glm::dvec3 turned = rotationVector(turning.handleWorld().orientation);
  EXPECT_NEAR(turned.y, -1.5, 1e-9);  // 1 s at 1.5 rad/s about −y
  EXPECT_EQ(turning.handleWorld().position, glm::dvec3(0.0));
}

TEST(RateControl, ViewToWorldTurnsTheVelocity) {
  RateControlParams p = params();
  p.viewToWorld = quatFromRotationVector(glm::dvec3(0.0, 0.0, std::numbers::pi / 2.0));  // view x → world y
  const HandleVelocity v = pivotVelocityWorld(Deflection{1.0, 0.0, 0.0, 1.0, 0.0, 0.0}, p);
  EXPECT_NEAR(v.linearWorld.x, 0.0, 1e-15);
  EXPECT_NEAR(v.linearWorld.y, 0.2, 1e-15);
  EXPECT_NEAR(v.angularWorld.y, 1.5, 1e-15);
}

TEST(RateControl, RotationIsAboutThePivot) {
  const glm::dvec3 pivotLocal(0.0, 0.0, 2.0);
  RateController control(params(), startPose(), pivotLocal);
  const glm::dvec3 pivotBefore = apply(control.handleWorld(), pivotLocal);
  for (int i = 0; i < 500; ++i) control.step(Deflection{0.0, 0.0, 0.0, 0.7, -0.4, 1.0}, kDtS);
  const glm::dvec3 pivotAfter = apply(control.handleWorld(), pivotLocal);
  EXPECT_NEAR(glm::length(pivotAfter - pivotBefore), 0.0, 1e-12);
  EXPECT_GT(glm::length(control.handleWorld().position - startPose().position), 0.1);
  // the reported velocity is the origin's: ω × (origin − pivot)
  const HandleVelocity& v = control.velocityWorld();
  EXPECT_GT(glm::length(v.linearWorld), 0.0);
  EXPECT_NEAR(glm::dot(v.linearWorld, v.angularWorld), 0.0, 1e-12);
}

TEST(RateControl, RotationStaysOnSO3OverAMillionSteps) {
  RateController control(params(), startPose());
  const Deflection spin{0.0, 0.0, 0.0, 1.0, 1.0, 1.0};
  constexpr int kSteps = 1000000;
  double worstNormError = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    control.step(spin, kDtS);
    worstNormError = std::max(worstNormError, std::abs(glm::length(control.handleWorld().orientation) - 1.0));
  }
  EXPECT_LT(worstNormError, 1e-14);
  // a constant axis: the whole turn is exp(ω·T) applied to the start
  const glm::dvec3 omega = control.velocityWorld().angularWorld;
  const glm::dquat expected =
      quatFromRotationVector(omega * (kSteps * kDtS)) * glm::normalize(startPose().orientation);
  const double error =
      glm::length(rotationVector(control.handleWorld().orientation * glm::conjugate(expected)));
  EXPECT_LT(error, 1e-6);
}

TEST(RateControl, ResetRestartsAtRest) {
  RateController control(params(), Pose{});
  control.step(Deflection{1.0, 1.0, 1.0, 1.0, 1.0, 1.0}, kDtS);
  control.reset(startPose());
  EXPECT_EQ(control.handleWorld().position, startPose().position);
  EXPECT_EQ(control.velocityWorld().linearWorld, glm::dvec3(0.0));
}

TEST(RateControl, NegativeOrNonFiniteStepsDoNotMove) {
  RateController control(params(), startPose());
  const Deflection full{1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
  control.step(full, -1e-3);
  control.step(full, std::nan(""));
  control.step(full, INFINITY);
  EXPECT_EQ(control.handleWorld().position, startPose().position);
}

TEST(RateControl, IsDeterministic) {
  RateController a(params(), startPose(), glm::dvec3(0.1, 0.2, 0.3));
  RateController b(params(), startPose(), glm::dvec3(0.1, 0.2, 0.3));
  for (int i = 0; i < 5000; ++i) {
    const double s = std::sin(i * 0.01);
    const Deflection d{s, -s, 0.5 * s, s * s, -0.3, 0.9 * s};
    a.step(d, kDtS);
    b.step(d, kDtS);
  }
  EXPECT_EQ(std::memcmp(&a.handleWorld(), &b.handleWorld(), sizeof(Pose)), 0);
}

TEST(RateControl, StepAllocatesNothing) {
  RateController control(params(), startPose());
  const test::AllocationCounter counter;
  for (int i = 0; i < 1000; ++i) control.step(Deflection{0.5, 0.0, -0.5, 0.2, 0.0, 1.0}, kDtS);
  EXPECT_EQ(counter.count(), 0u);
}

TEST(RateControl, BadParametersAreRefusedByName) {
  RateControlParams p = params();
  p.deadZone = 1.0;
  EXPECT_THROW(RateController(p, Pose{}), Error);
  p = params();
  p.linearGainMPerS = -1.0;
  try {
    validateRateControlParams(p, "test device");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("test device: rate control linearGainMPerS"), std::string::npos);
  }
  p = params();
  p.viewToWorld = quatWxyz(2.0, 0.0, 0.0, 0.0);
  EXPECT_THROW(validateRateControlParams(p, "x"), Error);
  p = params();
  p.cubicShaping = 1.5;
  EXPECT_THROW(validateRateControlParams(p, "x"), Error);
}

}  // namespace
}  // namespace voxhap

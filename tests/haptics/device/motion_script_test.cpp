#include "haptics/device/motion_script.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <ostream>
#include <string>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "support/gltf_fixtures.h"

namespace voxhap {
namespace {

constexpr double kHalfPi = std::numbers::pi / 2.0;
const glm::dvec3 kZ(0.0, 0.0, 1.0);

/// Angle between two rotations, rad (0 when equal, whatever the quaternions' signs).
double angleBetween(const glm::dquat& a, const glm::dquat& b) {
  return glm::length(rotationVector(a * glm::conjugate(b)));
}

const char* const kGoodScript =
    "# insert the peg\n"
    "\n"
    "0    1 0 0 0        0 0 0\n"
    "   0.5  2 0 0 0   0.1 0 -0.2   # a quaternion of length 2: normalized\n"
    "\t1.5 0.7071067811865476 0 0 0.7071067811865476  0.1\t0.3 -0.2\n"
    "# done\n";

TEST(MotionScript, ParsesPosesSkippingCommentsAndBlankLines) {
  const MotionScript script = parseMotionScript(kGoodScript, "peg.txt");
  ASSERT_EQ(script.keyframes().size(), 3u);
  EXPECT_EQ(script.sourceName(), "peg.txt");
  EXPECT_EQ(script.keyframes()[1].timeS, 0.5);
  EXPECT_EQ(script.keyframes()[1].handleWorld.position, glm::dvec3(0.1, 0.0, -0.2));
  EXPECT_EQ(script.keyframes()[1].handleWorld.orientation.w, 1.0);
  EXPECT_NEAR(angleBetween(script.keyframes()[2].handleWorld.orientation, glm::angleAxis(kHalfPi, kZ)), 0.0,
              1e-15);
  EXPECT_EQ(script.durationS(), 1.5);
}

TEST(MotionScript, AcceptsCrLfLineEndingsAndNoFinalNewline) {
  const MotionScript script = parseMotionScript("0 1 0 0 0 0 0 0\r\n1 1 0 0 0 1 2 3", "win.txt");
  ASSERT_EQ(script.keyframes().size(), 2u);
  EXPECT_EQ(script.keyframes()[1].handleWorld.position, glm::dvec3(1.0, 2.0, 3.0));
}

struct BadScript {
  const char* what;
  const char* text;
  const char* expected;  ///< must appear in the message
};

void PrintTo(const BadScript& bad, std::ostream* os) {
  *os << bad.what;
}

class MotionScriptRejects : public ::testing::TestWithParam<BadScript> {};

TEST_P(MotionScriptRejects, NamingFileAndLine) {
  try {
    parseMotionScript(GetParam().text, "moves.txt");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(GetParam().expected), std::string::npos) << message;
    EXPECT_EQ(message.rfind("moves.txt", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MotionScriptRejects,
    ::testing::Values(
        BadScript{"TooFewFields", "0 1 0 0 0 0 0 0\n1 1 0 0 0 0 0\n", "moves.txt:2: expected 8 numbers"},
        BadScript{"TooManyFields", "# x\n0 1 0 0 0 0 0 0 9\n", "moves.txt:2: expected 8 numbers"},
        BadScript{"NotANumber", "0 1 0 0 0 0 0 0\n\n1 1 0 zero 0 0 0 0\n",
                  "moves.txt:3: field 4 (qy) is not a number: 'zero'"},
        BadScript{"TrailingGarbage", "0 1 0 0 0 0 0 0.5m\n",
                  "moves.txt:1: field 8 (tz) is not a number: '0.5m'"},
        BadScript{"NaN", "0 1 0 0 0 nan 0 0\n", "moves.txt:1: field 6 (tx) is not finite"},
        BadScript{"Infinite", "0 1 0 0 0 0 0 0\n1 1 0 0 0 0 -inf 0\n",
                  "moves.txt:2: field 7 (ty) is not finite"},
        BadScript{"Overflow", "1e999 1 0 0 0 0 0 0\n", "moves.txt:1: field 1 (t) is out of range: '1e999'"},
        BadScript{"RepeatedTime", "0 1 0 0 0 0 0 0\n0.5 1 0 0 0 0 0 0\n0.5 1 0 0 0 0 0 0\n",
                  "moves.txt:3: time 0.5 s is not after 0.5 s at line 2"},
        BadScript{"DecreasingTime", "1 1 0 0 0 0 0 0\n# back\n0.5 1 0 0 0 0 0 0\n",
                  "moves.txt:3: time 0.5 s is not after 1 s at line 1"},
        BadScript{"NegativeStart", "-0.1 1 0 0 0 0 0 0\n", "moves.txt:1: time -0.1 s is negative"},
        BadScript{"ZeroQuaternion", "0 1 0 0 0 0 0 0\n1 0 0 0 0 1 1 1\n", "moves.txt:2: quaternion is zero"},
        BadScript{"Empty", "", "moves.txt: motion script has no poses"},
        BadScript{"OnlyComments", "# nothing\n\n   \n", "moves.txt: motion script has no poses"}),
    [](const ::testing::TestParamInfo<BadScript>& info) { return std::string(info.param.what); });

/// Identity at t = 1 s, a quarter turn about z and (2, −4, 6) m at t = 3 s, back at 4 s.
MotionScript turnScript() {
  return parseMotionScript(
      "1 1 0 0 0 0 0 0\n"
      "3 0.7071067811865476 0 0 0.7071067811865476 2 -4 6\n"
      "4 1 0 0 0 0 0 0\n",
      "turn.txt");
}

TEST(MotionScript, SampleIsExactAtKeyframes) {
  const MotionScript script = turnScript();
  for (const MotionKeyframe& k : script.keyframes()) {
    const Pose p = script.sample(k.timeS);
    EXPECT_EQ(p.position, k.handleWorld.position);
    EXPECT_EQ(p.orientation, k.handleWorld.orientation);
  }
}

TEST(MotionScript, SampleSlerpsRotationAndLerpsTranslationBetweenKeyframes) {
  const MotionScript script = turnScript();
  const Pose mid = script.sample(2.0);
  EXPECT_NEAR(glm::length(mid.position - glm::dvec3(1.0, -2.0, 3.0)), 0.0, 1e-15);
  EXPECT_NEAR(angleBetween(mid.orientation, glm::angleAxis(kHalfPi / 2.0, kZ)), 0.0, 1e-15);
  const Pose quarter = script.sample(1.5);
  EXPECT_NEAR(glm::length(quarter.position - glm::dvec3(0.5, -1.0, 1.5)), 0.0, 1e-15);
  // slerp turns at a constant rate, unlike normalized lerp
  EXPECT_NEAR(angleBetween(quarter.orientation, glm::angleAxis(kHalfPi / 4.0, kZ)), 0.0, 1e-15);
}

TEST(MotionScript, SampleTakesTheShortArcWhateverTheQuaternionSigns) {
  // 170° then 190° written as −(190°): the short way is 20° through 180°
  const glm::dquat a = glm::angleAxis(170.0 * std::numbers::pi / 180.0, kZ);
  const glm::dquat b = -glm::angleAxis(190.0 * std::numbers::pi / 180.0, kZ);
  const MotionScript script({{0.0, Pose{glm::dvec3(0.0), a}}, {1.0, Pose{glm::dvec3(0.0), b}}}, "signs");
  EXPECT_NEAR(angleBetween(script.sample(0.5).orientation, glm::angleAxis(std::numbers::pi, kZ)), 0.0, 1e-14);
}

TEST(MotionScript, SampleHoldsTheEndPosesOutsideTheScript) {
  const MotionScript script = turnScript();
  const auto& k = script.keyframes();
  EXPECT_EQ(script.sample(0.0).position, k.front().handleWorld.position);
  EXPECT_EQ(script.sample(-5.0).orientation, k.front().handleWorld.orientation);
  EXPECT_EQ(script.sample(std::numeric_limits<double>::quiet_NaN()).position, k.front().handleWorld.position);
  EXPECT_EQ(script.sample(100.0).position, k.back().handleWorld.position);
  EXPECT_EQ(script.sample(std::numeric_limits<double>::infinity()).position, k.back().handleWorld.position);
}

TEST(MotionScript, DurationIsTheTimeOfTheLastPose) {
  EXPECT_EQ(turnScript().durationS(), 4.0);
  EXPECT_EQ(parseMotionScript("0.25 1 0 0 0 0 0 0\n", "one.txt").durationS(), 0.25);
}

TEST(MotionScript, KeyframeConstructorValidatesLikeTheParser) {
  EXPECT_THROW(MotionScript({}, "none"), Error);
  try {
    MotionScript({{0.0, Pose{}}, {0.0, Pose{}}}, "twice");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("twice: keyframe 2: time 0 s is not after 0 s at keyframe 1"),
              std::string::npos)
        << e.what();
  }
}

TEST(MotionScript, LoadsFromFileAndNamesMissingFiles) {
  const test::TempDir dir;
  const std::filesystem::path file = dir / "peg.txt";
  std::ofstream(file) << kGoodScript;
  EXPECT_EQ(loadMotionScript(file).keyframes().size(), 3u);
  EXPECT_EQ(loadMotionScript(file).sourceName(), file.string());
  try {
    loadMotionScript(dir / "absent.txt");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("absent.txt: no such file"), std::string::npos) << e.what();
  }
  EXPECT_THROW(loadMotionScript(dir.path()), Error);  // a directory
}

}  // namespace
}  // namespace voxhap

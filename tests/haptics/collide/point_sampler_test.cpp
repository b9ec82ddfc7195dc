// Point tests eight at a time (AVX2) against one at a time: the same contacts, bit for
// bit, for the ball in its socket at many poses, for every word width, for ranges that do
// not fill the last eight, and for points on voxel boundaries, outside the grid, far away
// or not numbers; and the scalar floor of voxel coordinates against std::floor.
#include "haptics/collide/point_sampler.h"

#include <climits>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "haptics/collide/contact_params.h"
#include "haptics/collide/point_sampler_avx2.h"
#include "haptics/scene/builtin/builtin_scenes.h"
#include "haptics/sim/scene_model.h"

namespace voxhap {
namespace {

constexpr double kVoxelM = 0.0015;

Voxmap socketVoxmap(int bitsPerField) {
  const Scene scene = makeBallAndSocket();
  VoxelizeOptions options;
  options.voxelSizeM = kVoxelM;
  options.encoding = VoxelEncoding::forBits(bitsPerField);
  const SceneObject* socket[] = {scene.find("socket")};
  return voxelizeObjects(socket, options, {});
}

Pointshell ballShell() {
  PointshellOptions options;
  options.pointSpacingM = kVoxelM;
  options.displacementM = -0.5 * kVoxelM;
  return pointshellOf(*makeBallAndSocket().find("ball"), options, {});
}

/// Contacts of points [first, last) by `path`: values 1 … `maxValue`.
std::vector<PointContact> contactsBy(PointTestPath path, const Pointshell& shell, const Voxmap& voxmap,
                                     const VoxelTransform& transform, std::uint32_t first, std::uint32_t last,
                                     std::uint8_t maxValue = kDefaultForceLayer) {
  std::vector<PointContact> contacts(last - first);
  const auto shifts = fieldShiftsByFeature(true, voxmap.encoding());
  contacts.resize(
      samplePointsOn(path, shell, voxmap, transform, shifts, maxValue, first, last, contacts.data()));
  return contacts;
}

/// Whether both paths write the same contacts; says where they part when not.
::testing::AssertionResult sameContacts(const Pointshell& shell, const Voxmap& voxmap,
                                        const VoxelTransform& transform, std::uint32_t first,
                                        std::uint32_t last, std::uint8_t maxValue = kDefaultForceLayer) {
  const auto scalar = contactsBy(PointTestPath::Scalar, shell, voxmap, transform, first, last, maxValue);
  const auto avx2 = contactsBy(PointTestPath::Avx2, shell, voxmap, transform, first, last, maxValue);
  if (scalar.size() != avx2.size())
    return ::testing::AssertionFailure()
           << scalar.size() << " contacts one at a time, " << avx2.size() << " eight at a time";
  for (std::size_t k = 0; k < scalar.size(); ++k) {
    const PointContact& a = scalar[k];
    const PointContact& b = avx2[k];
    if (a.point != b.point || a.ijkVoxel != b.ijkVoxel || a.value != b.value)
      return ::testing::AssertionFailure()
             << "contact " << k << ": point " << a.point << " voxel (" << a.ijkVoxel.x << ", " << a.ijkVoxel.y
             << ", " << a.ijkVoxel.z << ") value " << int(a.value) << " one at a time; point " << b.point
             << " voxel (" << b.ijkVoxel.x << ", " << b.ijkVoxel.y << ", " << b.ijkVoxel.z << ") value "
             << int(b.value) << " eight at a time";
  }
  return ::testing::AssertionSuccess();
}

class PointSamplerAvx2 : public ::testing::Test {
protected:
  void SetUp() override {
    if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2";
  }
};

TEST_F(PointSamplerAvx2, FindsTheContactsOfTheScalarLoopForTheBallInItsSocketAtEveryWordWidth) {
  const Pointshell shell = ballShell();
  const auto points = static_cast<std::uint32_t>(shell.size());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const int bits : {2, 4, 8}) {
    const Voxmap voxmap = socketVoxmap(bits);
    ASSERT_EQ(pointTestPathFor(voxmap), PointTestPath::Avx2);
    std::size_t contacts = 0;
    for (int pose = 0; pose < 40; ++pose) {
      // turned anywhere, moved up to 2 voxels about the seat; every tenth pose half out of the grid
      const glm::dvec3 axis = glm::normalize(glm::dvec3(unit(random), unit(random), unit(random)) + 1e-3);
      const double reachM = pose % 10 == 9 ? 0.04 : 2.0 * kVoxelM;
      const Pose shellToSocket{glm::dvec3(unit(random), unit(random), unit(random)) * reachM,
                               glm::angleAxis(3.2 * unit(random), axis)};
      const VoxelTransform transform = VoxelTransform::make(shellToSocket, voxmap.grid());
      ASSERT_TRUE(sameContacts(shell, voxmap, transform, 0, points)) << bits << " bits, pose " << pose;
      const auto first = static_cast<std::uint32_t>(pose * 37 % 101);
      ASSERT_TRUE(sameContacts(shell, voxmap, transform, first, points - first % 7))
          << bits << " bits, pose " << pose;
      contacts += contactsBy(PointTestPath::Avx2, shell, voxmap, transform, 0, points).size();
    }
    // the poses touch: a good share of the points are contacts, and not all
    EXPECT_GT(contacts, 40u * points / 10) << bits << " bits";
    EXPECT_LT(contacts, 40u * points) << bits << " bits";
  }
}

TEST_F(PointSamplerAvx2, ReadsPointsOnVoxelBoundariesOutsideTheGridAndNotNumbersAsTheScalarLoop) {
  const Voxmap voxmap = socketVoxmap(4);
  const glm::dvec3 originM = voxmap.grid().originLocal;
  const glm::dvec3 extentM = glm::dvec3(voxmap.grid().dimsVoxels()) * kVoxelM;
  Pointshell shell;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  // on voxel corners, a hair either side of them, and at the grid's faces
  for (int i = -2; i <= 40; ++i) {
    for (const double hair : {0.0, -1e-7, 1e-7}) {
      const glm::dvec3 corner = originM + glm::dvec3(i, i * 7 % 41, i * 13 % 43) * kVoxelM * 3.0 + hair;
      shell.positionsLocal.push_back(glm::vec3(corner));
    }
  }
  shell.positionsLocal.push_back(glm::vec3(originM));
  shell.positionsLocal.push_back(glm::vec3(originM + extentM));
  shell.positionsLocal.push_back(glm::vec3(originM + extentM - 1e-6));
  shell.positionsLocal.push_back(glm::vec3(-0.0f));
  shell.positionsLocal.push_back(glm::vec3(1e30f, 0.0f, 0.0f));
  shell.positionsLocal.push_back(glm::vec3(0.0f, -1e30f, 0.0f));
  shell.positionsLocal.push_back(glm::vec3(nan, 0.0f, 0.0f));
  shell.positionsLocal.push_back(glm::vec3(0.0f, inf, -inf));
  for (std::size_t i = 0; i < shell.positionsLocal.size(); ++i)
    shell.features.push_back(static_cast<PointFeature>(i % 3));
  const auto points = static_cast<std::uint32_t>(shell.size());
  for (const Pose& pose : {Pose{}, Pose{glm::dvec3(0.0), glm::angleAxis(0.3, glm::dvec3(0.0, 0.0, 1.0))}}) {
    const VoxelTransform transform = VoxelTransform::make(pose, voxmap.grid());
    EXPECT_TRUE(sameContacts(shell, voxmap, transform, 0, points));
    EXPECT_FALSE(contactsBy(PointTestPath::Scalar, shell, voxmap, transform, 0, points).empty());
  }
}

TEST_F(PointSamplerAvx2, RoundsAsTheScalarLoopForPointsWithinAFewFloatStepsOfAVoxelBoundary) {
  // each point's voxel coordinate lies on a boundary before the point is rounded to float:
  // the rounding of each multiply and add decides its voxel, so a sum taken in another
  // order or fused would put some in the voxel beside
  const Voxmap voxmap = socketVoxmap(4);
  const Pose turned{glm::dvec3(0.002, -0.001, 0.0005),
                    glm::angleAxis(0.3, glm::normalize(glm::dvec3(1, 2, 3)))};
  const VoxelTransform transform = VoxelTransform::make(turned, voxmap.grid());
  const glm::dmat3 voxelsOfLocal = glm::dmat3(transform.rotationScaled);
  const glm::dmat3 localOfVoxels = glm::inverse(voxelsOfLocal);
  const glm::dvec3 dims(voxmap.grid().dimsVoxels());
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Pointshell shell;
  for (int n = 0; n < 30000; ++n) {
    glm::dvec3 voxel = dims * glm::dvec3(unit(random), unit(random), unit(random));
    voxel[n % 3] = std::round(voxel[n % 3]);
    shell.positionsLocal.push_back(glm::vec3(localOfVoxels * (voxel - glm::dvec3(transform.offset))));
    shell.features.push_back(static_cast<PointFeature>(n % 3));
  }
  const auto points = static_cast<std::uint32_t>(shell.size());
  // every voxel with a distance recorded: far more than the force layer
  const std::uint8_t anyValue = voxmap.encoding().maxValue();
  EXPECT_TRUE(sameContacts(shell, voxmap, transform, 0, points, anyValue));
  EXPECT_GT(contactsBy(PointTestPath::Scalar, shell, voxmap, transform, 0, points, anyValue).size(),
            points / 10);
}

TEST_F(PointSamplerAvx2, ReadsTheWordsOfVoxelsAsVoxmapWordInsideAndOutsideTheGrid) {
  for (const int bits : {2, 4, 8}) {
    const Voxmap voxmap = socketVoxmap(bits);
    const glm::ivec3 dims = voxmap.grid().dimsVoxels();
    std::mt19937 random(5);
    std::vector<glm::ivec3> voxels;
    for (int n = 0; n < 4000; ++n) {
      // a tenth up to a grid's size outside it, on any side
      const int reach = n % 10 == 0 ? 3 : 1;
      auto along = [&](int d) {
        return std::uniform_int_distribution<int>(-(reach - 1) * d, reach * d - 1)(random);
      };
      voxels.push_back({along(dims.x), along(dims.y), along(dims.z)});
    }
    std::vector<VoxelWord> words(voxels.size());
    voxelWordsAvx2(voxmap, voxels.data(), voxels.size(), words.data());
    std::size_t stored = 0;
    for (std::size_t n = 0; n < voxels.size(); ++n) {
      ASSERT_EQ(words[n], voxmap.word(voxels[n])) << bits << " bits, voxel " << n;
      stored += words[n] != 0 ? 1 : 0;
    }
    EXPECT_GT(stored, voxels.size() / 20) << bits << " bits";
  }
}

TEST(PointSampler, TakesTheScalarPathOnAPagedVoxmap) {
  const Voxmap voxmap = socketVoxmap(4);
  // as a cache file pages it: every mixed chunk missing until a pager brings it in
  std::vector<std::uint32_t> chunks(voxmap.chunkEntries().begin(), voxmap.chunkEntries().end());
  for (std::uint32_t& entry : chunks)
    if (!(entry & Voxmap::kUniform)) entry = Voxmap::kUniform | Voxmap::kMissingWord;
  const Voxmap paged = Voxmap::paged(
      voxmap.grid(), voxmap.encoding(), {voxmap.hyperEntries().begin(), voxmap.hyperEntries().end()},
      std::move(chunks), 4, {voxmap.chunkDistances().begin(), voxmap.chunkDistances().end()});
  ASSERT_TRUE(paged.isPaged());
  EXPECT_EQ(pointTestPathFor(paged), PointTestPath::Scalar);
  EXPECT_EQ(pointTestPathFor(voxmap), cpuHasAvx2() ? PointTestPath::Avx2 : PointTestPath::Scalar);
}

/// floor(v) where it is an int, else INT_MIN: what voxelOf promises.
int flooredOrIntMin(float v) {
  const double floored = std::floor(static_cast<double>(v));
  return std::isnan(floored) || floored < INT_MIN || floored > INT_MAX ? INT_MIN : static_cast<int>(floored);
}

TEST(PointSampler, FloorsEveryKindOfFloatAsFloorDoesAndGivesIntMinOutsideIntsRange) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  std::vector<float> values = {0.0f,
                               -0.0f,
                               0.5f,
                               -0.5f,
                               1.0f,
                               -1.0f,
                               0.99999994f,
                               -0.99999994f,
                               1e-45f,
                               -1e-45f,
                               16777215.0f,
                               -16777215.0f,
                               16777216.0f,
                               -16777216.0f,
                               8388607.5f,
                               -8388607.5f,
                               2147483520.0f,
                               -2147483520.0f,
                               2147483648.0f,
                               -2147483648.0f,
                               -2147483904.0f,
                               3e9f,
                               -3e9f,
                               1e30f,
                               -1e30f,
                               kInf,
                               -kInf,
                               std::numeric_limits<float>::quiet_NaN(),
                               -std::numeric_limits<float>::quiet_NaN()};
  std::mt19937 random(13);
  std::uniform_real_distribution<float> within(-4096.0f, 4096.0f);
  for (int i = 0; i < 100000; ++i) {
    const float v = within(random);
    values.push_back(v);
    values.push_back(std::nextafter(std::round(v), kInf));
    values.push_back(std::nextafter(std::round(v), -kInf));
  }
  for (const float v : values) {
    const glm::ivec3 ijk = voxelOf(glm::vec3(v, -v, v * 0.5f));
    EXPECT_EQ(ijk.x, flooredOrIntMin(v)) << v;
    EXPECT_EQ(ijk.y, flooredOrIntMin(-v)) << -v;
    EXPECT_EQ(ijk.z, flooredOrIntMin(v * 0.5f)) << v * 0.5f;
  }
}

}  // namespace
}  // namespace voxhap

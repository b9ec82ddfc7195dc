#include "haptics/voxel/chunk_distance.h"

#include <algorithm>
#include <cstdlib>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace voxhap {
namespace {

std::size_t indexOf(const glm::ivec3& p, const glm::ivec3& dims) {
  return static_cast<std::size_t>(p.x + dims.x * (p.y + dims.y * p.z));
}

/// The definition, by brute force: min over sources of max(|dx|, |dy|, |dz|), capped.
std::vector<std::uint8_t> bruteForce(const std::vector<std::uint8_t>& sources, const glm::ivec3& dims) {
  std::vector<glm::ivec3> points;
  for (int z = 0; z < dims.z; ++z) {
    for (int y = 0; y < dims.y; ++y) {
      for (int x = 0; x < dims.x; ++x) {
        if (sources[indexOf({x, y, z}, dims)] == 0) points.emplace_back(x, y, z);
      }
    }
  }
  std::vector<std::uint8_t> out(sources.size(), kChunkDistanceCap);
  for (int z = 0; z < dims.z; ++z) {
    for (int y = 0; y < dims.y; ++y) {
      for (int x = 0; x < dims.x; ++x) {
        int best = kChunkDistanceCap;
        for (const glm::ivec3& p : points) {
          best = std::min(best, std::max({std::abs(p.x - x), std::abs(p.y - y), std::abs(p.z - z)}));
        }
        out[indexOf({x, y, z}, dims)] = static_cast<std::uint8_t>(best);
      }
    }
  }
  return out;
}

TEST(ChunkDistance, MatchesTheBruteForceChessboardDistanceOnRandomSources) {
  std::mt19937 random(12345);
  for (int trial = 0; trial < 40; ++trial) {
    // small grids with dense sources, then larger ones with sparse sources
    const bool large = trial >= 30;
    std::uniform_int_distribution<int> side(1, large ? 40 : 12);
    const glm::ivec3 dims(side(random), side(random), side(random));
    const std::size_t n = static_cast<std::size_t>(dims.x * dims.y * dims.z);
    std::bernoulli_distribution isSource(large ? 0.0002 * (trial % 5 + 1) : 0.02 * (trial % 6));
    std::vector<std::uint8_t> field(n);
    for (std::uint8_t& v : field) v = isSource(random) ? 0 : 7;
    const std::vector<std::uint8_t> expected = bruteForce(field, dims);
    chessboardChunkTransform(field, dims);
    ASSERT_EQ(field, expected) << "trial " << trial << " dims " << dims.x << " " << dims.y << " " << dims.z;
  }
}

TEST(ChunkDistance, SameWhateverTheThreadCount) {
  // larger than a batch of lines in every direction, sources sparse enough for long distances
  const glm::ivec3 dims(150, 97, 70);
  std::mt19937 random(7);
  std::bernoulli_distribution isSource(0.0003);
  std::vector<std::uint8_t> one(static_cast<std::size_t>(dims.x * dims.y * dims.z));
  for (std::uint8_t& v : one) v = isSource(random) ? 0 : 1;
  std::vector<std::uint8_t> two = one;
  chessboardChunkTransform(one, dims, 1);
  chessboardChunkTransform(two, dims, 2);
  EXPECT_EQ(one, two);
  EXPECT_GT(*std::max_element(one.begin(), one.end()), 20);
}

TEST(ChunkDistance, LongRowsAreCappedAt255) {
  const glm::ivec3 dims(600, 2, 1);
  std::vector<std::uint8_t> field(static_cast<std::size_t>(dims.x * dims.y * dims.z), 1);
  field[0] = 0;
  chessboardChunkTransform(field, dims);
  EXPECT_EQ(field[indexOf({200, 1, 0}, dims)], 200);
  EXPECT_EQ(field[indexOf({255, 0, 0}, dims)], 255);
  EXPECT_EQ(field[indexOf({599, 1, 0}, dims)], 255);
}

TEST(ChunkDistance, NoSourceMeansCappedEverywhere) {
  const glm::ivec3 dims(5, 4, 3);
  std::vector<std::uint8_t> field(60, 3);
  chessboardChunkTransform(field, dims);
  for (std::uint8_t v : field) EXPECT_EQ(v, kChunkDistanceCap);
}

}  // namespace
}  // namespace voxhap

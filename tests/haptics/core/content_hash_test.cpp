#include "haptics/core/content_hash.h"

#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

namespace voxhap {
namespace {

std::vector<unsigned char> randomBytes(std::size_t n, unsigned seed) {
  std::mt19937 random(seed);
  std::vector<unsigned char> bytes(n);
  for (unsigned char& b : bytes) b = static_cast<unsigned char>(random());
  return bytes;
}

Digest128 hashOf(const std::vector<unsigned char>& bytes) {
  ContentHash h;
  h.update(bytes.data(), bytes.size());
  return h.digest();
}

TEST(ContentHash, DependsOnTheBytesNotOnHowTheyWereSplit) {
  const std::vector<unsigned char> bytes = randomBytes(1000, 1);
  const Digest128 whole = hashOf(bytes);
  for (std::size_t piece : {1u, 3u, 7u, 31u, 32u, 33u, 100u}) {
    ContentHash h;
    for (std::size_t at = 0; at < bytes.size(); at += piece) {
      h.update(bytes.data() + at, std::min(piece, bytes.size() - at));
    }
    EXPECT_EQ(h.digest(), whole) << piece;
  }
}

TEST(ContentHash, EveryFlippedBitAndEveryLengthGivesADifferentDigest) {
  const std::vector<unsigned char> bytes = randomBytes(67, 2);
  std::set<std::pair<std::uint64_t, std::uint64_t>> seen;
  for (std::size_t n = 0; n <= bytes.size(); ++n) {
    const Digest128 d = hashOf({bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n)});
    EXPECT_TRUE(seen.insert({d.lo, d.hi}).second) << "prefix " << n;
  }
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      std::vector<unsigned char> flipped = bytes;
      flipped[i] = static_cast<unsigned char>(flipped[i] ^ (1u << bit));
      const Digest128 d = hashOf(flipped);
      EXPECT_TRUE(seen.insert({d.lo, d.hi}).second) << i << " " << bit;
    }
  }
  // zeros of different lengths differ too
  EXPECT_NE(hashOf(std::vector<unsigned char>(64, 0)), hashOf(std::vector<unsigned char>(65, 0)));
}

TEST(ContentHash, IsXxh3OneTwentyEight) {
  // the published XXH3-128 of no bytes (seed 0), from the xxHash reference
  EXPECT_EQ(ContentHash().digest().hex(), "99aa06d3014798d86001c324468d497f");
}

TEST(ContentHash, AMovedHashGoesOnWhereItWas) {
  const std::vector<unsigned char> bytes = randomBytes(100, 3);
  ContentHash h;
  h.update(bytes.data(), 40);
  ContentHash moved(std::move(h));
  moved.update(bytes.data() + 40, 60);
  EXPECT_EQ(moved.digest(), hashOf(bytes));
}

TEST(ContentHash, HexIsThirtyTwoDigitsHighLaneFirst) {
  const Digest128 d{0x0123456789abcdefull, 0xfedcba9876543210ull};
  EXPECT_EQ(d.hex(), "fedcba98765432100123456789abcdef");
}

}  // namespace
}  // namespace voxhap

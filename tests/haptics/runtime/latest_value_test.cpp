#include "haptics/runtime/latest_value.h"

#include <atomic>
#include <cstdint>
#include <thread>

#include <gtest/gtest.h>

#include "support/allocation_counter.h"
#include "support/sanitizers.h"

namespace voxhap {
namespace {

/// A device sample of six words, every one a function of the sample's number: a value put
/// together from two writes would show.
struct Sample {
  std::uint64_t number = 0;
  double xM = 0.0;
  double yM = 0.0;
  double zM = 0.0;
  std::uint64_t buttons = 0;
  std::uint64_t check = 0;
};

Sample sampleOf(std::uint64_t n) {
  const double x = static_cast<double>(n);
  return {n, x, -2.0 * x, 0.5 * x, n % 7, n * 0x9E3779B97F4A7C15ull};
}

bool whole(const Sample& s) {
  const Sample expected = sampleOf(s.number);
  return s.xM == expected.xM && s.yM == expected.yM && s.zM == expected.zM && s.buttons == expected.buttons &&
         s.check == expected.check;
}

TEST(LatestValue, ReadsOnlyWhatIsNewerThanItsVersionAndTheNewestWins) {
  LatestValue<Sample> mailbox;
  std::uint64_t version = 0;
  Sample out = sampleOf(1000);
  EXPECT_EQ(mailbox.version(), 0u);
  EXPECT_FALSE(mailbox.readNewer(version, out)) << "an empty mailbox gave a value";
  EXPECT_EQ(out.number, 1000u);
  mailbox.publish(sampleOf(1));
  ASSERT_TRUE(mailbox.readNewer(version, out));
  EXPECT_EQ(version, 1u);
  EXPECT_EQ(out.number, 1u);
  EXPECT_FALSE(mailbox.readNewer(version, out)) << "the same value read as new twice";
  mailbox.publish(sampleOf(2));
  mailbox.publish(sampleOf(3));
  ASSERT_TRUE(mailbox.readNewer(version, out));
  EXPECT_EQ(version, 3u);
  EXPECT_EQ(out.number, 3u);
  EXPECT_TRUE(whole(out));
  // another reader, with its own version, reads the newest too
  std::uint64_t otherVersion = 0;
  Sample other;
  ASSERT_TRUE(mailbox.readNewer(otherVersion, other));
  EXPECT_EQ(otherVersion, 3u);
}

TEST(LatestValue, PublishAndReadAllocateNothing) {
  LatestValue<Sample> mailbox;
  const test::AllocationCounter allocations;
  std::uint64_t version = 0;
  Sample out;
  for (std::uint64_t i = 1; i <= 100; ++i) {
    mailbox.publish(sampleOf(i));
    mailbox.readNewer(version, out);
  }
  EXPECT_EQ(allocations.count(), 0u);
}

TEST(LatestValue, AReaderRacingTheWriterSeesOnlyWholeValuesEachNewerThanTheLast) {
  // the writer publishes until the reader has read enough values (or at most maxSamples),
  // with a short pause after each, as a device thread waits for its next sample
  const std::uint64_t maxSamples = test::kThreadSanitizer ? 50'000 : 500'000;
  constexpr std::uint64_t kEnoughReads = 5'000;
  LatestValue<Sample> mailbox;
  std::atomic<bool> enough{false};
  std::atomic<bool> writerDone{false};
  std::thread writer([&] {
    for (std::uint64_t n = 1; n <= maxSamples && !enough.load(std::memory_order_relaxed); ++n) {
      mailbox.publish(sampleOf(n));
      for (int spin = 0; spin < 200 && !enough.load(std::memory_order_relaxed); ++spin) {
      }
    }
    writerDone.store(true, std::memory_order_release);
  });
  std::uint64_t version = 0;
  std::uint64_t reads = 0;
  std::uint64_t torn = 0;
  std::uint64_t wrongVersion = 0;
  std::uint64_t notNewer = 0;
  const auto read = [&] {
    const std::uint64_t before = version;
    Sample s;
    if (!mailbox.readNewer(version, s)) return;
    ++reads;
    torn += whole(s) ? 0 : 1;
    wrongVersion += s.number == version ? 0 : 1;  // the n-th publish has version n
    notNewer += version > before ? 0 : 1;
  };
  while (!writerDone.load(std::memory_order_acquire)) {
    read();
    if (reads == kEnoughReads) enough.store(true, std::memory_order_relaxed);
  }
  writer.join();
  read();  // no write overlaps this one: it gets the last value unless it had it
  EXPECT_EQ(torn, 0u);
  EXPECT_EQ(wrongVersion, 0u);
  EXPECT_EQ(notNewer, 0u);
  EXPECT_EQ(version, mailbox.version()) << "the last value never reached the reader";
  RecordProperty("reads", static_cast<int>(reads));
  RecordProperty("samples", static_cast<int>(mailbox.version()));
}

}  // namespace
}  // namespace voxhap

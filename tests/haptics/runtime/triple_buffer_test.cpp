#include "haptics/runtime/triple_buffer.h"

#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "support/allocation_counter.h"
#include "support/sanitizers.h"

namespace voxhap {
namespace {

/// A frame's snapshot: its number and every object's figure, all equal to the number, so
/// that a snapshot caught half written would show.
struct Snapshot {
  std::uint64_t frame = 0;
  std::vector<double> poses;
};

Snapshot sized(std::size_t objects) {
  Snapshot s;
  s.poses.assign(objects, 0.0);
  return s;
}

void fill(Snapshot& s, std::uint64_t frame) {
  s.frame = frame;
  for (double& p : s.poses) p = static_cast<double>(frame);
}

bool complete(const Snapshot& s) {
  for (const double p : s.poses) {
    if (p != static_cast<double>(s.frame)) return false;
  }
  return true;
}

TEST(TripleBuffer, TheReaderTakesTheNewestPublishedSnapshotOnce) {
  TripleBuffer<Snapshot> buffer(sized(3));
  EXPECT_FALSE(buffer.update()) << "nothing published yet";
  EXPECT_EQ(buffer.readBuffer().frame, 0u);
  EXPECT_EQ(buffer.readBuffer().poses.size(), 3u);
  fill(buffer.writeBuffer(), 1);
  buffer.publish();
  ASSERT_TRUE(buffer.update());
  EXPECT_EQ(buffer.readBuffer().frame, 1u);
  EXPECT_FALSE(buffer.update()) << "the same snapshot taken twice";
  EXPECT_EQ(buffer.readBuffer().frame, 1u);
  // two frames before the reader looks: it gets the second, the first is dropped
  fill(buffer.writeBuffer(), 2);
  buffer.publish();
  fill(buffer.writeBuffer(), 3);
  buffer.publish();
  ASSERT_TRUE(buffer.update());
  EXPECT_EQ(buffer.readBuffer().frame, 3u);
  EXPECT_TRUE(complete(buffer.readBuffer()));
  // the writer never writes into the reader's buffer
  for (std::uint64_t f = 4; f < 10; ++f) {
    fill(buffer.writeBuffer(), f);
    EXPECT_NE(&buffer.writeBuffer(), &buffer.readBuffer());
    buffer.publish();
  }
  EXPECT_EQ(buffer.readBuffer().frame, 3u);
}

TEST(TripleBuffer, AReaderRacingTheWriterSeesOnlyCompleteSnapshotsInIncreasingOrder) {
  // the writer publishes until the reader has taken enough snapshots (or at most maxFrames)
  const std::uint64_t maxFrames = test::kThreadSanitizer ? 200'000 : 2'000'000;
  constexpr std::uint64_t kEnoughUpdates = 5'000;
  TripleBuffer<Snapshot> buffer(sized(256));
  std::atomic<bool> enough{false};
  std::atomic<bool> writerDone{false};
  std::uint64_t lastPublished = 0;
  std::uint64_t writerAllocations = 0;
  std::thread writer([&] {
    const test::AllocationCounter allocations;
    for (std::uint64_t f = 1; f <= maxFrames && !enough.load(std::memory_order_relaxed); ++f) {
      fill(buffer.writeBuffer(), f);
      buffer.publish();
      lastPublished = f;
    }
    writerAllocations = allocations.count();
    writerDone.store(true, std::memory_order_release);
  });
  const test::AllocationCounter readerAllocations;
  std::uint64_t last = 0;
  std::uint64_t updates = 0;
  std::uint64_t incomplete = 0;
  std::uint64_t notNewer = 0;
  const auto take = [&] {
    const Snapshot& s = buffer.readBuffer();
    ++updates;
    incomplete += complete(s) && s.poses.size() == 256 ? 0 : 1;
    notNewer += s.frame > last ? 0 : 1;
    last = s.frame;
  };
  while (!writerDone.load(std::memory_order_acquire)) {
    if (buffer.update()) take();
    if (updates == kEnoughUpdates) enough.store(true, std::memory_order_relaxed);
  }
  writer.join();
  if (buffer.update()) take();  // the last snapshot, if not taken yet
  EXPECT_EQ(incomplete, 0u);
  EXPECT_EQ(notNewer, 0u);
  EXPECT_EQ(last, lastPublished) << "the newest snapshot never reached the reader";
  EXPECT_EQ(writerAllocations, 0u);
  EXPECT_EQ(readerAllocations.count(), 0u);
  RecordProperty("updates", static_cast<int>(updates));
  RecordProperty("frames", static_cast<int>(lastPublished));
}

}  // namespace
}  // namespace voxhap

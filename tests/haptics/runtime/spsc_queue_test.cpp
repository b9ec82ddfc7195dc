#include "haptics/runtime/spsc_queue.h"

#include <cstdint>
#include <thread>

#include <gtest/gtest.h>

#include "support/allocation_counter.h"
#include "support/sanitizers.h"

namespace voxhap {
namespace {

/// A command whose two words must agree: a torn copy would show.
struct Command {
  std::uint64_t sequence = 0;
  std::uint64_t check = 0;
};

Command commandOf(std::uint64_t sequence) {
  return {sequence, ~sequence * 0x9E3779B97F4A7C15ull};
}

TEST(SpscQueue, GivesItemsFirstInFirstOutAndRefusesWhenFull) {
  SpscQueue<Command> queue(4);
  EXPECT_EQ(queue.capacity(), 4u);
  Command out;
  EXPECT_FALSE(queue.tryPop(out));
  // around the ring several times, each time filled to the last slot
  std::uint64_t pushed = 0;
  std::uint64_t popped = 0;
  for (int round = 0; round < 5; ++round) {
    for (int i = 0; i < 4; ++i) ASSERT_TRUE(queue.tryPush(commandOf(pushed++)));
    EXPECT_FALSE(queue.tryPush(commandOf(99))) << "a full queue took an item";
    for (int i = 0; i < 3; ++i) {
      ASSERT_TRUE(queue.tryPop(out));
      EXPECT_EQ(out.sequence, popped++);
    }
    ASSERT_TRUE(queue.tryPush(commandOf(pushed++)));
    for (int i = 0; i < 2; ++i) {
      ASSERT_TRUE(queue.tryPop(out));
      EXPECT_EQ(out.sequence, popped++);
    }
  }
  while (queue.tryPop(out)) EXPECT_EQ(out.sequence, popped++);
  EXPECT_EQ(popped, pushed);
  out = commandOf(77);
  EXPECT_FALSE(queue.tryPop(out));
  EXPECT_EQ(out.sequence, 77u) << "an empty queue wrote the output";
}

TEST(SpscQueue, PushAndPopAllocateNothing) {
  SpscQueue<Command> queue(8);
  const test::AllocationCounter allocations;
  Command out;
  for (std::uint64_t i = 0; i < 100; ++i) {
    queue.tryPush(commandOf(i));
    if (i % 3 == 0) queue.tryPop(out);
  }
  EXPECT_EQ(allocations.count(), 0u);
}

TEST(SpscQueue, TwoThreadsLoseDuplicateAndReorderNothing) {
  const std::uint64_t items = test::kThreadSanitizer ? 100'000 : 1'000'000;
  SpscQueue<Command> queue(64);  // small: full and empty often, many laps of the ring
  std::uint64_t refused = 0;
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < items;) {
      if (queue.tryPush(commandOf(i))) {
        ++i;
      } else {
        ++refused;
        std::this_thread::yield();
      }
    }
  });
  std::uint64_t received = 0;
  std::uint64_t torn = 0;
  std::uint64_t outOfOrder = 0;
  while (received < items) {
    Command c;
    if (!queue.tryPop(c)) {
      std::this_thread::yield();
      continue;
    }
    torn += c.check == commandOf(c.sequence).check ? 0 : 1;
    outOfOrder += c.sequence == received ? 0 : 1;
    ++received;
  }
  producer.join();
  Command extra;
  EXPECT_FALSE(queue.tryPop(extra)) << "more items came out than went in";
  EXPECT_EQ(torn, 0u);
  EXPECT_EQ(outOfOrder, 0u) << "items lost, duplicated or reordered";
  RecordProperty("refused_pushes", static_cast<int>(refused));
}

}  // namespace
}  // namespace voxhap

#include "support/allocation_counter.h"

#include <memory>
#include <new>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "support/sanitizers.h"

namespace voxhap {
namespace {

struct alignas(64) Aligned {
  char bytes[64];
};

/// Where each block's address goes before it is freed: an allocation whose pointer goes
/// nowhere else may be optimised away (GCC's -fallocation-dce).
void* volatile escaped = nullptr;

template <typename T>
T* kept(T* p) {
  escaped = p;
  return p;
}

TEST(AllocationCounter, CountsEveryFormOfOperatorNewOnItsThread) {
  const test::AllocationCounter allocations;
  EXPECT_EQ(allocations.count(), 0u);
  delete kept(new int(1));
  delete[] kept(new int[3]);
  delete kept(new (std::nothrow) int(2));
  delete kept(new Aligned);
  delete[] kept(new Aligned[2]);
  const std::uint64_t afterNew = allocations.count();
  std::vector<double> v(100);
  escaped = v.data();
  const std::uint64_t afterVector = allocations.count();
  EXPECT_EQ(afterNew, 5u);
  EXPECT_EQ(afterVector, 6u);
}

TEST(AllocationCounter, DoesNotCountOtherThreads) {
  const test::AllocationCounter allocations;
  std::thread other([] {
    std::vector<std::unique_ptr<int>> kept;
    for (int i = 0; i < 10; ++i) kept.push_back(std::make_unique<int>(i));
  });
  const std::uint64_t started = allocations.count();  // the thread's state, allocated here
  other.join();
  EXPECT_EQ(allocations.count(), started);
  EXPECT_LE(started, 1u);
}

TEST(AllocationCounter, AddressSanitizerStillSeesTheBlocks) {
  if (!test::kAddressSanitizer) GTEST_SKIP() << "not built with AddressSanitizer";
  EXPECT_DEATH(
      {
        // the size out of the compiler's sight, or UBSan's object-size check reports first
        const volatile std::size_t n = 4;
        int* p = new int[n];
        volatile int* v = p;
        v[n] = 1;  // one past the end
        delete[] p;
      },
      "heap-buffer-overflow");
}

}  // namespace
}  // namespace voxhap

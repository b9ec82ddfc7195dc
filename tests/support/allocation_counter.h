#pragma once
/// Test support: counts the heap allocations of the calling thread. allocation_counter.cpp
/// replaces the global operator new (every form) in the test binary by one that counts
/// per thread and forwards to malloc. AddressSanitizer and ThreadSanitizer still see every
/// block, since they intercept malloc and free (allocation_counter_test.cpp checks); what
/// AddressSanitizer loses is telling new from malloc, so a delete of malloc'd memory (or a
/// free of new'd) goes unreported in this binary.

#include <cstdint>

namespace voxhap::test {

/// Allocations made by the calling thread since the counter was constructed on it.
class AllocationCounter {
public:
  AllocationCounter() noexcept;
  /// Calls of any global operator new on this thread since construction.
  std::uint64_t count() const noexcept;

private:
  std::uint64_t start_;
};

}  // namespace voxhap::test

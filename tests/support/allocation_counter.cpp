#include "support/allocation_counter.h"

#include <cstdlib>
#include <new>

namespace {

constinit thread_local std::uint64_t threadAllocations = 0;

void* allocate(std::size_t bytes) noexcept {
  ++threadAllocations;
  return std::malloc(bytes ? bytes : 1);
}

void* allocateAligned(std::size_t bytes, std::align_val_t alignment) noexcept {
  ++threadAllocations;
  // posix_memalign wants a multiple of sizeof(void*); the block is freed by free()
  std::size_t a = static_cast<std::size_t>(alignment);
  if (a < sizeof(void*)) a = sizeof(void*);
  void* p = nullptr;
  return posix_memalign(&p, a, bytes ? bytes : 1) == 0 ? p : nullptr;
}

void* orThrow(void* p) {
  if (!p) throw std::bad_alloc();
  return p;
}

}  // namespace

namespace voxhap::test {

AllocationCounter::AllocationCounter() noexcept : start_(threadAllocations) {}

std::uint64_t AllocationCounter::count() const noexcept {
  return threadAllocations - start_;
}

}  // namespace voxhap::test

void* operator new(std::size_t bytes) {
  return orThrow(allocate(bytes));
}
void* operator new[](std::size_t bytes) {
  return orThrow(allocate(bytes));
}
void* operator new(std::size_t bytes, const std::nothrow_t&) noexcept {
  return allocate(bytes);
}
void* operator new[](std::size_t bytes, const std::nothrow_t&) noexcept {
  return allocate(bytes);
}
void* operator new(std::size_t bytes, std::align_val_t alignment) {
  return orThrow(allocateAligned(bytes, alignment));
}
void* operator new[](std::size_t bytes, std::align_val_t alignment) {
  return orThrow(allocateAligned(bytes, alignment));
}
void* operator new(std::size_t bytes, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return allocateAligned(bytes, alignment);
}
void* operator new[](std::size_t bytes, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return allocateAligned(bytes, alignment);
}

void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(p);
}

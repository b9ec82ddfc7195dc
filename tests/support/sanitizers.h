#pragma once
/// Test support: whether this build runs under AddressSanitizer, which makes long
/// simulations ten times slower, so that a test can run fewer frames there, or under
/// ThreadSanitizer, which slows every memory access of a concurrency test as much.

namespace voxhap::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif

#if defined(__SANITIZE_THREAD__)
inline constexpr bool kThreadSanitizer = true;
#else
inline constexpr bool kThreadSanitizer = false;
#endif

/// Either: for the tests that run in Release only, or shorter, under a sanitizer.
inline constexpr bool kSanitizer = kAddressSanitizer || kThreadSanitizer;

}  // namespace voxhap::test

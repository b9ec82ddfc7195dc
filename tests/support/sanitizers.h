#pragma once
/// Test support: whether this build runs under AddressSanitizer, which makes long
/// simulations ten times slower, so that a test can run fewer frames there, or under
/// ThreadSanitizer, which slows every memory access of a concurrency test as much.

#include <cstdlib>
#include <string>

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

/// Child processes started from now on that open a window run without LeakSanitizer:
/// Mesa's DRI driver, unloaded when GLFW terminates, leaves blocks LSan reports from an
/// unknown module and no suppression can name (the HUD tests found it); the view's own
/// parts (link, picker, in-process controller) are leak-checked in the test process by
/// their tests.
inline void windowChildrenWithoutLeakCheck() {
  const char* asan = std::getenv("ASAN_OPTIONS");
  setenv("ASAN_OPTIONS", (std::string(asan ? asan : "") + ":detect_leaks=0").c_str(), 1);
}

}  // namespace voxhap::test

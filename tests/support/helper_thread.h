#pragma once
/// Test support for code that makes a frame helper (haptics/runtime/frame_helper.h).

#include <thread>

#include <gtest/gtest.h>

namespace voxhap::test {

/// Why a test that makes a frame helper skips here, or null where it can run.
inline const char* noSpareCore() {
  return std::thread::hardware_concurrency() < 2 ? "one CPU: no spare core for a helper" : nullptr;
}

/// Runs `body` on a thread of its own, since a helper keeps the thread that makes it off
/// its CPU (the test's main thread keeps all of them); skips the test where there is no
/// spare core.
template <typename Body>
void onAThreadOfItsOwn(Body body) {
  if (const char* why = noSpareCore()) GTEST_SKIP() << why;
  std::thread(body).join();
}

}  // namespace voxhap::test

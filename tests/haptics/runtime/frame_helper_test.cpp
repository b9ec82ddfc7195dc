#include "haptics/runtime/frame_helper.h"

#include <atomic>
#include <thread>

#include <gtest/gtest.h>
#include <sched.h>

#include "haptics/core/error.h"
#include "support/helper_thread.h"

namespace voxhap {
namespace {

TEST(FrameHelper, RunsEachJobOnItsOwnCpuWhileTheMakerStaysOffIt) {
  test::onAThreadOfItsOwn([] {
    FrameHelper helper;
    int jobCpu = -1;
    auto job = [&] { jobCpu = sched_getcpu(); };
    helper.run(job);
    const int makerCpu = sched_getcpu();
    helper.finish();
    EXPECT_EQ(jobCpu, helper.cpu());
    EXPECT_NE(makerCpu, helper.cpu());
  });
}

TEST(FrameHelper, GivesTheMakerItsCpusBackWhenDestroyedOnIt) {
  test::onAThreadOfItsOwn([] {
    cpu_set_t before;
    ASSERT_EQ(sched_getaffinity(0, sizeof before, &before), 0);
    for (int helper = 0; helper < 2; ++helper) {  // a second one finds a spare core again
      FrameHelper h;
      cpu_set_t during;
      ASSERT_EQ(sched_getaffinity(0, sizeof during, &during), 0);
      EXPECT_FALSE(CPU_ISSET(static_cast<std::size_t>(h.cpu()), &during));
    }
    cpu_set_t after;
    ASSERT_EQ(sched_getaffinity(0, sizeof after, &after), 0);
    EXPECT_TRUE(CPU_EQUAL(&before, &after));
  });
}

TEST(FrameHelper, FinishReturnsOnlyOnceTheJobHasReturned) {
  test::onAThreadOfItsOwn([] {
    FrameHelper helper;
    std::uint64_t sum = 0;  // plain: finish() must order the helper's writes before our reads
    for (std::uint64_t i = 1; i <= 20000; ++i) {
      auto job = [&sum, i] { sum += i; };
      helper.run(job);
      helper.finish();
      ASSERT_EQ(sum, i * (i + 1) / 2);
    }
  });
}

TEST(FrameHelper, WakesForAJobAfterSleeping) {
  test::onAThreadOfItsOwn([] {
    FrameHelper helper;
    for (int round = 0; round < 2; ++round) {
      std::this_thread::sleep_for(2 * FrameHelper::kIdleBeforeSleep);
      bool ran = false;
      auto job = [&] { ran = true; };
      helper.run(job);
      helper.finish();
      EXPECT_TRUE(ran) << "round " << round;
    }
  });  // and the destructor stops a sleeping helper
}

TEST(FrameHelper, RefusesWhereTheMakerMayRunOnOneCpuOnly) {
  test::onAThreadOfItsOwn([] {
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(static_cast<std::size_t>(sched_getcpu()), &one);
    ASSERT_EQ(sched_setaffinity(0, sizeof one, &one), 0);
    try {
      FrameHelper helper;
      ADD_FAILURE() << "a helper on CPU " << helper.cpu() << " beside a thread pinned to one CPU";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("spare core"), std::string::npos) << e.what();
    }
  });
}

}  // namespace
}  // namespace voxhap

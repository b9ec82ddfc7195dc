#include "haptics/runtime/realtime.h"

#include <cerrno>
#include <thread>

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

namespace voxhap {
namespace {

/// ok exactly when there is no error, and a refusal says why.
void expectConsistent(const RealtimeOutcome& outcome, const char* what) {
  EXPECT_EQ(outcome.ok, outcome.errorCode == 0) << what;
  EXPECT_EQ(outcome.ok, outcome.error.empty()) << what << ": " << outcome.error;
}

/// requestRealtime(priority) on a thread of its own, which ends with it; the memory lock,
/// which is the whole process's, is undone. Also gives the thread's policy and priority after.
RealtimeStatus requestOnAThreadOfItsOwn(int priority, int& policy, int& threadPriority) {
  RealtimeStatus status;
  std::thread([&] {
    status = requestRealtime(priority);
    sched_param param{};
    pthread_getschedparam(pthread_self(), &policy, &param);
    threadPriority = param.sched_priority;
  }).join();
  if (status.memoryLock.ok) munlockall();
  return status;
}

TEST(Realtime, SaysWhatTookEffectAndWhyNot) {
  int policy = -1;
  int priority = -1;
  const RealtimeStatus status = requestOnAThreadOfItsOwn(10, policy, priority);
  EXPECT_EQ(status.fifoPriority, 10);
  expectConsistent(status.memoryLock, "mlockall");
  expectConsistent(status.fifo, "SCHED_FIFO");
  if (status.fifo.ok) {
    EXPECT_EQ(policy, SCHED_FIFO);
    EXPECT_EQ(priority, 10);
  } else {
    EXPECT_EQ(policy, SCHED_OTHER) << "refused, yet the policy changed";
  }
  RecordProperty("memory_lock", status.memoryLock.ok ? "ok" : status.memoryLock.error);
  RecordProperty("sched_fifo", status.fifo.ok ? "ok" : status.fifo.error);
}

TEST(Realtime, APriorityOutsideSchedFifosRangeIsRefusedWithItsReason) {
  for (const int bad : {0, 100}) {
    int policy = -1;
    int priority = -1;
    const RealtimeStatus status = requestOnAThreadOfItsOwn(bad, policy, priority);
    EXPECT_FALSE(status.fifo.ok) << bad;
    EXPECT_EQ(status.fifo.errorCode, EINVAL) << bad;
    EXPECT_FALSE(status.fifo.error.empty()) << bad;
    EXPECT_EQ(policy, SCHED_OTHER) << bad;
    expectConsistent(status.memoryLock, "mlockall");
  }
}

}  // namespace
}  // namespace voxhap

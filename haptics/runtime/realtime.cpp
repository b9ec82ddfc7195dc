#include "haptics/runtime/realtime.h"

#include <cerrno>
#include <system_error>

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

namespace voxhap {
namespace {

RealtimeOutcome outcomeOf(int errorCode) {
  if (errorCode == 0) return {true, 0, {}};
  return {false, errorCode, std::system_category().message(errorCode)};
}

}  // namespace

RealtimeStatus requestRealtime(int fifoPriority) {
  RealtimeStatus status;
  status.fifoPriority = fifoPriority;
  status.memoryLock = outcomeOf(mlockall(MCL_CURRENT | MCL_FUTURE) == 0 ? 0 : errno);
  sched_param param{};
  param.sched_priority = fifoPriority;
  // pthread_setschedparam returns its error number instead of setting errno
  status.fifo = outcomeOf(pthread_setschedparam(pthread_self(), SCHED_FIFO, &param));
  return status;
}

void yieldToEqualPriority() noexcept {
  sched_yield();
}

// sched_setscheduler with pid 0 acts on the calling thread (Linux), without
// pthread_setschedparam's lock on the thread's descriptor
bool leaveFifo() noexcept {
  const sched_param param{};
  return sched_setscheduler(0, SCHED_OTHER, &param) == 0;
}

bool enterFifo(int fifoPriority) noexcept {
  sched_param param{};
  param.sched_priority = fifoPriority;
  return sched_setscheduler(0, SCHED_FIFO, &param) == 0;
}

}  // namespace voxhap

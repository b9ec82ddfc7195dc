#pragma once
/// Real-time set-up of the haptic thread (DESIGN §7): memory locked (no page fault in a
/// frame) and SCHED_FIFO, when the system permits. Each is tried and reported, never
/// required: the caller prints the line that says what runs without them and why (the
/// engine never prints).

#include <string>

namespace voxhap {

/// One real-time measure: whether it took effect and, if not, why.
struct RealtimeOutcome {
  bool ok = false;
  int errorCode = 0;  ///< the errno value of the refusal, 0 when ok
  std::string error;  ///< its text (strerror), empty when ok
};

/// What requestRealtime() achieved.
struct RealtimeStatus {
  RealtimeOutcome memoryLock;  ///< mlockall(MCL_CURRENT | MCL_FUTURE), for the whole process
  RealtimeOutcome fifo;        ///< SCHED_FIFO at the asked priority, for the calling thread
  int fifoPriority = 0;        ///< the priority asked
};

/// Locks the process's memory, present and future, and puts the calling thread under
/// SCHED_FIFO at `fifoPriority` (1 … 99 on Linux); tries both whatever the first gives.
/// Call it after loading, from the haptic thread: with MCL_FUTURE every later mapping (a
/// new thread's whole stack too) is locked and, unprivileged, counts against RLIMIT_MEMLOCK. Set-up time
/// only: allocates the messages; never throws for a refusal.
RealtimeStatus requestRealtime(int fifoPriority);

/// Lets the other runnable threads of the caller's SCHED_FIFO priority run before it goes
/// on (sched_yield); returns at once when none waits. A SCHED_FIFO thread is never
/// preempted by one of its own priority: a haptic thread whose frames overrun never sleeps,
/// and without this would take a core from every other such thread for as long as it
/// overruns (three peers in one process on two cores: one peer stood still for 12.5 s).
/// Never blocks; the haptic thread calls it once a frame.
void yieldToEqualPriority() noexcept;

/// Puts the calling thread under SCHED_OTHER (its overrunning frames then share the cores
/// with every ordinary thread; FifoHold decides when). A system call only: never
/// allocates, locks or throws. True when done.
bool leaveFifo() noexcept;
/// Puts the calling thread under SCHED_FIFO at `fifoPriority` again; the same. True when done.
bool enterFifo(int fifoPriority) noexcept;

}  // namespace voxhap

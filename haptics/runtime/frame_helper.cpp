#include "haptics/runtime/frame_helper.h"

#include <string>
#include <system_error>

#include <pthread.h>
#include <sched.h>

#include "haptics/core/error.h"

namespace voxhap {
namespace {

/// Tells the core that this thread spins (x86's pause; ARMv8's yield).
void spinPause() noexcept {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

/// The last CPU the calling thread may run on, or −1 when it may run on only one.
int spareCpu() {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0 || CPU_COUNT(&allowed) < 2) return -1;
  for (std::size_t cpu = CPU_SETSIZE; cpu-- > 0;) {
    if (CPU_ISSET(cpu, &allowed)) return static_cast<int>(cpu);
  }
  return -1;
}

}  // namespace

FrameHelper::FrameHelper() : cpu_(spareCpu()), maker_(pthread_self()) {
  if (cpu_ < 0) throw Error("a frame helper needs a spare core: this thread may run on one CPU only");
  if (sched_getaffinity(0, sizeof makerCpus_, &makerCpus_) != 0)
    throw Error("cannot read this thread's CPUs");
  cpu_set_t others = makerCpus_;
  CPU_CLR(static_cast<std::size_t>(cpu_), &others);
  cpu_set_t only;
  CPU_ZERO(&only);
  CPU_SET(static_cast<std::size_t>(cpu_), &only);
  thread_ = std::thread([this] { loop(); });
  int e = pthread_setaffinity_np(thread_.native_handle(), sizeof only, &only);
  if (e == 0) e = pthread_setaffinity_np(pthread_self(), sizeof others, &others);
  if (e != 0) {
    stop_ = true;
    post(nullptr, nullptr);
    thread_.join();
    throw Error("cannot pin the frame helper to CPU " + std::to_string(cpu_) +
                " and this thread off it: " + std::system_category().message(e));
  }
}

FrameHelper::~FrameHelper() {
  finish();
  stop_ = true;
  post(nullptr, nullptr);
  thread_.join();
  if (pthread_equal(pthread_self(), maker_)) pthread_setaffinity_np(maker_, sizeof makerCpus_, &makerCpus_);
}

void FrameHelper::post(void* job, void (*call)(void*)) noexcept {
  job_ = job;
  call_ = call;
  // seq_cst store then load, against the helper's store of sleeping_ then load of posted_:
  // one of the two sees the other's, so a post never finds the helper asleep unwoken
  posted_.fetch_add(1, std::memory_order_seq_cst);
  if (sleeping_.load(std::memory_order_seq_cst)) posted_.notify_one();
}

void FrameHelper::finish() noexcept {
  const std::uint32_t posted = posted_.load(std::memory_order_relaxed);
  while (done_.load(std::memory_order_acquire) != posted) spinPause();
}

void FrameHelper::loop() noexcept {
  std::uint32_t seen = 0;
  for (;;) {
    auto idleSince = std::chrono::steady_clock::now();
    std::uint32_t posted;
    for (std::uint32_t spins = 1; (posted = posted_.load(std::memory_order_acquire)) == seen; ++spins) {
      spinPause();
      if (spins % 1024 != 0 || std::chrono::steady_clock::now() - idleSince < kIdleBeforeSleep) continue;
      sleeping_.store(true, std::memory_order_seq_cst);
      posted_.wait(seen, std::memory_order_seq_cst);
      sleeping_.store(false, std::memory_order_relaxed);
      idleSince = std::chrono::steady_clock::now();
    }
    seen = posted;
    if (stop_) return;
    call_(job_);
    done_.store(seen, std::memory_order_release);
  }
}

}  // namespace voxhap

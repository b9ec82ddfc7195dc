#pragma once
/// Test support: tests that each load this 2-core machine fully (several 1 kHz peers on
/// the landing gear) hold one system-wide lock while they run, so that ctest -j never
/// runs two of them together. Together they overload the peers until they miss their
/// own patience (ownership not settled, parts moved against stale poses).

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace voxhap::test {

class ExclusiveSection {
public:
  /// Blocks until no other process holds the section named by `lockFile`.
  explicit ExclusiveSection(const char* lockFile)
      : fd_(::open(lockFile, O_RDWR | O_CREAT | O_CLOEXEC, 0666)) {
    if (fd_ >= 0) ::flock(fd_, LOCK_EX);
  }
  ~ExclusiveSection() {
    if (fd_ >= 0) ::close(fd_);  // releases the lock
  }
  ExclusiveSection(const ExclusiveSection&) = delete;
  ExclusiveSection& operator=(const ExclusiveSection&) = delete;

private:
  int fd_;
};

/// The lock of the tests that run whole landing-gear sessions.
inline constexpr const char* kLandingGearSessionLock = "/tmp/voxhap-landing-gear-session-tests.lock";

}  // namespace voxhap::test

#pragma once
/// The few HID operations an input device's reader thread needs (enumerate, open, read,
/// close), behind an interface so that the device logic is testable without hardware. The
/// real one is hidapi's hidraw backend (makeHidapiTransport); tests use an in-process fake.
///
/// Threads. A transport is used by one thread at a time (the constructing thread, then the
/// device's reader thread). Calls may block for their time-out and may allocate.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace voxhap {

/// One HID interface as enumeration reports it. hidapi lists an interface once per
/// top-level collection, so the same path may appear with several usages.
struct HidDeviceInfo {
  std::string path;  ///< what open() takes, e.g. /dev/hidraw3
  std::uint16_t vendorId = 0;
  std::uint16_t productId = 0;
  std::uint16_t usagePage = 0;
  std::uint16_t usage = 0;
  std::string name;  ///< product string, UTF-8 (may be empty)
};

class HidTransport {
public:
  virtual ~HidTransport() = default;

  /// Every HID interface present now. Throws voxhap::Error when enumeration itself fails.
  virtual std::vector<HidDeviceInfo> enumerate() = 0;

  /// Opens `path` for reading, closing what was open; false (see lastError) on failure.
  virtual bool open(const std::string& path) = 0;

  /// Reads what the device has into `buffer`, waiting up to `timeoutMs`: the number of
  /// bytes, 0 on time-out, −1 on an error (the device is gone; see lastError).
  virtual int read(std::span<std::uint8_t> buffer, int timeoutMs) = 0;

  /// Closes the device (nothing when none is open).
  virtual void close() noexcept = 0;

  /// What the last failed open or read said.
  virtual std::string lastError() const = 0;
};

/// hidapi (hidraw backend). Throws voxhap::Error when hidapi cannot be initialised.
std::unique_ptr<HidTransport> makeHidapiTransport();

}  // namespace voxhap

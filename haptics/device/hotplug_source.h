#pragma once
/// A source of "a device may have been plugged in" notices, so that an input device's
/// reader thread, which has lost its device, enumerates at once instead of at its next
/// periodic rescan. The real one is libusb hotplug (UsbHotplugWatcher); tests use a fake.
///
/// Threads. start() and the destructor are called by the owner's thread; the arrival
/// function is called on whatever thread the source uses (its own, or a test's) from
/// start() until the destructor returns, never after.

#include <functional>
#include <string>

namespace voxhap {

class HotplugSource {
public:
  /// Called on each arrival. It must return at once: no I/O, no wait beyond a brief lock.
  using ArrivalFn = std::function<void()>;

  /// Stops watching; once it returns, the arrival function is not running and is never
  /// called again.
  virtual ~HotplugSource() = default;

  /// Starts watching (called once). Never throws on a platform without hotplug: that is
  /// reported by active() and status().
  virtual void start(ArrivalFn onArrival) = 0;

  /// Whether arrivals are reported; false: the owner has only its periodic enumeration.
  virtual bool active() const noexcept = 0;

  /// One line for a log: what is watched, or why nothing is. Read after start().
  virtual std::string status() const = 0;
};

}  // namespace voxhap

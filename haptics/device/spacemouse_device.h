#pragma once
/// A SpaceMouse-class 6-DOF HID controller as a HapticDevice (DESIGN §7): rate control,
/// no force feedback, buttons as press/release events.
///
/// Threads.
///   reader thread (its own): enumerate → open → hid read (readTimeoutMs) → parse →
///     publish the newest state to a LatestValue; button edges into an SpscQueue. On a read
///     error the device is closed, a zero deflection is published, and the thread
///     enumerates again every rescanPeriodS, and at once on each hotplug arrival, until a
///     SpaceMouse is back, then reads it.
///   hotplug thread (the HotplugSource's; libusb's event thread by default): on an arrival,
///     sets a flag under the reader's wake mutex and wakes the reader; nothing else.
///   haptic thread: handlePose / handleVelocity / setFeedback / resetHandle — they take the
///     newest state with readNewer and integrate rate control; no lock, allocation or wait.
///   comms thread (one consumer): tryPopButtonEvent.
///   any thread: the counters.
/// A device that vanishes leaves the handle where it is at zero velocity (the object stays
/// held, force zero); no button event is made up for it, and the button state is kept, so
/// the first report of the device once back gives the edges since.

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "haptics/device/hid_transport.h"
#include "haptics/device/hotplug_source.h"
#include "haptics/device/rate_control.h"
#include "haptics/device/scripted_device.h"
#include "haptics/device/spacemouse_report.h"
#include "haptics/runtime/latest_value.h"
#include "haptics/runtime/spsc_queue.h"

namespace voxhap {

/// A SpaceMouse found by enumeration.
struct SpaceMouseInfo {
  std::string path;  ///< e.g. /dev/hidraw3
  std::uint16_t vendorId = 0;
  std::uint16_t productId = 0;
  std::string name;         ///< the product string, else the known model's name
  bool knownModel = false;  ///< in knownSpaceMouseModels (else found by its usage)
};

/// What an enumeration found.
struct SpaceMouseScan {
  std::vector<SpaceMouseInfo> spaceMice;  ///< in enumeration order, one per path
  std::size_t hidDevicesSeen = 0;         ///< distinct HID paths seen
};

/// The SpaceMice among `devices`: a known vendor/product id, or usage page 0x01 with
/// usage 0x08 (multi-axis controller) on any of a path's collections.
SpaceMouseScan findSpaceMice(const std::vector<HidDeviceInfo>& devices);

/// The SpaceMice present now, through hidapi. Throws voxhap::Error when hidapi fails.
std::vector<SpaceMouseInfo> listSpaceMice();

/// One press or release of a button.
struct ButtonEvent {
  std::uint8_t button = 0;  ///< 1-based, as printed on the device (bit button − 1)
  bool pressed = false;     ///< true: went down; false: came up
};

/// The USB vendor ids whose arrivals a SpaceMouseDevice's default hotplug watcher reports
/// (a model of another vendor, found by its usage, is found by the periodic rescan).
inline constexpr std::array<std::uint16_t, 2> kSpaceMouseVendorIds{kVendorLogitech3Dconnexion,
                                                                   kVendor3Dconnexion};

/// Set-up of a SpaceMouseDevice.
struct SpaceMouseConfig {
  RateControlParams rate;
  double fullScaleCounts = 350.0;  ///< counts at full deflection, > 0
  std::string path;                ///< this device only; empty: the first SpaceMouse found
  int readTimeoutMs = 50;          ///< > 0; also how soon the destructor's stop is seen
  double rescanPeriodS = 1.0;      ///< > 0: how often to look for a device when none is open
  glm::dvec3 pivotLocal{0.0};      ///< rotation centre, object local frame, m
};

class SpaceMouseDevice final : public HapticDevice {
public:
  /// How many button events wait for the comms thread before new ones are dropped.
  static constexpr std::size_t kButtonQueueCapacity = 64;

  /// Finds and opens a SpaceMouse through `transport` (hidapi unless given), starts
  /// `hotplug` (unless given: a UsbHotplugWatcher for kSpaceMouseVendorIds) and the reader
  /// thread; the handle starts at `startWorld` (the grabbed object's pose). Throws
  /// voxhap::Error when none is found ("no SpaceMouse found: N HID devices seen, …"), when
  /// it cannot be opened, or on bad limits or parameters.
  SpaceMouseDevice(const Pose& startWorld, const DeviceLimits& limits, const SpaceMouseConfig& config = {},
                   std::unique_ptr<HidTransport> transport = nullptr,
                   std::unique_ptr<HotplugSource> hotplug = nullptr);
  /// Stops the hotplug source, stops and joins the reader thread, closes the device.
  ~SpaceMouseDevice() override;
  SpaceMouseDevice(const SpaceMouseDevice&) = delete;
  SpaceMouseDevice& operator=(const SpaceMouseDevice&) = delete;

  /// Haptic thread: the handle pose at `tS`, integrated from the previous call's time at the
  /// newest deflection (steps are clamped to kMaxStepS, so a stall does not fling it).
  Pose handlePose(double tS) noexcept override;
  /// Haptic thread: the handle velocity at `tS` (world frame; zero while disconnected).
  HandleVelocity handleVelocity(double tS) noexcept override;
  /// No force feedback: ignored.
  void setFeedback(const CouplingWrench&) noexcept override {}
  const DeviceLimits& limits() const noexcept override { return limits_; }

  /// Haptic thread: restarts the handle at `startWorld`, at rest (a new grab), its clock
  /// from the next call.
  void resetHandle(const Pose& startWorld) noexcept;
  void grabbed(const Pose& objectWorld) noexcept override { resetHandle(objectWorld); }

  /// Comms thread (the one consumer): the oldest button event not taken yet; false when none.
  bool tryPopButtonEvent(ButtonEvent& out) noexcept { return buttonEvents_.tryPop(out); }

  /// The device opened by the constructor.
  const SpaceMouseInfo& openedAtStart() const noexcept { return openedAtStart_; }
  /// Whether a device is open now.
  bool connected() const noexcept { return connected_.load(std::memory_order_acquire); }
  /// Whole reports parsed so far.
  std::uint64_t reportsParsed() const noexcept { return reportsParsed_.load(std::memory_order_acquire); }
  /// Unknown ids and cut-short reports so far.
  std::uint64_t reportErrors() const noexcept { return reportErrors_.load(std::memory_order_acquire); }
  /// Times the device was lost (read errors).
  std::uint64_t disconnects() const noexcept { return disconnects_.load(std::memory_order_acquire); }
  /// Times a device was opened again after a loss.
  std::uint64_t reconnects() const noexcept { return reconnects_.load(std::memory_order_acquire); }
  /// Whether a hotplug arrival wakes the reader (else it has only its periodic rescan).
  bool hotplugActive() const noexcept { return hotplugActive_; }
  /// One line for the log, e.g. "libusb hotplug unavailable: …; looking for a SpaceMouse
  /// every 1 s" or "libusb hotplug on for vendors 046d, 256f; enumerating on arrival and
  /// every 1 s". Fixed at construction.
  const std::string& hotplugStatus() const noexcept { return hotplugStatus_; }
  /// Hotplug arrivals seen so far (of any device of the watched vendors).
  std::uint64_t hotplugArrivals() const noexcept { return hotplugArrivals_.load(std::memory_order_acquire); }
  /// Button events dropped because the queue was full.
  std::uint64_t droppedButtonEvents() const noexcept {
    return droppedEvents_.load(std::memory_order_acquire);
  }

  /// Longest integration step, s.
  static constexpr double kMaxStepS = 0.05;

private:
  /// The reader thread's hand-over to the haptic thread.
  struct Sample {
    std::array<double, kAxisCount> deflectionView{};
    std::uint32_t buttons = 0;
    std::uint32_t connected = 0;
  };

  void readerLoop();
  void onHotplugArrival();
  bool tryOpen(bool afterLoss);
  void handleBytes(std::span<const std::uint8_t> bytes);
  void advanceTo(double tS) noexcept;

  DeviceLimits limits_;
  SpaceMouseConfig config_;
  std::unique_ptr<HidTransport> transport_;
  SpaceMouseInfo openedAtStart_;

  // reader thread's own
  SpaceMouseReportFormat format_;
  SpaceMouseState state_;

  // hand-over
  LatestValue<Sample> mailbox_;
  SpscQueue<ButtonEvent> buttonEvents_{kButtonQueueCapacity};
  std::atomic<bool> connected_{false};
  std::atomic<std::uint64_t> reportsParsed_{0};
  std::atomic<std::uint64_t> reportErrors_{0};
  std::atomic<std::uint64_t> disconnects_{0};
  std::atomic<std::uint64_t> reconnects_{0};
  std::atomic<std::uint64_t> droppedEvents_{0};
  std::atomic<std::uint64_t> hotplugArrivals_{0};

  // haptic thread's own
  RateController rate_;
  std::uint64_t seenVersion_ = 0;
  Sample current_;
  double lastTimeS_ = 0.0;
  bool started_ = false;

  // what wakes the reader: stop, or a hotplug arrival (never touched by the haptic thread)
  std::mutex wakeMutex_;
  std::condition_variable wakeSignal_;
  bool stopping_ = false;  // under wakeMutex_
  bool arrived_ = false;   // under wakeMutex_
  std::thread reader_;

  // stopped first in the destructor: its arrival function uses the members above
  std::unique_ptr<HotplugSource> hotplug_;
  bool hotplugActive_ = false;
  std::string hotplugStatus_;
};

}  // namespace voxhap

#pragma once
/// libusb hotplug as a HotplugSource: a USB device of one of the given vendors arriving
/// calls the arrival function.
///
/// How. start() checks libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG), opens a libusb
/// context of its own, registers one arrival callback per vendor id and starts an event
/// thread that runs libusb_handle_events_timeout_completed with a kEventTimeoutMs time-out
/// until stopped. The destructor sets the stop flag, deregisters the callbacks (which wakes
/// the event handler), joins the thread and closes the context.
/// When hotplug is not there (no capability, libusb_init fails — e.g. a container with no
/// usbfs — or a registration fails) start() leaves nothing running and says why in
/// status().
///
/// Threads. start(), the destructor and the getters: the owner's thread (the getters also
/// any thread after start() returned). The arrival function: the event thread.

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "haptics/device/hotplug_source.h"

struct libusb_context;

namespace voxhap {

class UsbHotplugWatcher final : public HotplugSource {
public:
  /// How far start() got.
  enum class State : std::uint8_t {
    kNotStarted,
    kNoCapability,    ///< this libusb build or platform has no hotplug
    kInitFailed,      ///< libusb_init failed (e.g. no usbfs)
    kRegisterFailed,  ///< libusb_hotplug_register_callback failed
    kWatching,        ///< the event thread runs
  };

  /// How long one libusb event wait lasts, ms: the bound on the destructor's join should
  /// deregistering not wake the handler.
  static constexpr int kEventTimeoutMs = 100;

  /// Watches for USB devices with these vendor ids (any product, any class).
  explicit UsbHotplugWatcher(std::vector<std::uint16_t> vendorIds);
  ~UsbHotplugWatcher() override;
  UsbHotplugWatcher(const UsbHotplugWatcher&) = delete;
  UsbHotplugWatcher& operator=(const UsbHotplugWatcher&) = delete;

  void start(ArrivalFn onArrival) override;
  bool active() const noexcept override { return state_ == State::kWatching; }
  /// "libusb hotplug on for vendors 046d, 256f", or "libusb hotplug unavailable: <why>".
  std::string status() const override { return status_; }

  State state() const noexcept { return state_; }

private:
  void fail(State state, const std::string& why);

  std::vector<std::uint16_t> vendorIds_;
  ArrivalFn onArrival_;  // read by the event thread through the callbacks' user data
  State state_ = State::kNotStarted;
  std::string status_ = "libusb hotplug not started";
  libusb_context* context_ = nullptr;
  std::vector<int> callbacks_;  // libusb_hotplug_callback_handle values
  std::atomic<bool> stopping_{false};
  std::thread events_;
};

}  // namespace voxhap

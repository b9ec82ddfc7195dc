#include "haptics/device/usb_hotplug.h"

#include <cstdio>
#include <filesystem>
#include <system_error>
#include <type_traits>
#include <utility>

#include <libusb.h>

namespace voxhap {
namespace {

static_assert(std::is_same_v<libusb_hotplug_callback_handle, int>);

int LIBUSB_CALL onArrived(libusb_context*, libusb_device*, libusb_hotplug_event, void* userData) {
  (*static_cast<HotplugSource::ArrivalFn*>(userData))();
  return 0;  // stay registered
}

std::string libusbErrorText(int code) {
  return std::string(libusb_error_name(code)) + " (" + libusb_strerror(code) + ")";
}

}  // namespace

UsbHotplugWatcher::UsbHotplugWatcher(std::vector<std::uint16_t> vendorIds)
    : vendorIds_(std::move(vendorIds)) {}

UsbHotplugWatcher::~UsbHotplugWatcher() {
  stopping_.store(true, std::memory_order_release);
  for (const int handle : callbacks_) libusb_hotplug_deregister_callback(context_, handle);
  if (events_.joinable()) events_.join();
  if (context_ != nullptr) libusb_exit(context_);
}

void UsbHotplugWatcher::fail(State state, const std::string& why) {
  for (const int handle : callbacks_) libusb_hotplug_deregister_callback(context_, handle);
  callbacks_.clear();
  if (context_ != nullptr) libusb_exit(context_);
  context_ = nullptr;
  state_ = state;
  status_ = "libusb hotplug unavailable: " + why;
}

void UsbHotplugWatcher::start(ArrivalFn onArrival) {
  if (state_ != State::kNotStarted) return;
  onArrival_ = std::move(onArrival);
  if (libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG) == 0) {
    fail(State::kNoCapability, "this libusb has no hotplug support on this platform");
    return;
  }
  const int init = libusb_init(&context_);
  if (init != LIBUSB_SUCCESS) {
    context_ = nullptr;
    std::string why = "libusb_init failed: " + libusbErrorText(init);
#ifdef __linux__
    // libusb's Linux backend needs usbfs; containers often have none
    std::error_code ignored;
    if (!std::filesystem::exists("/dev/bus/usb", ignored)) why += " — no /dev/bus/usb (no usbfs here)";
#endif
    fail(State::kInitFailed, why);
    return;
  }
  std::string vendors;
  for (const std::uint16_t vendorId : vendorIds_) {
    libusb_hotplug_callback_handle handle = 0;
    const int registered = libusb_hotplug_register_callback(
        context_, LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED, LIBUSB_HOTPLUG_NO_FLAGS, vendorId,
        LIBUSB_HOTPLUG_MATCH_ANY, LIBUSB_HOTPLUG_MATCH_ANY, onArrived, &onArrival_, &handle);
    char hex[8];
    std::snprintf(hex, sizeof hex, "%04x", vendorId);
    if (registered != LIBUSB_SUCCESS) {
      fail(State::kRegisterFailed, "libusb_hotplug_register_callback for vendor " + std::string(hex) +
                                       " failed: " + libusbErrorText(registered));
      return;
    }
    callbacks_.push_back(handle);
    vendors += (vendors.empty() ? "" : ", ") + std::string(hex);
  }
  events_ = std::thread([this] {
    while (!stopping_.load(std::memory_order_acquire)) {
      timeval timeout{0, kEventTimeoutMs * 1000};
      libusb_handle_events_timeout_completed(context_, &timeout, nullptr);
    }
  });
  state_ = State::kWatching;
  status_ = "libusb hotplug on for vendors " + vendors;
}

}  // namespace voxhap

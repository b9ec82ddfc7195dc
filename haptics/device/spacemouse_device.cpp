#include "haptics/device/spacemouse_device.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>

#include "haptics/core/error.h"
#include "haptics/device/usb_hotplug.h"

namespace voxhap {
namespace {

constexpr std::size_t kReadBufferBytes = 64;  // a full-speed USB interrupt packet

std::string hexId(std::uint16_t vendorId, std::uint16_t productId) {
  char text[16];
  std::snprintf(text, sizeof text, "%04x:%04x", vendorId, productId);
  return text;
}

std::string describe(const SpaceMouseInfo& info) {
  return (info.name.empty() ? std::string("SpaceMouse") : info.name) + " (" +
         hexId(info.vendorId, info.productId) + ") at " + info.path;
}

const SpaceMouseInfo* choose(const SpaceMouseScan& scan, const std::string& path) {
  for (const SpaceMouseInfo& info : scan.spaceMice) {
    if (path.empty() || info.path == path) return &info;
  }
  return nullptr;
}

SpaceMouseReportFormat formatOf(const SpaceMouseInfo& info) {
  const SpaceMouseModel* model = findSpaceMouseModel(info.vendorId, info.productId);
  return model != nullptr ? model->format : SpaceMouseReportFormat{};
}

}  // namespace

SpaceMouseScan findSpaceMice(const std::vector<HidDeviceInfo>& devices) {
  SpaceMouseScan scan;
  std::vector<std::string> paths;
  for (const HidDeviceInfo& device : devices) {
    if (std::find(paths.begin(), paths.end(), device.path) == paths.end()) paths.push_back(device.path);
    const SpaceMouseModel* model = findSpaceMouseModel(device.vendorId, device.productId);
    const bool multiAxis =
        device.usagePage == kUsagePageGenericDesktop && device.usage == kUsageMultiAxisController;
    if (model == nullptr && !multiAxis) continue;
    const bool listed = std::any_of(scan.spaceMice.begin(), scan.spaceMice.end(),
                                    [&](const SpaceMouseInfo& info) { return info.path == device.path; });
    if (listed) continue;
    SpaceMouseInfo info;
    info.path = device.path;
    info.vendorId = device.vendorId;
    info.productId = device.productId;
    info.name = !device.name.empty() ? device.name : model != nullptr ? std::string(model->name) : "";
    info.knownModel = model != nullptr;
    scan.spaceMice.push_back(std::move(info));
  }
  scan.hidDevicesSeen = paths.size();
  return scan;
}

std::vector<SpaceMouseInfo> listSpaceMice() {
  return findSpaceMice(makeHidapiTransport()->enumerate()).spaceMice;
}

SpaceMouseDevice::SpaceMouseDevice(const Pose& startWorld, const DeviceLimits& limits,
                                   const SpaceMouseConfig& config, std::unique_ptr<HidTransport> transport,
                                   std::unique_ptr<HotplugSource> hotplug)
    : limits_(limits),
      config_(config),
      transport_(std::move(transport)),
      rate_(config.rate, startWorld, config.pivotLocal),
      hotplug_(std::move(hotplug)) {
  validateDeviceLimits(limits_, "SpaceMouse");
  if (!(config_.fullScaleCounts > 0.0) || !std::isfinite(config_.fullScaleCounts))
    throw Error("SpaceMouse: fullScaleCounts must be a positive number of counts");
  if (config_.readTimeoutMs <= 0) throw Error("SpaceMouse: readTimeoutMs must be positive");
  if (!(config_.rescanPeriodS > 0.0) || !std::isfinite(config_.rescanPeriodS))
    throw Error("SpaceMouse: rescanPeriodS must be a positive number of seconds");
  if (!transport_) transport_ = makeHidapiTransport();

  const SpaceMouseScan scan = findSpaceMice(transport_->enumerate());
  const SpaceMouseInfo* chosen = choose(scan, config_.path);
  if (chosen == nullptr) {
    std::ostringstream s;
    if (config_.path.empty()) {
      s << "no SpaceMouse found: " << scan.hidDevicesSeen
        << " HID devices seen, none with usage 0x01/0x08 or "
        << "a known id";
    } else {
      s << "no SpaceMouse at " << config_.path << ": " << scan.spaceMice.size() << " SpaceMice among "
        << scan.hidDevicesSeen << " HID devices seen";
      for (const SpaceMouseInfo& info : scan.spaceMice)
        s << (&info == &scan.spaceMice.front() ? " (" : ", ") << info.path;
      if (!scan.spaceMice.empty()) s << ")";
    }
    throw Error(s.str());
  }
  if (!transport_->open(chosen->path)) {
    throw Error("cannot open " + describe(*chosen) + ": " + transport_->lastError() +
                " (is /dev/hidraw* readable by this user? a udev rule can grant it)");
  }
  openedAtStart_ = *chosen;
  format_ = formatOf(*chosen);
  connected_.store(true, std::memory_order_release);
  Sample first;
  first.connected = 1;
  mailbox_.publish(first);

  if (!hotplug_) {
    hotplug_ = std::make_unique<UsbHotplugWatcher>(
        std::vector<std::uint16_t>(kSpaceMouseVendorIds.begin(), kSpaceMouseVendorIds.end()));
  }
  hotplug_->start([this] { onHotplugArrival(); });
  hotplugActive_ = hotplug_->active();
  std::ostringstream status;
  status << hotplug_->status()
         << (hotplugActive_ ? "; enumerating on arrival and every " : "; looking for a SpaceMouse every ")
         << config_.rescanPeriodS << " s";
  hotplugStatus_ = status.str();

  reader_ = std::thread([this] { readerLoop(); });
}

SpaceMouseDevice::~SpaceMouseDevice() {
  hotplug_.reset();
  {
    std::lock_guard<std::mutex> lock(wakeMutex_);
    stopping_ = true;
  }
  wakeSignal_.notify_all();
  if (reader_.joinable()) reader_.join();
  transport_->close();
}

bool SpaceMouseDevice::tryOpen(bool afterLoss) {
  SpaceMouseScan scan;
  try {
    scan = findSpaceMice(transport_->enumerate());
  } catch (const Error&) {
    return false;
  }
  const SpaceMouseInfo* chosen = choose(scan, config_.path);
  if (chosen == nullptr || !transport_->open(chosen->path)) return false;
  format_ = formatOf(*chosen);
  if (afterLoss) reconnects_.fetch_add(1, std::memory_order_acq_rel);
  connected_.store(true, std::memory_order_release);
  Sample sample;
  sample.buttons = state_.buttons;
  sample.connected = 1;
  mailbox_.publish(sample);
  return true;
}

void SpaceMouseDevice::handleBytes(std::span<const std::uint8_t> bytes) {
  // a model of unknown layout shows it in a read holding one motion report (hidraw gives
  // one report per read)
  if (format_.motion == SpaceMouseMotionLayout::kAuto && !bytes.empty() && bytes[0] == 1) {
    if (bytes.size() == 13) format_.motion = SpaceMouseMotionLayout::kCombined;
    if (bytes.size() == 7) format_.motion = SpaceMouseMotionLayout::kSeparate;
  }
  const std::uint32_t buttonsBefore = state_.buttons;
  const SpaceMouseParseResult result =
      parseSpaceMouseReports(bytes, format_, config_.fullScaleCounts, state_);
  reportsParsed_.fetch_add(result.reports, std::memory_order_acq_rel);
  reportErrors_.fetch_add(result.errors, std::memory_order_acq_rel);
  if (result.changed == 0) return;
  Sample sample;
  sample.deflectionView = state_.deflectionView;
  sample.buttons = state_.buttons;
  sample.connected = 1;
  mailbox_.publish(sample);
  const std::uint32_t edges = buttonsBefore ^ state_.buttons;
  for (std::uint8_t bit = 0; bit < 32; ++bit) {
    const std::uint32_t mask = std::uint32_t{1} << bit;
    if ((edges & mask) == 0) continue;
    const ButtonEvent event{static_cast<std::uint8_t>(bit + 1), (state_.buttons & mask) != 0};
    if (!buttonEvents_.tryPush(event)) droppedEvents_.fetch_add(1, std::memory_order_acq_rel);
  }
}

void SpaceMouseDevice::onHotplugArrival() {
  hotplugArrivals_.fetch_add(1, std::memory_order_acq_rel);
  {
    std::lock_guard<std::mutex> lock(wakeMutex_);
    arrived_ = true;
  }
  wakeSignal_.notify_all();
}

void SpaceMouseDevice::readerLoop() {
  std::array<std::uint8_t, kReadBufferBytes> buffer{};
  const auto rescan = std::chrono::duration<double>(config_.rescanPeriodS);
  std::unique_lock<std::mutex> lock(wakeMutex_);
  while (!stopping_) {
    lock.unlock();
    bool waitBeforeNext = false;
    if (!connected_.load(std::memory_order_relaxed)) {
      waitBeforeNext = !tryOpen(true);
    } else {
      const int n = transport_->read(buffer, config_.readTimeoutMs);
      if (n > 0) {
        handleBytes(std::span<const std::uint8_t>(buffer.data(),
                                                  std::min<std::size_t>(std::size_t(n), buffer.size())));
      } else if (n < 0) {
        transport_->close();
        state_.deflectionView = {};
        connected_.store(false, std::memory_order_release);
        disconnects_.fetch_add(1, std::memory_order_acq_rel);
        Sample lost;
        lost.buttons = state_.buttons;
        mailbox_.publish(lost);
        waitBeforeNext = true;
      }
    }
    lock.lock();
    // an arrival ends the wait at once; the hidraw node may come a little after the USB
    // device (the HID driver binds, udev sets its permissions), so an enumeration at the
    // arrival can miss it, and the next periodic rescan, rescanPeriodS on, finds it
    if (waitBeforeNext) {
      wakeSignal_.wait_for(lock, rescan, [this] { return stopping_ || arrived_; });
      arrived_ = false;
    }
  }
}

void SpaceMouseDevice::advanceTo(double tS) noexcept {
  Sample newest;
  if (mailbox_.readNewer(seenVersion_, newest)) current_ = newest;
  double dtS = 0.0;
  if (std::isfinite(tS) && !started_) {
    started_ = true;
    lastTimeS_ = tS;
  } else if (std::isfinite(tS) && tS > lastTimeS_) {
    dtS = std::min(tS - lastTimeS_, kMaxStepS);
    lastTimeS_ = tS;
  }
  if (current_.connected == 0) {
    rate_.stop();
    return;
  }
  rate_.step(current_.deflectionView, dtS);
}

Pose SpaceMouseDevice::handlePose(double tS) noexcept {
  advanceTo(tS);
  return rate_.handleWorld();
}

HandleVelocity SpaceMouseDevice::handleVelocity(double tS) noexcept {
  advanceTo(tS);
  return rate_.velocityWorld();
}

void SpaceMouseDevice::resetHandle(const Pose& startWorld) noexcept {
  rate_.reset(startWorld);
  started_ = false;  // a new grab's time starts at 0 again
}

}  // namespace voxhap

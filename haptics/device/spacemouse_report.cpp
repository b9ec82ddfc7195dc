#include "haptics/device/spacemouse_report.h"

#include <algorithm>

namespace voxhap {
namespace {

constexpr std::uint8_t kIdMotion = 1;  // translation, or translation + rotation (combined)
constexpr std::uint8_t kIdRotation = 2;
constexpr std::uint8_t kIdButtons = 3;
constexpr std::size_t kAxisReportBytes = 1 + 3 * 2;
constexpr std::size_t kCombinedReportBytes = 1 + 6 * 2;

constexpr SpaceMouseReportFormat kSeparate2{SpaceMouseMotionLayout::kSeparate, 2};
constexpr SpaceMouseReportFormat kSeparate4{SpaceMouseMotionLayout::kSeparate, 4};
constexpr SpaceMouseReportFormat kCombined4{SpaceMouseMotionLayout::kCombined, 4};
constexpr SpaceMouseReportFormat kAuto4{SpaceMouseMotionLayout::kAuto, 4};

// product ids as 3Dconnexion allocated them (the same under either vendor id); layouts as
// the models are publicly described, kAuto where not sure
constexpr std::array kModels{
    SpaceMouseModel{0xc603, "SpaceMouse Plus XT", kSeparate2},
    SpaceMouseModel{0xc606, "SpaceTraveler", kSeparate2},
    SpaceMouseModel{0xc621, "SpaceBall 5000", kSeparate2},
    SpaceMouseModel{0xc623, "SpaceTraveler", kSeparate2},
    SpaceMouseModel{0xc625, "SpacePilot", kSeparate4},
    SpaceMouseModel{0xc626, "SpaceNavigator", kSeparate2},
    SpaceMouseModel{0xc627, "SpaceExplorer", kSeparate2},
    SpaceMouseModel{0xc628, "SpaceNavigator for Notebooks", kSeparate2},
    SpaceMouseModel{0xc629, "SpacePilot Pro", kSeparate4},
    SpaceMouseModel{0xc62b, "SpaceMouse Pro", kSeparate4},
    SpaceMouseModel{0xc62e, "SpaceMouse Wireless (cable)", kCombined4},
    SpaceMouseModel{0xc62f, "SpaceMouse Wireless (receiver)", kCombined4},
    SpaceMouseModel{0xc631, "SpaceMouse Pro Wireless (cable)", kCombined4},
    SpaceMouseModel{0xc632, "SpaceMouse Pro Wireless (receiver)", kCombined4},
    SpaceMouseModel{0xc633, "SpaceMouse Enterprise", kAuto4},
    SpaceMouseModel{0xc635, "SpaceMouse Compact", kAuto4},
    SpaceMouseModel{0xc652, "3Dconnexion Universal Receiver", kCombined4},
};

double normalised(const std::uint8_t* littleEndian, double fullScaleCounts) noexcept {
  const auto counts = static_cast<std::int16_t>(static_cast<std::uint16_t>(littleEndian[0]) |
                                                static_cast<std::uint16_t>(littleEndian[1] << 8));
  return std::clamp(static_cast<double>(counts) / fullScaleCounts, -1.0, 1.0);
}

// the three axes of one device vector (3 × int16) into view axes first..first+2
bool applyVector(const std::uint8_t* counts, std::size_t firstViewAxis, double fullScaleCounts,
                 SpaceMouseState& state) noexcept {
  bool changed = false;
  for (std::size_t viewAxis = 0; viewAxis < 3; ++viewAxis) {
    const AxisMap& map = kDeviceToViewAxes[viewAxis];
    const double value = map.sign * normalised(counts + 2 * map.deviceAxis, fullScaleCounts);
    double& slot = state.deflectionView[firstViewAxis + viewAxis];
    changed = changed || slot != value;
    slot = value;
  }
  return changed;
}

bool isCombined(SpaceMouseMotionLayout layout, std::span<const std::uint8_t> rest) noexcept {
  switch (layout) {
    case SpaceMouseMotionLayout::kSeparate:
      return false;
    case SpaceMouseMotionLayout::kCombined:
      return true;
    case SpaceMouseMotionLayout::kAuto:
      break;
  }
  if (rest.size() < kCombinedReportBytes) return false;
  if (rest.size() == kCombinedReportBytes) return true;
  const std::uint8_t next = rest[kAxisReportBytes];
  return next != kIdMotion && next != kIdRotation && next != kIdButtons;
}

}  // namespace

std::span<const SpaceMouseModel> knownSpaceMouseModels() noexcept {
  return kModels;
}

const SpaceMouseModel* findSpaceMouseModel(std::uint16_t vendorId, std::uint16_t productId) noexcept {
  if (vendorId != kVendorLogitech3Dconnexion && vendorId != kVendor3Dconnexion) return nullptr;
  for (const SpaceMouseModel& model : kModels) {
    if (model.productId == productId) return &model;
  }
  return nullptr;
}

SpaceMouseParseResult parseSpaceMouseReports(std::span<const std::uint8_t> bytes,
                                             const SpaceMouseReportFormat& format, double fullScaleCounts,
                                             SpaceMouseState& state) noexcept {
  SpaceMouseParseResult result;
  const std::size_t buttonBytes = std::clamp<std::size_t>(format.buttonBytes, 1, 4);
  std::size_t at = 0;
  while (at < bytes.size()) {
    const std::span<const std::uint8_t> rest = bytes.subspan(at);
    std::size_t length = 0;
    switch (rest[0]) {
      case kIdMotion:
        length = isCombined(format.motion, rest) ? kCombinedReportBytes : kAxisReportBytes;
        break;
      case kIdRotation:
        length = kAxisReportBytes;
        break;
      case kIdButtons:
        length = 1 + buttonBytes;
        break;
      default:
        break;
    }
    if (length == 0 || length > rest.size()) {
      ++result.errors;
      result.bytesDiscarded = rest.size();
      break;
    }
    const std::uint8_t* body = rest.data() + 1;
    if (rest[0] == kIdMotion) {
      if (applyVector(body, kAxisTx, fullScaleCounts, state)) result.changed |= kChangedTranslation;
      if (length == kCombinedReportBytes && applyVector(body + 6, kAxisRx, fullScaleCounts, state))
        result.changed |= kChangedRotation;
    } else if (rest[0] == kIdRotation) {
      if (applyVector(body, kAxisRx, fullScaleCounts, state)) result.changed |= kChangedRotation;
    } else {
      std::uint32_t buttons = 0;
      for (std::size_t i = 0; i < buttonBytes; ++i) buttons |= static_cast<std::uint32_t>(body[i]) << (8 * i);
      if (buttons != state.buttons) result.changed |= kChangedButtons;
      state.buttons = buttons;
    }
    ++result.reports;
    at += length;
  }
  return result;
}

}  // namespace voxhap

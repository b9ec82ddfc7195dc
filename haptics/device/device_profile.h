#pragma once
/// Device profiles: what a haptic device can render, by name (DESIGN §4.7). Every run
/// takes its device limits from one, so that no limit is ever infinite: the coupling's
/// pull on a body is saturated at the profile's force and torque (simulation.h), and its
/// stiffness lowered to what the profile renders stably (virtual_coupling.h).
///
/// The figures are round nominal values for a class of device, not one vendor's data
/// sheet; a site with a real device sets its own.

#include <span>
#include <string>
#include <string_view>

#include "haptics/dynamics/virtual_coupling.h"

namespace voxhap {

/// A named set of device limits.
struct DeviceProfile {
  std::string_view name;
  std::string_view description;  ///< one line, for --help
  DeviceLimits limits;
};

/// The built-in profiles; the first is the default (kDefaultDeviceProfile).
std::span<const DeviceProfile> deviceProfiles() noexcept;

/// The default profile's name: a motion script played through a rigid handle.
inline constexpr std::string_view kDefaultDeviceProfile = "scripted";

/// The profile called `name`; throws voxhap::Error listing the names when there is none.
const DeviceProfile& deviceProfile(std::string_view name);

/// The profiles' names, comma-separated, for --help and errors.
std::string deviceProfileNames();

}  // namespace voxhap

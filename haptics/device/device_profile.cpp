#include "haptics/device/device_profile.h"

#include <array>

#include "haptics/core/error.h"

namespace voxhap {
namespace {

constexpr DeviceLimits limitsOf(double forceN, double torqueNm, double stiffnessNPerM,
                                double angularNmPerRad) {
  DeviceLimits limits;
  limits.maxForceN = forceN;
  limits.maxTorqueNm = torqueNm;
  limits.maxLinearStiffnessNPerM = stiffnessNPerM;
  limits.maxAngularStiffnessNmPerRad = angularNmPerRad;
  return limits;
}

// the default's figures are DeviceLimits' defaults (virtual_coupling.h)
constexpr std::array kProfiles{
    DeviceProfile{"scripted",
                  "a motion script through a rigid handle: 100 N, 10 N·m (a firm two-handed pull)",
                  DeviceLimits{}},
    DeviceProfile{"desktop-6dof", "a desktop 6-DOF force device: 8 N, 0.4 N·m, 2 kN/m, 2 N·m/rad",
                  limitsOf(8.0, 0.4, 2000.0, 2.0)},
    DeviceProfile{"arm-6dof", "an arm-sized 6-DOF force device: 35 N, 3 N·m, 15 kN/m, 50 N·m/rad",
                  limitsOf(35.0, 3.0, 15000.0, 50.0)},
};

}  // namespace

std::span<const DeviceProfile> deviceProfiles() noexcept {
  return kProfiles;
}

std::string deviceProfileNames() {
  std::string names;
  for (const DeviceProfile& profile : kProfiles)
    names += (names.empty() ? "" : ", ") + std::string(profile.name);
  return names;
}

const DeviceProfile& deviceProfile(std::string_view name) {
  for (const DeviceProfile& profile : kProfiles) {
    if (profile.name == name) return profile;
  }
  throw Error("unknown device profile '" + std::string(name) + "' (known: " + deviceProfileNames() + ")");
}

}  // namespace voxhap

#include "render/proximity_ramp.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace voxhap::render {
namespace {

constexpr glm::vec3 kRed{1.0f, 0.0f, 0.0f};
constexpr glm::vec3 kOrange{1.0f, 0.5f, 0.0f};
constexpr glm::vec3 kYellow{1.0f, 0.9f, 0.1f};

}  // namespace

glm::vec4 proximityColour(float distanceM, float rangeM, const glm::vec4& baseColor) {
  if (!(distanceM < rangeM) || !(rangeM > 0.0f)) return baseColor;  // far, +inf, NaN
  const float t = std::clamp(distanceM / rangeM, 0.0f, 1.0f) * 3.0f;
  glm::vec3 rgb;
  if (t < 1.0f) {
    rgb = glm::mix(kRed, kOrange, t);
  } else if (t < 2.0f) {
    rgb = glm::mix(kOrange, kYellow, t - 1.0f);
  } else {
    rgb = glm::mix(kYellow, glm::vec3(baseColor), t - 2.0f);
  }
  return glm::vec4(rgb, baseColor.a);
}

Rgba8 toRgba8(const glm::vec4& colour) {
  const auto byte = [](float v) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
  };
  return Rgba8{byte(colour.r), byte(colour.g), byte(colour.b), byte(colour.a)};
}

}  // namespace voxhap::render

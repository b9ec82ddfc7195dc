#pragma once
/// Proximity colours of a moving object (paper §3.1, DESIGN §9): warmer is closer.
///
/// The mapping, with t = distance / range clamped to [0, 1]:
///   t = 0    red      (1.0, 0.0, 0.0)   touching (or inside)
///   t = 1/3  orange   (1.0, 0.5, 0.0)
///   t = 2/3  yellow   (1.0, 0.9, 0.1)
///   t = 1    the part's own base colour, and everything beyond the range (+inf, NaN)
/// linear in between. Colours are linear RGB, as a Part's baseColor; alpha is the part's.

#include <cstdint>

#include <glm/vec4.hpp>

namespace voxhap::render {

/// The range the ramp spans by default when the caller gives none: 5 voxels of 1 mm, m.
constexpr float kDefaultProximityRangeM = 0.005f;

/// The linear RGBA colour of a vertex at `distanceM` from the nearest static surface
/// (m; ≤ 0 touching, +inf far), for a part of colour `baseColor`, over `rangeM` (> 0).
glm::vec4 proximityColour(float distanceM, float rangeM, const glm::vec4& baseColor);

/// An RGBA8 vertex colour (linear values, 0…255), as the colour stream stores it.
struct Rgba8 {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
};

/// `colour` (linear, 0…1, clamped) as RGBA8.
Rgba8 toRgba8(const glm::vec4& colour);

}  // namespace voxhap::render

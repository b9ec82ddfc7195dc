#pragma once
/// One voxel's plane of the nearest surface (contact finer than a voxel, DESIGN §4.4;
/// beyond the paper): the exact signed distance φ_c of the voxel's centre c from the
/// object's surface (negative inside) and the outward unit direction n_c = ∇φ at c. A
/// point p in that voxel lies φ_c + (p − c)·n_c from the surface (surface_planes.h says
/// how well). Quantized to 8 bytes, so that every peer reads the same bits.

#include <cstdint>
#include <limits>

#include <glm/vec3.hpp>

namespace voxhap {

struct SurfacePlane {
  /// Units of distance: 1/1024 voxel, so ±32 voxels fit.
  static constexpr double kDistanceStepsPerVoxel = 1024.0;
  /// Units of the direction's components.
  static constexpr double kDirectionSteps = 32767.0;
  /// A voxel without a plane (too far from the surface to need one).
  static constexpr std::int16_t kNone = std::numeric_limits<std::int16_t>::min();

  std::int16_t distance = kNone;        ///< φ_c, 1/1024 voxel
  std::int16_t outward[3] = {0, 0, 0};  ///< n_c, units of 1/32767

  /// `distanceVoxels` clamped to what fits; `outwardUnit` of length 1.
  static SurfacePlane make(double distanceVoxels, const glm::dvec3& outwardUnit);

  bool valid() const noexcept { return distance != kNone; }
  bool operator==(const SurfacePlane&) const = default;
  double distanceVoxels() const noexcept { return distance / kDistanceStepsPerVoxel; }
  glm::dvec3 outwardUnit() const noexcept {
    return glm::dvec3(outward[0], outward[1], outward[2]) / kDirectionSteps;
  }

  /// Every one of a voxel's six face neighbours (sideBit).
  static constexpr std::uint8_t kAllSides = 0x3f;
  /// The bit of a voxel's face neighbour one step along `axis` (0, 1, 2) on `side` (−1, +1),
  /// in a set of six (convexSides).
  static constexpr std::uint8_t sideBit(int axis, int side) noexcept {
    return static_cast<std::uint8_t>(1u << (2 * axis + (side > 0 ? 1 : 0)));
  }
  /// Whether this plane and `beside`'s, the plane of the face neighbour on `side` along
  /// `axis`, agree with convexity between their centres: each lies under the other's value
  /// at the other's centre, with no slack (surface_distance.h says why). Symmetric.
  bool convexWith(const SurfacePlane& beside, int axis, int side) const noexcept {
    const double ownVoxels = distanceVoxels();
    const double besideVoxels = beside.distanceVoxels();
    return besideVoxels - side * beside.outwardUnit()[axis] <= ownVoxels &&
           ownVoxels + side * outwardUnit()[axis] <= besideVoxels;
  }
};

}  // namespace voxhap

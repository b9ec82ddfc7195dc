#pragma once
/// Point-voxel sampling (DESIGN §4.4, paper §2.1 and §4): points of a pointshell
/// object, moved into the frame of a voxmap object, read the distance field their
/// feature label asks for; the voxels at or inside the force layer are contacts.
///
/// The hot loop: one fused transform from pointshell-local metres straight to voxel
/// coordinates (rotation and scale folded together, float), a floor, and the voxmap's
/// two or three dependent loads. No allocation, no branch on the bit width; contacts go
/// to a caller-sized buffer. Any number of threads may sample one voxmap at once.

#include <array>
#include <climits>
#include <cstdint>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <xmmintrin.h>

#include "haptics/dynamics/pose.h"
#include "haptics/pointshell/pointshell.h"
#include "haptics/voxel/voxmap.h"

namespace voxhap {

/// One point found at or inside the force layer.
struct PointContact {
  std::uint32_t point;  ///< index in the pointshell
  glm::ivec3 ijkVoxel;  ///< voxel of the voxmap it fell in
  std::uint8_t value;   ///< the field value read there (1 … force layer)
};

/// Pointshell-local metres → voxmap voxel coordinates (voxel (i,j,k) spans [i, i+1)).
struct VoxelTransform {
  glm::mat3 rotationScaled{1.0f};  ///< rotation (shell-local → voxmap-local) / voxel size
  glm::vec3 offset{0.0f};          ///< (translation − grid origin) / voxel size

  /// `shellToVoxmap` maps pointshell-local points to voxmap-local points.
  static VoxelTransform make(const Pose& shellToVoxmap, const VoxelGrid& grid);

  glm::vec3 apply(const glm::vec3& pointLocal) const { return rotationScaled * pointLocal + offset; }
};

/// What one point test reads.
struct PointSample {
  glm::ivec3 ijkVoxel;  ///< voxel of the voxmap the point fell in
  std::uint8_t value;   ///< the field value read there (0 … 2^bits − 1)
  bool missing;         ///< its chunk is paged out (value meaningless)
};

/// floor(v) as an int, as the AVX2 paths take it (floor, then truncation): NaN and values
/// outside int's range give INT_MIN. A truncation, one down where it rounded up: a few
/// instructions where floorf's inline sequence (no SSE4.1 in the base target) took a tenth
/// of the time-critical tests' frame (perf, coherentTests).
inline int floorAsInt(float v) noexcept {
  const int truncated = _mm_cvtt_ss2si(_mm_set_ss(v));  // INT_MIN for NaN and out of range
  return truncated - static_cast<int>(v < static_cast<float>(truncated) && truncated != INT_MIN);
}

/// The voxel that voxel coordinates `voxelCoords` fall in.
inline glm::ivec3 voxelOf(const glm::vec3& voxelCoords) noexcept {
  return {floorAsInt(voxelCoords.x), floorAsInt(voxelCoords.y), floorAsInt(voxelCoords.z)};
}

/// The field at `shift` of a voxel word; `fieldMask` is VoxelEncoding::fieldMask().
inline std::uint8_t fieldValue(VoxelWord word, std::uint8_t shift, VoxelWord fieldMask) noexcept {
  return static_cast<std::uint8_t>((word >> shift) & fieldMask);
}

/// Reads the field at `shift` where voxel coordinates `voxelCoords` fall.
inline PointSample sampleAt(const Voxmap& voxmap, const glm::vec3& voxelCoords, std::uint8_t shift) noexcept {
  const glm::ivec3 ijk = voxelOf(voxelCoords);
  const VoxelWord word = voxmap.word(ijk);
  return {ijk, fieldValue(word, shift, voxmap.encoding().fieldMask()), word == Voxmap::kMissingWord};
}

/// Tests point `index` of `shell`; `fieldShifts` comes from fieldShiftsByFeature. Inline:
/// the hot loops of samplePoints and of time-critical sampling are built from it.
inline PointSample samplePointAt(const Pointshell& shell, const Voxmap& voxmap,
                                 const VoxelTransform& transform,
                                 const std::array<std::uint8_t, 3>& fieldShifts,
                                 std::uint32_t index) noexcept {
  return sampleAt(voxmap, transform.apply(shell.positionsLocal[index]),
                  fieldShifts[static_cast<std::size_t>(shell.features[index])]);
}

/// The field each feature label samples: geometrical awareness or the surface field.
std::array<std::uint8_t, 3> fieldShiftsByFeature(bool geometricalAwareness, const VoxelEncoding& encoding);

/// How samplePoints runs: one point at a time, or eight with AVX2 (point_sampler_avx2.h).
/// Both write the same contacts, bit for bit.
enum class PointTestPath : std::uint8_t { Scalar, Avx2 };

/// The path samplePoints takes for `voxmap` on this CPU: AVX2 where the CPU has it and
/// the voxmap is not paged.
PointTestPath pointTestPathFor(const Voxmap& voxmap) noexcept;

/// samplePoints by `path` (Avx2 only where pointTestPathFor gives it).
std::uint32_t samplePointsOn(PointTestPath path, const Pointshell& shell, const Voxmap& voxmap,
                             const VoxelTransform& transform, const std::array<std::uint8_t, 3>& fieldShifts,
                             std::uint8_t maxValue, std::uint32_t first, std::uint32_t last,
                             PointContact* contacts) noexcept;

/// Tests points [first, last) of `shell` against `voxmap`; writes every point whose
/// value lies in [1, maxValue] (the force layer, or one beyond for pre-contact damping)
/// to `contacts` (room for last − first entries; those past the count may be written too),
/// in point order, and returns how many it wrote. `fieldShifts` comes from fieldShiftsByFeature.
inline std::uint32_t samplePoints(const Pointshell& shell, const Voxmap& voxmap,
                                  const VoxelTransform& transform,
                                  const std::array<std::uint8_t, 3>& fieldShifts, std::uint8_t maxValue,
                                  std::uint32_t first, std::uint32_t last, PointContact* contacts) noexcept {
  return samplePointsOn(pointTestPathFor(voxmap), shell, voxmap, transform, fieldShifts, maxValue, first,
                        last, contacts);
}

/// The field value point `index` reads (0 … 2^bits − 1); for tests and proximity.
inline std::uint8_t samplePoint(const Pointshell& shell, const Voxmap& voxmap,
                                const VoxelTransform& transform,
                                const std::array<std::uint8_t, 3>& fieldShifts,
                                std::uint32_t index) noexcept {
  return samplePointAt(shell, voxmap, transform, fieldShifts, index).value;
}

}  // namespace voxhap

#include "haptics/collide/point_sampler.h"

#include <glm/gtc/quaternion.hpp>

#include "haptics/collide/point_sampler_avx2.h"

namespace voxhap {

VoxelTransform VoxelTransform::make(const Pose& shellToVoxmap, const VoxelGrid& grid) {
  const double inv = 1.0 / grid.voxelSizeM;
  VoxelTransform t;
  t.rotationScaled = glm::mat3(glm::mat3_cast(shellToVoxmap.orientation) * inv);
  t.offset = glm::vec3((shellToVoxmap.position - grid.originLocal) * inv);
  return t;
}

std::array<std::uint8_t, 3> fieldShiftsByFeature(bool geometricalAwareness, const VoxelEncoding& encoding) {
  // indexed by PointFeature {Surface, Edge, Vertex}
  const Field aware[3] = {Field::Vertex, Field::Edge, Field::Surface};
  std::array<std::uint8_t, 3> shifts{};
  for (int f = 0; f < 3; ++f) {
    const Field field = geometricalAwareness ? aware[f] : Field::Surface;
    shifts[static_cast<std::size_t>(f)] =
        static_cast<std::uint8_t>(static_cast<int>(field) * encoding.bitsPerField);
  }
  return shifts;
}

PointTestPath pointTestPathFor(const Voxmap& voxmap) noexcept {
  // the gathers index hyperchunk and chunk entries with 31 bits, words with 32
  constexpr std::size_t kIndexLimit = std::size_t{1} << 31;
  const std::size_t words =
      voxmap.voxelBytes().size() / static_cast<std::size_t>(voxmap.encoding().bytesPerWord());
  const bool reachable = voxmap.hyperEntries().size() < kIndexLimit &&
                         voxmap.chunkEntries().size() < kIndexLimit && words < 2 * kIndexLimit;
  return cpuHasAvx2() && !voxmap.isPaged() && reachable ? PointTestPath::Avx2 : PointTestPath::Scalar;
}

std::uint32_t samplePointsOn(PointTestPath path, const Pointshell& shell, const Voxmap& voxmap,
                             const VoxelTransform& transform, const std::array<std::uint8_t, 3>& fieldShifts,
                             std::uint8_t maxValue, std::uint32_t first, std::uint32_t last,
                             PointContact* contacts) noexcept {
  if (path == PointTestPath::Avx2)
    return samplePointsAvx2(shell, voxmap, transform, fieldShifts, maxValue, first, last, contacts);
  const VoxelWord fieldMask = voxmap.encoding().fieldMask();
  std::uint32_t found = 0;
  for (std::uint32_t i = first; i < last; ++i) {
    const glm::ivec3 ijk = voxelOf(transform.apply(shell.positionsLocal[i]));
    const std::uint8_t value =
        fieldValue(voxmap.word(ijk), fieldShifts[static_cast<std::size_t>(shell.features[i])], fieldMask);
    // value − 1 wraps far (0) to 255, so one compare keeps [1, maxValue]. Field by field:
    // a PointSample built and copied whole stalled on its narrow stores (perf, pointTests)
    if (static_cast<std::uint8_t>(value - 1u) < maxValue) {
      PointContact& contact = contacts[found++];
      contact.point = i;
      contact.ijkVoxel = ijk;
      contact.value = value;
    }
  }
  return found;
}

}  // namespace voxhap

#pragma once
/// samplePoints eight points at a time with AVX2 (issue 13): the same float operations in
/// the same order as the scalar loop (a multiply and an add, never fused: the target has
/// no FMA), the same floor and the same tree walk by masked gathers, so the contacts are
/// the same bits on every CPU. Only for an unpaged voxmap (a paged one marks the slots it
/// reads, and may read a chunk missing) whose hyperchunk and chunk entries a 31-bit index
/// reaches and whose words a 32-bit one; pointTestPathFor says when.

#include <array>
#include <cstdint>

#include "haptics/collide/point_sampler.h"

namespace voxhap {

/// Whether this CPU runs AVX2 (checked once, at load).
bool cpuHasAvx2() noexcept;

/// samplePoints on AVX2; call only where pointTestPathFor gives PointTestPath::Avx2.
std::uint32_t samplePointsAvx2(const Pointshell& shell, const Voxmap& voxmap, const VoxelTransform& transform,
                               const std::array<std::uint8_t, 3>& fieldShifts, std::uint8_t maxValue,
                               std::uint32_t first, std::uint32_t last, PointContact* contacts) noexcept;

/// Voxmap::word of the first `count` voxels of `ijkVoxels`, rounded down to a multiple of
/// eight, into `words`; call only where pointTestPathFor gives PointTestPath::Avx2.
void voxelWordsAvx2(const Voxmap& voxmap, const glm::ivec3* ijkVoxels, std::size_t count,
                    VoxelWord* words) noexcept;

}  // namespace voxhap

#pragma once
/// The chunk-level distance field of a voxmap (DESIGN §4.1, §4.5): for every chunk of
/// the grid, the chessboard (L∞) distance in chunk units to the nearest voxel-bearing
/// chunk, capped at kChunkDistanceCap.
///
/// The transform is separable: the chessboard distance from a set is
/// min over sources of max(|dx|, |dy|, |dz|), so three one-dimensional passes
/// d'(u) = min_i max(|u − i|, d(i)) along x, then y, then z give it exactly. Each pass
/// is the linear-time lower-envelope scan of Meijster, Roerdink and Hesselink (2000)
/// with its L∞ separator. Capping every intermediate value commutes with the passes,
/// so one byte per chunk is enough throughout. Lines are independent within a pass, so
/// they run in parallel; deterministic.

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

namespace voxhap {

/// Largest stored chunk distance; farther chunks hold this value.
inline constexpr std::uint8_t kChunkDistanceCap = 255;

/// Replaces `field` (dims.x × dims.y × dims.z bytes, x fastest; 0 for a source chunk,
/// anything else for a non-source) with each chunk's chessboard distance, in chunks,
/// to the nearest source, capped at kChunkDistanceCap (also when there is no source).
/// Uses `threads` threads (0: all cores); the result does not depend on it.
void chessboardChunkTransform(std::span<std::uint8_t> field, const glm::ivec3& dims, int threads = 0);

}  // namespace voxhap

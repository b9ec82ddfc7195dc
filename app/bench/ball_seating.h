#pragma once
// How the built-in balls seat in their sockets in `voxhap bench rotation` (and the
// micro-benchmarks that measure pieces of its frames, tests/bench/seated_ball_model.h).
#include <cstdint>

#include "haptics/voxel/voxel_encoding.h"

namespace voxhap {

/// The ball's points along their normals, voxels (inward), and the force layer of its
/// pair with the socket (the surface voxels): what seats it (mating surfaces, paper §3.2
/// and §7). Against half a voxel and the paper's layer 4 (two free layers), measured at
/// 0.35 mm (stop 34): turns 3.4 and 1.7–2.3 times as fast (25 and 12.5 mm ball), 25–31
/// times fewer contacts, the ball's centre within 0.03 mm of the socket's instead of
/// 0.25 mm, the exact penetration 0.06–0.10 mm instead of 0.17–0.19 mm (the meshes' own
/// facets cross by up to 0.1 mm with the ball centred).
inline constexpr double kBallPointOffsetVoxels = -1.0;
inline constexpr std::uint8_t kBallForceLayer = kValueFeature;

}  // namespace voxhap

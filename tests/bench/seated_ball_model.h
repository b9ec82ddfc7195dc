#pragma once
// The 25 mm ball in its socket as `voxhap bench rotation` seats it (app/bench/ball_seating.h),
// built once per voxel size for the micro-benchmarks that measure pieces of that
// benchmark's frames.
#include <map>
#include <memory>
#include <utility>

#include "app/bench/ball_seating.h"
#include "haptics/scene/builtin/builtin_scenes.h"
#include "haptics/sim/scene_model.h"

namespace voxhap {

/// The 25 mm ball in its socket at `voxelM`, built once per voxel size and contact: the
/// paper's, seated as `voxhap bench rotation` seats it; or contact finer than a voxel (the
/// commands' default), its points half a voxel inward and its pair at the default force
/// layer, so that every point of the mating surfaces lies closer to the socket's exact
/// surface than the contact distance (0.75 point spacings) and every contact pushes,
/// measured by surface planes.
inline const SimModel& ballInSocketModel(double voxelM, bool surfaceContact) {
  static std::map<std::pair<double, bool>, std::unique_ptr<SimModel>> cache;
  auto& entry = cache[{voxelM, surfaceContact}];
  if (entry) return *entry;
  SceneModelOptions options;
  options.staticVoxelSizeM = voxelM;
  options.pointSpacingM = voxelM;
  if (surfaceContact) {
    options.sim.surfaceContact = true;
    options.pointDisplacementM = -0.5 * voxelM;
  } else {
    options.pointDisplacementM = kBallPointOffsetVoxels * voxelM;
    options.forceLayerOf = {{"ball", kBallForceLayer}};
  }
  entry = std::make_unique<SimModel>(buildSceneModel(makeBallAndSocket(), {"ball"}, options));
  return *entry;
}

inline const SimModel& seatedBallModel(double voxelM) {
  return ballInSocketModel(voxelM, false);
}

}  // namespace voxhap

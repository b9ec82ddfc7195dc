#pragma once
// The 25 mm ball in its socket as `voxhap bench rotation` seats it (app/bench/ball_seating.h),
// built once per voxel size for the micro-benchmarks that measure pieces of that
// benchmark's frames.
#include <map>
#include <memory>

#include "app/bench/ball_seating.h"
#include "haptics/scene/builtin/builtin_scenes.h"
#include "haptics/sim/scene_model.h"

namespace voxhap {

inline const SimModel& seatedBallModel(double voxelM) {
  static std::map<double, std::unique_ptr<SimModel>> cache;
  auto& entry = cache[voxelM];
  if (entry) return *entry;
  SceneModelOptions options;
  options.staticVoxelSizeM = voxelM;
  options.pointSpacingM = voxelM;
  options.pointDisplacementM = kBallPointOffsetVoxels * voxelM;
  options.forceLayerOf = {{"ball", kBallForceLayer}};
  entry = std::make_unique<SimModel>(buildSceneModel(makeBallAndSocket(), {"ball"}, options));
  return *entry;
}

/// The same ball with contact finer than a voxel (the commands' default contact), its
/// points half a voxel inward and its pair at the default force layer: every point of the
/// mating surfaces lies closer to the socket's exact surface than the contact distance
/// (0.75 point spacings), so every contact pushes, measured by surface planes.
inline const SimModel& surfaceContactBallModel(double voxelM) {
  static std::map<double, std::unique_ptr<SimModel>> cache;
  auto& entry = cache[voxelM];
  if (entry) return *entry;
  SceneModelOptions options;
  options.sim.surfaceContact = true;
  options.staticVoxelSizeM = voxelM;
  options.pointSpacingM = voxelM;
  options.pointDisplacementM = -0.5 * voxelM;
  entry = std::make_unique<SimModel>(buildSceneModel(makeBallAndSocket(), {"ball"}, options));
  return *entry;
}

}  // namespace voxhap

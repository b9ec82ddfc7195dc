#pragma once
// The 25 mm ball in its socket as `voxhap bench rotation` seats it (rotation_benchmark.cpp:
// its points a voxel inward, the surface voxels its pair's force layer), built once per
// voxel size for the micro-benchmarks that measure pieces of that benchmark's frames.
#include <map>
#include <memory>

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
  options.pointDisplacementM = -voxelM;
  options.forceLayerOf = {{"ball", kValueFeature}};
  entry = std::make_unique<SimModel>(buildSceneModel(makeBallAndSocket(), {"ball"}, options));
  return *entry;
}

}  // namespace voxhap

#include "haptics/sim/scene_model.h"

#include <algorithm>

#include "haptics/core/error.h"
#include "haptics/dynamics/mass_properties.h"
#include "haptics/scene/object_selection.h"
#include "haptics/voxel/voxel_cache.h"

namespace voxhap {
Voxmap voxelizeObjects(std::span<const SceneObject* const> objects, const VoxelizeOptions& options,
                       const ProgressFn& progress) {
  return voxelizeCached(objects, options, CacheOptions{{}, false}, progress).voxelized.voxmap;
}

Pointshell pointshellOf(const SceneObject& object, const PointshellOptions& options,
                        const ProgressFn& progress) {
  const SceneObject* objects[] = {&object};
  return pointshellCached(objects, options, CacheOptions{{}, false}, progress).pointshell;
}

double pointDisplacementOf(const SceneObject& object, const SceneModelOptions& options) {
  return options.pointDisplacementM.value_or(object.settings.pointOffsetM.value_or(0.0));
}

BuiltScene buildScene(const Scene& scene, const std::vector<std::string>& movingNames,
                      const SceneModelOptions& options, const ProgressFn& progress) {
  const ObjectSelection selection = selectObjects(scene, movingNames);
  const std::vector<const SceneObject*>& moving = selection.picked;
  const std::vector<const SceneObject*>& fixed = selection.rest;
  for (const auto& [name, layer] : options.forceLayerOf) {
    if (std::none_of(moving.begin(), moving.end(), [&](const SceneObject* o) { return o->name == name; }))
      throw Error("a force layer for " + name + ", which is not a moving object");
  }

  const double steps = static_cast<double>(2 * moving.size() + 1);
  auto stage = [&](double k) -> ProgressFn {
    if (!progress) return {};
    return [&progress, k, steps](double f) { progress((k + f) / steps); };
  };
  VoxelizeOptions voxelOptions;
  voxelOptions.encoding = VoxelEncoding::forBits(options.bitsPerField);
  // contact by surface planes reads only the surface field
  voxelOptions.surfacePlanes = options.sim.surfaceContact;
  voxelOptions.buildFeatureFields = options.sim.geometricalAwareness && !voxelOptions.surfacePlanes;
  std::optional<Voxmap> staticVoxmap;
  std::shared_ptr<VoxelPager> staticPager;
  if (!fixed.empty()) {
    voxelOptions.voxelSizeM = options.staticVoxelSizeM;
    if (options.budgetedVoxelizeFn) {
      BudgetedVoxmap budgeted = options.budgetedVoxelizeFn(fixed, voxelOptions, stage(0));
      staticVoxmap = std::move(budgeted.voxmap);
      staticPager = std::move(budgeted.pager);
    } else {
      staticVoxmap = options.voxelizeFn(fixed, voxelOptions, stage(0));
    }
  }
  if (staticPager && !options.sim.coherence.enabled) {
    throw Error(
        "paging the static voxels within a memory budget needs time-critical sampling (not brute force)");
  }

  std::vector<MovingObjectModel> objects;
  for (std::size_t i = 0; i < moving.size(); ++i) {
    const SceneObject& source = *moving[i];
    MovingObjectModel object;
    object.name = source.name;
    object.body =
        makeRigidBodyModel(computeMassProperties(source, objectDensityKgPerM3(source)), source.name);
    PointshellOptions shellOptions;
    shellOptions.pointSpacingM = options.pointSpacingM;
    shellOptions.displacementM = pointDisplacementOf(source, options);
    shellOptions.freeLayer = options.pointFreeLayer;
    shellOptions.onSurface = options.sim.surfaceContact;
    object.shell = options.pointshellFn(source, shellOptions, stage(static_cast<double>(1 + 2 * i)));
    if (moving.size() > 1) {
      voxelOptions.voxelSizeM = options.pointSpacingM;
      const SceneObject* one[] = {&source};
      object.voxmap = options.voxelizeFn(one, voxelOptions, stage(static_cast<double>(2 + 2 * i)));
    }
    object.coupled = true;
    const auto layer = options.forceLayerOf.find(source.name);
    object.forceLayer = layer != options.forceLayerOf.end() ? layer->second : source.settings.forceLayer;
    objects.push_back(std::move(object));
  }
  // the voxmap's arrays that the pager fills stay where they are when the voxmap moves
  return {makeSimModel(std::move(objects), std::move(staticVoxmap), options.sim), std::move(staticPager)};
}

SimModel buildSceneModel(const Scene& scene, const std::vector<std::string>& movingNames,
                         const SceneModelOptions& options, const ProgressFn& progress) {
  BuiltScene built = buildScene(scene, movingNames, options, progress);
  if (built.staticPager) throw Error("the static voxmap is paged: build the scene with buildScene");
  return std::move(built.model);
}

Voxmap movingSurfaceVoxmap(const SceneObject& object, const SceneModelOptions& options,
                           const ProgressFn& progress) {
  VoxelizeOptions voxelOptions;
  voxelOptions.voxelSizeM = options.pointSpacingM;
  voxelOptions.encoding = VoxelEncoding::forBits(options.bitsPerField);
  voxelOptions.buildFeatureFields = false;  // only the surface field is read
  const SceneObject* one[] = {&object};
  return options.voxelizeFn(one, voxelOptions, progress);
}

}  // namespace voxhap

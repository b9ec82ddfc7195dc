#pragma once
/// From a loaded Scene to a SimModel: the static objects merged into one voxmap (the
/// static environment), each named moving object given its rigid body (mass and inertia
/// from its closed meshes), pointshell and voxmap. Load time only; allocates; throws
/// voxhap::Error naming the object.

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "haptics/core/progress.h"
#include "haptics/pointshell/pointshell.h"
#include "haptics/scene/scene.h"
#include "haptics/sim/sim_model.h"
#include "haptics/voxel/voxel_cache.h"
#include "haptics/voxel/voxel_pager.h"
#include "haptics/voxel/voxelizer.h"

namespace voxhap {

/// How to voxelize a set of objects (one voxmap for all of them), e.g. from a cache.
using VoxelizeObjectsFn = std::function<Voxmap(std::span<const SceneObject* const> objects,
                                               const VoxelizeOptions& options, const ProgressFn& progress)>;
/// How to build the pointshell of one object, e.g. from a cache.
using PointshellFn = std::function<Pointshell(const SceneObject& object, const PointshellOptions& options,
                                              const ProgressFn& progress)>;

/// Voxelizes `objects` as one voxmap, now (cache off).
Voxmap voxelizeObjects(std::span<const SceneObject* const> objects, const VoxelizeOptions& options,
                       const ProgressFn& progress);
/// Builds the pointshell of `object`, now (cache off).
Pointshell pointshellOf(const SceneObject& object, const PointshellOptions& options,
                        const ProgressFn& progress);

struct SceneModelOptions {
  SimOptions sim;
  double staticVoxelSizeM = 0.0;  ///< voxel size of the static environment, m
  double pointSpacingM = 0.0;     ///< point spacing (and voxel size) of the moving objects, m
  int bitsPerField = 4;
  /// Every moving object's points displaced along their normals, m (negative: inward;
  /// mating surfaces). Unset: each object's own (ObjectSettings::pointOffsetM).
  std::optional<double> pointDisplacementM;
  /// Force layers of moving objects by name, over their own (ObjectSettings::forceLayer).
  std::map<std::string, std::uint8_t> forceLayerOf;
  /// Take the moving objects' points from this free-space layer (0: the surface).
  int pointFreeLayer = 0;
  VoxelizeObjectsFn voxelizeFn = voxelizeObjects;
  PointshellFn pointshellFn = pointshellOf;
  /// When set, the static environment comes from here instead of voxelizeFn: whole, or
  /// paged within a memory budget (voxel_cache.h, voxelizeWithinBudget).
  std::function<BudgetedVoxmap(std::span<const SceneObject* const> objects, const VoxelizeOptions& options,
                               const ProgressFn& progress)>
      budgetedVoxelizeFn;
};

/// A scene built for simulation: its model, and the pager of its static voxmap when
/// that is paged (for makeSimWorkspace; the model must outlive it).
struct BuiltScene {
  SimModel model;
  std::shared_ptr<VoxelPager> staticPager;
};

/// The displacement of `object`'s points: options.pointDisplacementM when set, else the
/// object's own point offset, else 0.
double pointDisplacementOf(const SceneObject& object, const SceneModelOptions& options);

/// The model of `scene` with `movingNames` moving (each coupled to a handle) and every
/// other object static. A name is an object or a group, whose objects then move merged
/// as one (object_selection.h). Throws voxhap::Error for a name that selectObjects refuses
/// (unknown, repeated, overlapping another), or a moving object whose mesh is not closed.
BuiltScene buildScene(const Scene& scene, const std::vector<std::string>& movingNames,
                      const SceneModelOptions& options, const ProgressFn& progress = {});

/// As buildScene, for a static voxmap that is whole: throws voxhap::Error when
/// options.budgetedVoxelizeFn paged it.
SimModel buildSceneModel(const Scene& scene, const std::vector<std::string>& movingNames,
                         const SceneModelOptions& options, const ProgressFn& progress = {});

/// The surface voxmap of moving object `object` alone, local frame, at options.pointSpacingM
/// through options.voxelizeFn (so its cache), without feature fields: what a moving object
/// that is no pair's voxmap needs for proximity and exact checks.
Voxmap movingSurfaceVoxmap(const SceneObject& object, const SceneModelOptions& options,
                           const ProgressFn& progress = {});

}  // namespace voxhap

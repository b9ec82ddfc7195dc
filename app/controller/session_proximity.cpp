#include "app/controller/session_proximity.h"

#include "haptics/collide/proximity.h"

namespace voxhap::controller {

SessionProximity::SessionProximity(const ObjectSelection& selection, const SimModel& model,
                                   const SceneModelOptions& options, const ProgressFn& progress)
    : model_(model) {
  if (!model.staticVoxmap) {
    unavailable_ = "the scene has no static objects";
  } else if (model.staticVoxmap->isPaged()) {
    unavailable_ = "the static scene is paged (--voxel-memory): its voxels are the haptic thread's";
  }
  const std::size_t n = model.objects.size();
  verticesLocal_.resize(n);
  movingVoxmaps_.resize(n, nullptr);
  for (std::size_t i = 0; i < n; ++i) {
    // the scene places each object where its local frame is: mesh positions are local
    for (const Part& part : selection.picked[i]->parts) {
      const auto& p = part.mesh.positionsWorld;
      verticesLocal_[i].insert(verticesLocal_[i].end(), p.begin(), p.end());
    }
    const Voxmap& own = model.objects[i].voxmap;
    if (own.grid().voxelSizeM > 0.0) {
      movingVoxmaps_[i] = &own;
      continue;
    }
    if (!unavailable_.empty()) continue;
    ProgressFn stage;
    if (progress) {
      stage = [&progress, i, n](double f) {
        progress((static_cast<double>(i) + f) / static_cast<double>(n));
      };
    }
    ownVoxmaps_.push_back(
        std::make_unique<Voxmap>(movingSurfaceVoxmap(*selection.picked[i], options, stage)));
    movingVoxmaps_[i] = ownVoxmaps_.back().get();
  }
  if (progress) progress(1.0);
}

SessionProximity::~SessionProximity() = default;

void SessionProximity::measure(std::size_t object, const Pose& objectWorld, double withinM,
                               ProximityResult& out) const {
  const Voxmap& staticVoxmap = *model_.staticVoxmap;
  vertexDistancesM(verticesLocal_[object], objectWorld, staticVoxmap, out.vertexDistanceM);
  out.staticVoxelSizeM = staticVoxmap.grid().voxelSizeM;
  out.nearStaticVoxelsWorld.clear();
  if (withinM <= 0.0) return;
  std::vector<glm::ivec3> near;
  surfaceVoxelsNear(staticVoxmap, *movingVoxmaps_[object], objectWorld, withinM, near);
  out.nearStaticVoxelsWorld.reserve(near.size());
  for (const glm::ivec3& v : near) out.nearStaticVoxelsWorld.push_back(staticVoxmap.grid().voxelCentre(v));
}

}  // namespace voxhap::controller

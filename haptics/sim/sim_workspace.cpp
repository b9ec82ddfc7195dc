#include "haptics/sim/sim_workspace.h"

#include <algorithm>

#include "haptics/core/error.h"
#include "haptics/sim/pair_geometry.h"

namespace voxhap {

SimWorkspace makeSimWorkspace(const SimModel& model, const SimState& state,
                              std::shared_ptr<VoxelPager> staticPager) {
  const bool paged = model.staticVoxmap && model.staticVoxmap->isPaged();
  if (paged != (staticPager != nullptr)) {
    throw Error(paged ? "the static voxmap is paged: its workspace needs the pager that buildScene made"
                      : "a pager was given for a static voxmap that is not paged");
  }
  if (state.bodies.size() != model.objects.size()) throw Error("the state is not of this model (its bodies)");
  SimWorkspace ws;
  ws.staticPager = std::move(staticPager);
  std::size_t largest = 0;
  std::size_t mostChunks = 0;
  std::size_t rowCapacity = 0;
  for (const MovingObjectModel& object : model.objects) {
    largest = std::max(largest, object.shell.size());
    mostChunks = std::max(mostChunks, object.shell.chunkCount());
  }
  for (const PairModel& pair : model.pairs) {
    rowCapacity += model.objects[static_cast<std::size_t>(pair.shellObject)].shell.size();
  }
  ws.depthScratch = DepthLimitScratch(rowCapacity, model.pairs.size(), model.objects.size());
  ws.beforeStep.resize(model.objects.size());
  ws.travelBoundM.resize(model.objects.size());
  ws.contacts.resize(largest);
  ws.due.resize(largest);
  ws.dueChunks.resize(mostChunks);
  ws.pairFrames.resize(model.pairs.size());
  if (!model.coherence.enabled) return ws;
  for (const PairModel& pair : model.pairs) {
    const MovingObjectModel& shellObject = model.objects[static_cast<std::size_t>(pair.shellObject)];
    const Voxmap& voxmap = model.voxmapOf(pair);
    PairCoherence& coherence = ws.coherence.emplace_back(
        shellObject.shell, voxmap.grid().voxelSizeM, pair.forceLayer(state.forceLayer),
        voxmap.encoding().maxValue(), model.coherence.pointDrifting);
    const Pose shellToVoxmap = shellToVoxmapPose(model, state, pair);
    if (inRange(shellObject, shellToVoxmap, voxmap.grid())) {
      coherence.sortAll(shellObject.shell, voxmap, VoxelTransform::make(shellToVoxmap, voxmap.grid()),
                        pair.fieldShifts, ws.pagerOf(pair));
    } else {
      coherence.skipFrame(0.0);
    }
  }
  return ws;
}

}  // namespace voxhap

#include "haptics/sim/sim_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "haptics/collide/point_sampler.h"
#include "haptics/core/error.h"

namespace voxhap {
namespace {

bool hasVoxels(const Voxmap& voxmap) {
  return voxmap.grid().voxelSizeM > 0.0;
}

/// The inertia a contact on `object` sees at its worst, kg: the smaller of the mass and
/// 1 / max over points r and unit directions u of (r × u)ᵀ·I⁻¹·(r × u), the rotational
/// response of the body to a unit force at r (r from the centre of mass, local frame).
/// With k_total = M·ω_c² no rotation of the body then responds to a contact spring faster
/// than ω_c, however long and thin it is (a bound by I_min / r_max² would make a rod's
/// contacts a hundred times softer than they need be).
double contactInertiaKg(const MovingObjectModel& object) {
  const glm::dmat3& inverseInertia = object.body.inverseInertiaBody;
  double worst = 0.0;
  for (const glm::vec3& p : object.shell.positionsLocal) {
    const glm::dvec3 r = glm::dvec3(p) - object.body.comLocal;
    // [r]x, the matrix of u -> r x u (GLM is column-major)
    const glm::dmat3 cross(0.0, r.z, -r.y, -r.z, 0.0, r.x, r.y, -r.x, 0.0);
    worst = std::max(worst, symmetricEigenvalues(glm::transpose(cross) * inverseInertia * cross).z);
  }
  return worst > 0.0 ? std::min(object.body.massKg, 1.0 / worst) : object.body.massKg;
}

/// The smaller of the force layers that the pair's moving objects have of their own.
std::optional<std::uint8_t> ownForceLayer(const SimModel& model, const PairModel& pair) {
  std::optional<std::uint8_t> layer;
  for (const int i : {pair.shellObject, pair.voxmapObject}) {
    if (i == kStaticEnvironment) continue;
    const std::optional<std::uint8_t> own = model.objects[static_cast<std::size_t>(i)].forceLayer;
    if (own) layer = std::min(layer.value_or(*own), *own);
  }
  return layer;
}

/// Throws voxhap::Error, `whose` leading, when the pair cannot render force layer `forceLayer`.
void checkForceLayer(const SimModel& model, const PairModel& pair, const SimOptions& options,
                     std::uint8_t forceLayer, const std::string& whose) {
  const Voxmap& voxmap = model.voxmapOf(pair);
  if (forceLayer < 1 || forceLayer > voxmap.encoding().maxValue()) {
    throw Error(whose + "force layer " + std::to_string(forceLayer) + " is outside the voxmap's values 1 … " +
                std::to_string(voxmap.encoding().maxValue()));
  }
  if (options.surfaceContact && voxmap.hasSurfacePlanes() && forceLayer < kSurfaceContactForceLayer) {
    throw Error(whose + "force layer " + std::to_string(forceLayer) +
                " does not reach the points that surface contact pushes (at least " +
                std::to_string(kSurfaceContactForceLayer) + ")");
  }
}

ContactParams pairParams(const SimModel& model, const PairModel& pair, const SimOptions& options) {
  const Voxmap& voxmap = model.voxmapOf(pair);
  const std::uint8_t forceLayer = options.forceLayerValue();
  checkForceLayer(model, pair, options, forceLayer, "");
  if (pair.ownForceLayer) {
    const auto nameOf = [&model](int i) {
      return i == kStaticEnvironment ? std::string("the static scene")
                                     : model.objects[static_cast<std::size_t>(i)].name;
    };
    checkForceLayer(model, pair, options, *pair.ownForceLayer,
                    nameOf(pair.shellObject) + " against " + nameOf(pair.voxmapObject) + ": its own ");
  }
  double inertia = contactInertiaKg(model.objects[static_cast<std::size_t>(pair.shellObject)]);
  if (pair.voxmapObject != kStaticEnvironment) {
    inertia = std::min(inertia, contactInertiaKg(model.objects[static_cast<std::size_t>(pair.voxmapObject)]));
  }
  const double omega = kContactFrequencyTimesDt / options.dtS;
  ContactParams params;
  params.forceLayer = forceLayer;
  params.geometricalAwareness = options.geometricalAwareness;
  params.preContactDamping = options.preContactDamping;
  if (options.surfaceContact && voxmap.hasSurfacePlanes()) {
    const Pointshell& shell = model.objects[static_cast<std::size_t>(pair.shellObject)].shell;
    const double voxelM = voxmap.grid().voxelSizeM;
    if (shell.pointSpacingM > 2.0 * voxelM) {
      throw Error("surface contact needs points at most two voxels apart, not " +
                  std::to_string(shell.pointSpacingM / voxelM) + " voxels");
    }
    params.surfaceContactM = kSurfaceContactSpacings * shell.pointSpacingM;
    params.geometricalAwareness = false;
  }
  params.pointStiffnessNPerM = inertia * omega * omega / kStiffContacts;
  params.pointDampingNsPerM = 2.0 * kContactDampingRatio * inertia * omega / kStiffContacts;
  return params;
}

}  // namespace

SimModel makeSimModel(std::vector<MovingObjectModel> objects, std::optional<Voxmap> staticVoxmap,
                      const SimOptions& options) {
  if (!(options.dtS > 0.0) || !std::isfinite(options.dtS)) throw Error("frame period must be positive");
  SimModel model;
  model.dtS = options.dtS;
  model.gravityWorld = options.gravityWorld;
  model.staticVoxmap = std::move(staticVoxmap);
  validateDeviceLimits(options.deviceLimits, "device");
  model.deviceLimits = options.deviceLimits;
  model.coherence = options.coherence;
  if (!(model.coherence.capacityTests >= 0.0) || !std::isfinite(model.coherence.capacityTests)) {
    throw Error("capacity must be a finite number of point tests, or 0 to measure it");
  }
  model.objects = std::move(objects);

  for (MovingObjectModel& object : model.objects) {
    if (object.shell.size() == 0) throw Error(object.name + ": the pointshell has no points");
    object.shellRadiusM = object.shell.radiusAbout(object.body.comLocal);
    Bounds bounds;
    for (const glm::vec3& p : object.shell.positionsLocal) bounds.add(glm::dvec3(p));
    object.shellCentreLocal = 0.5 * (bounds.min + bounds.max);
    object.shellBoundRadiusM = object.shell.radiusAbout(object.shellCentreLocal);
    if (object.coupled) object.gains = defaultCouplingGains(object.body, options.dtS, options.deviceLimits);
  }

  const int n = static_cast<int>(model.objects.size());
  for (int i = 0; i < n; ++i) {
    if (model.staticVoxmap) model.pairs.push_back({i, kStaticEnvironment, {}, {}});
  }
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const MovingObjectModel& a = model.objects[static_cast<std::size_t>(i)];
      const MovingObjectModel& b = model.objects[static_cast<std::size_t>(j)];
      const bool aIsShell = a.shell.size() <= b.shell.size();
      const MovingObjectModel& voxels = aIsShell ? b : a;
      if (!hasVoxels(voxels.voxmap))
        throw Error(voxels.name + ": a moving object needs a voxmap to collide with " +
                    (aIsShell ? a.name : b.name));
      model.pairs.push_back({aIsShell ? i : j, aIsShell ? j : i, {}, {}});
    }
  }
  for (MovingObjectModel& object : model.objects) object.maxTravelM = std::numeric_limits<double>::infinity();
  for (PairModel& pair : model.pairs) {
    pair.ownForceLayer = ownForceLayer(model, pair);
    pair.params = pairParams(model, pair, options);
    const Voxmap& voxmap = model.voxmapOf(pair);
    pair.fieldShifts = fieldShiftsByFeature(pair.params.geometricalAwareness, voxmap.encoding());
    const double share = pair.voxmapObject == kStaticEnvironment ? 0.5 : 0.25;
    pair.nearTravelM = share * voxmap.grid().voxelSizeM;
    pair.farTravelM = share * kChunkEdgeVoxels * voxmap.grid().voxelSizeM;
    for (const int i : {pair.shellObject, pair.voxmapObject}) {
      if (i == kStaticEnvironment) continue;
      double& travel = model.objects[static_cast<std::size_t>(i)].maxTravelM;
      travel = std::min(travel, pair.nearTravelM);
    }
  }
  return model;
}

}  // namespace voxhap

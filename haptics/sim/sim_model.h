#pragma once
/// The read-only model of a haptic simulation (DESIGN §4.7, paper §2.1): the static
/// environment as one voxmap, the moving objects with their rigid-body data,
/// pointshells and voxmaps, and every pair that can touch (paper Eq. 1:
/// n(n−1)/2 among the n moving objects, plus each against the static environment).
/// In a pair of moving objects the one with fewer points is the pointshell.
///
/// Built once at load time (allocates, may throw voxhap::Error), then never changed:
/// shared by every thread as std::shared_ptr<const SimModel>, read by step(). It holds
/// no thread and no per-frame data (SimState, SimWorkspace).

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "haptics/collide/contact_params.h"
#include "haptics/dynamics/rigid_body.h"
#include "haptics/dynamics/virtual_coupling.h"
#include "haptics/pointshell/pointshell.h"
#include "haptics/voxel/voxmap.h"

namespace voxhap {

/// Index that stands for the static environment in a pair.
inline constexpr int kStaticEnvironment = -1;

/// Contact stiffness of a pair, as ω_c·dt: k_total = M·ω_c² with M the smallest inertia
/// a contact force at any point of either body meets (sim_model.cpp), so that neither
/// translation nor rotation of either body sees a contact frequency above ω_c. With the coupling's (ω·dt)² =
/// 0.0625 and damping term 0.5 (virtual_coupling.cpp), a contact at (0.5)² = 0.25 with damping ratio 0.5 adds
/// a = 0.25 and c = 0.5: the sum a + 2c = 1.31 stays far inside the semi-implicit Euler bound a + 2c < 4.
inline constexpr double kContactFrequencyTimesDt = 0.5;
/// Damping ratio of the contact spring at its capped total stiffness.
inline constexpr double kContactDampingRatio = 0.5;

/// One moving object: read-only data.
struct MovingObjectModel {
  std::string name;
  RigidBodyModel body;
  Pointshell shell;                  ///< object-local frame
  Voxmap voxmap;                     ///< object-local frame; empty grid when never the voxmap of a pair
  double shellRadiusM = 0.0;         ///< largest distance of a point from the centre of mass, m
  glm::dvec3 shellCentreLocal{0.0};  ///< centre of the pointshell's bounding sphere, m
  double shellBoundRadiusM = 0.0;    ///< radius of that sphere, m
  /// Upper bound of MaxTravel near contact, the most any of its points may move in a
  /// frame, m: half the finest voxel of its pairs, halved again when both objects of the
  /// pair move (infinite when it has no pair). Far from everything the bound rises
  /// (PairModel::farTravelM); Eq. 2 scales it down when the capacity is short.
  double maxTravelM = 0.0;
  bool coupled = false;  ///< a handle drives it through a virtual coupling
  CouplingGains gains;   ///< of that coupling
  /// The force layer of its pairs (ObjectSettings::forceLayer); unset: the session's.
  std::optional<std::uint8_t> forceLayer;
};

/// One pair that can touch.
struct PairModel {
  int shellObject = 0;                    ///< index of the moving object sampled as points
  int voxmapObject = kStaticEnvironment;  ///< index of the moving object sampled as voxels, or static
  ContactParams params;  ///< its force layer is the session's at the start (SimState::forceLayer)
  /// The pair's own force layer, kept whatever the session's: the smaller of its objects'
  /// (MovingObjectModel::forceLayer) where either has one.
  std::optional<std::uint8_t> ownForceLayer;
  std::array<std::uint8_t, 3> fieldShifts{};  ///< per point feature, from fieldShiftsByFeature
  /// Most each of its objects may move in a frame for this pair's sake, m: half a voxel
  /// of its voxmap while any of its chunks is in range (paper §5), half a chunk while the
  /// pair is out of range or all its chunks are collapsed (§5.1, pair_coherence.h);
  /// halved again when both objects move.
  double nearTravelM = 0.0;
  double farTravelM = 0.0;

  /// The force layer the pair renders with while the session's is `sessionForceLayer`.
  std::uint8_t forceLayer(std::uint8_t sessionForceLayer) const noexcept {
    return ownForceLayer.value_or(sessionForceLayer);
  }
};

/// Time-critical sampling (paper §5, DESIGN §4.5).
struct CoherenceOptions {
  /// Off: every point in range is tested every frame and MaxTravel is its upper bound
  /// (brute force, for comparison).
  bool enabled = true;
  /// Point tests per frame (n_cap of Eq. 2); 0: measured online from the real cost of
  /// each test and the frame's budget (the run is then not bit-reproducible).
  double capacityTests = 0.0;
  /// Share of the frame period that step() may take when the capacity is measured online
  /// (from the caller's timing of whole frames, FrameInputs::previousStepS); the rest is
  /// for devices, the network and the jitter of the clock.
  double testBudgetFraction = 0.5;
  /// Point drifting (paper §5.2): tests of points far from contact skip the voxmap lookup
  /// while their drift since the last lookup leaves two queues of margin.
  bool pointDrifting = true;
};

struct SimModel {
  double dtS = 1e-3;             ///< frame period, s
  glm::dvec3 gravityWorld{0.0};  ///< m/s²; zero: parts are held, not dropped
  /// World frame; none: nothing static collides. When paged (Voxmap::paged), its words
  /// are the residency of a SimWorkspace, written by that workspace's pager alone.
  std::optional<Voxmap> staticVoxmap;
  std::vector<MovingObjectModel> objects;
  std::vector<PairModel> pairs;
  DeviceLimits deviceLimits;
  CoherenceOptions coherence;

  /// The largest force layer every pair's voxmap can render (255 when there is no pair).
  std::uint8_t maxForceLayer() const noexcept {
    std::uint8_t largest = 255;
    for (const PairModel& pair : pairs) largest = std::min(largest, voxmapOf(pair).encoding().maxValue());
    return largest;
  }

  /// Whether a pair's contact is by surface planes (SimOptions::surfaceContact).
  bool usesSurfaceContact() const noexcept {
    return std::any_of(pairs.begin(), pairs.end(),
                       [](const PairModel& pair) { return pair.params.surfaceContactM > 0.0; });
  }

  /// The smallest force layer every pair can take: kSurfaceContactForceLayer with surface
  /// contact (it pushes points in that layer), else 1.
  std::uint8_t minForceLayer() const noexcept { return usesSurfaceContact() ? kSurfaceContactForceLayer : 1; }

  /// Whether `value` is a force layer every pair can take (minForceLayer() … maxForceLayer()).
  bool forceLayerInRange(std::uint8_t value) const noexcept {
    return value >= minForceLayer() && value <= maxForceLayer();
  }

  const Voxmap& voxmapOf(const PairModel& pair) const {
    return pair.voxmapObject == kStaticEnvironment
               ? *staticVoxmap
               : objects[static_cast<std::size_t>(pair.voxmapObject)].voxmap;
  }
};

/// Options of makeSimModel.
struct SimOptions {
  double dtS = 1e-3;
  glm::dvec3 gravityWorld{0.0};
  /// The force layer's voxel value; none: the contact's own (forceLayerValue()).
  std::optional<std::uint8_t> forceLayer;
  bool geometricalAwareness = true;
  bool preContactDamping = false;  ///< see ContactParams
  /// Contact by surface planes where a pair's voxmap has them (ContactParams::
  /// surfaceContactM: kSurfaceContactSpacings of the point spacing of the pair's
  /// pointshell); needs a force layer of at least kSurfaceContactForceLayer. Off: the
  /// paper's voxel tangent planes, the engine's own default; the commands turn it on unless
  /// asked for --paper-contact (app/sim_options.h).
  bool surfaceContact = false;
  DeviceLimits deviceLimits;
  CoherenceOptions coherence;

  /// forceLayer, else kSurfaceContactForceLayer with surface contact and the paper's
  /// kDefaultForceLayer without.
  std::uint8_t forceLayerValue() const noexcept {
    return forceLayer.value_or(surfaceContact ? kSurfaceContactForceLayer : kDefaultForceLayer);
  }
};

/// Completes `objects` (rigid body, pointshell and voxmap set by the caller; `coupled`
/// too) into a model: shell radii, coupling gains, the pairs and their contact
/// stiffness. Throws voxhap::Error when a pair of moving objects lacks the voxmap it
/// needs or the force layer is outside the voxmaps' range.
SimModel makeSimModel(std::vector<MovingObjectModel> objects, std::optional<Voxmap> staticVoxmap,
                      const SimOptions& options);

}  // namespace voxhap

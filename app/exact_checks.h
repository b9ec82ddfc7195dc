#pragma once
/// Exact penetration checks of a running model (haptics/collide/exact_penetration.h), for
/// `voxhap demo`, `voxhap bench extraction` and `voxhap simulate --check-exact`: every
/// moving object against the static scene and every pair of moving objects, measured on
/// the meshes at the objects' current poses, outside the timed frames.
///
/// Filters: the static scene's voxmap, and each moving object's voxmap: the model's when
/// it has one (several objects move), else one voxelized at load through the model's
/// voxelizer (and so its cache) at the moving objects' point spacing, surface field only.

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "haptics/collide/exact_penetration.h"
#include "haptics/core/progress.h"
#include "haptics/scene/object_selection.h"
#include "haptics/scene/scene.h"
#include "haptics/sim/scene_model.h"
#include "haptics/sim/simulation.h"

namespace voxhap::cli {

/// One checked pair and what its last measurement found.
struct ExactPairSample {
  int first = 0;                    ///< moving object index (body A)
  int second = kStaticEnvironment;  ///< moving object index (body B), or the static scene
  PenetrationSample sample;
};

/// The worst of a run of checks.
struct ExactCheckSummary {
  std::uint64_t checks = 0;                 ///< frames measured
  std::uint64_t framesWithPenetration = 0;  ///< of which with some probe inside
  double maxDepthM = 0.0;                   ///< deepest probe over the run, m
  double maxDepthAtS = 0.0;                 ///< when, simulated s
  std::uint64_t maxDepthFrame = 0;          ///< after which frame (SimState::frame, as the trace counts)
  glm::dvec3 maxDepthWorld{0.0};            ///< where, world, m
  std::string maxDepthInto;                 ///< whose surface into what: "actuator into static"
  double minClearanceM = std::numeric_limits<double>::infinity();  ///< least clearance, m
  double minClearanceAtS = 0.0;                                    ///< when, s
  std::uint64_t probes = 0;                                        ///< probes considered, over the run
  std::uint64_t nearProbes = 0;                                    ///< of which looked at one by one
  std::uint64_t candidates = 0;                                    ///< of which took the exact inside test
  double wallS = 0.0;                                              ///< spent measuring, s

  /// Adds the pairs of frame `frame` at simulated time `timeS`.
  void add(const std::vector<ExactPairSample>& pairs,
           const std::vector<std::array<std::string, 2>>& pairNames, std::uint64_t frame, double timeS,
           double wallSpentS);
};

/// `summary` as the `exact_penetration` object of `voxhap simulate --json`: every_frames,
/// checks, probe_spacing_m, max_depth_m, max_depth_voxels (in voxels of `voxelSizeM`),
/// max_depth_frame, max_depth_at_s, max_depth_into, max_depth_world_m (the last four null
/// without penetration), frames_with_penetration, min_clearance_m (null: beyond range),
/// min_clearance_at_s, probes, near_probes, exact_tests, wall_s.
nlohmann::ordered_json exactCheckJson(const ExactCheckSummary& summary, std::uint64_t everyFrames,
                                      double probeSpacingM, double voxelSizeM);

/// The same as aligned text lines.
void printExactChecks(std::ostream& out, const ExactCheckSummary& summary, std::uint64_t everyFrames,
                      double probeSpacingM, double voxelSizeM);

class ExactChecks {
public:
  /// The checks of `model`, built from `scene` with `options` (whose voxelizer gives the
  /// moving objects' voxmaps when the model has none), probes `probeSpacingM` apart.
  /// Throws voxhap::Error when Embree or voxelizing fails.
  ExactChecks(const Scene& scene, const SimModel& model, const SceneModelOptions& options,
              double probeSpacingM, const ProgressFn& progress = {});
  ~ExactChecks();

  /// Measures every pair at the poses of `state`, the clearance too when `withClearance`.
  const std::vector<ExactPairSample>& measure(const SimModel& model, const SimState& state,
                                              bool withClearance = true);
  /// Measures every pair at the poses of `state` and adds it to `summary` with the wall
  /// time it took.
  void check(const SimModel& model, const SimState& state, ExactCheckSummary& summary,
             bool withClearance = true);

  /// Per pair, the names of body A and body B ("static" for the static scene).
  const std::vector<std::array<std::string, 2>>& pairNames() const { return names_; }
  /// Probes of moving object `object`'s surface (probed whole at load).
  std::size_t movingProbes(std::size_t object) const;
  double probeSpacingM() const { return spacingM_; }

private:
  struct Pair;
  ObjectSelection selection_;  // the moving objects' meshes (merged groups owned here)
  double spacingM_;
  std::vector<std::unique_ptr<Voxmap>> ownVoxmaps_;
  std::vector<std::unique_ptr<Pair>> pairs_;
  std::vector<std::array<std::string, 2>> names_;
  std::vector<std::size_t> movingProbes_;
  std::vector<ExactPairSample> samples_;
};

}  // namespace voxhap::cli

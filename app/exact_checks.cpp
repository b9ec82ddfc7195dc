#include "app/exact_checks.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "app/cli/number_format.h"
#include "haptics/core/error.h"

namespace voxhap::cli {

struct ExactChecks::Pair {
  int first = 0;
  int second = kStaticEnvironment;
  std::unique_ptr<ExactPenetration> truth;
};

void ExactCheckSummary::add(const std::vector<ExactPairSample>& pairs,
                            const std::vector<std::array<std::string, 2>>& pairNames, std::uint64_t frame,
                            double timeS, double wallSpentS) {
  ++checks;
  wallS += wallSpentS;
  bool anyInside = false;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const PenetrationSample& s = pairs[p].sample;
    anyInside = anyInside || s.inside > 0;
    probes += s.probes;
    nearProbes += s.nearProbes;
    candidates += s.candidates;
    if (s.depthM > maxDepthM) {
      maxDepthM = s.depthM;
      maxDepthAtS = timeS;
      maxDepthFrame = frame;
      maxDepthWorld = s.deepestWorld;
      const bool aIntoB = s.direction == PenetrationDirection::AIntoB;
      maxDepthInto = pairNames[p][aIntoB ? 0 : 1] + " into " + pairNames[p][aIntoB ? 1 : 0];
    }
    if (s.clearanceM < minClearanceM) {
      minClearanceM = s.clearanceM;
      minClearanceAtS = timeS;
    }
  }
  framesWithPenetration += anyInside ? 1 : 0;
}

nlohmann::ordered_json exactCheckJson(const ExactCheckSummary& summary, std::uint64_t everyFrames,
                                      double probeSpacingM, double voxelSizeM) {
  const bool penetrated = summary.maxDepthM > 0.0;
  auto orNull = [penetrated](nlohmann::ordered_json value) {
    return penetrated ? value : nlohmann::ordered_json();
  };
  const glm::dvec3& w = summary.maxDepthWorld;
  return {
      {"every_frames", everyFrames},
      {"checks", summary.checks},
      {"probe_spacing_m", probeSpacingM},
      {"max_depth_m", summary.maxDepthM},
      {"max_depth_voxels", summary.maxDepthM / voxelSizeM},
      {"max_depth_frame", orNull(summary.maxDepthFrame)},
      {"max_depth_at_s", orNull(summary.maxDepthAtS)},
      {"max_depth_into", orNull(summary.maxDepthInto)},
      {"max_depth_world_m", orNull({w.x, w.y, w.z})},
      {"frames_with_penetration", summary.framesWithPenetration},
      {"min_clearance_m", std::isinf(summary.minClearanceM) ? nlohmann::ordered_json()
                                                            : nlohmann::ordered_json(summary.minClearanceM)},
      {"min_clearance_at_s", summary.minClearanceAtS},
      {"probes", summary.probes},
      {"near_probes", summary.nearProbes},
      {"exact_tests", summary.candidates},
      {"wall_s", summary.wallS}};
}

void printExactChecks(std::ostream& out, const ExactCheckSummary& summary, std::uint64_t everyFrames,
                      double probeSpacingM, double voxelSizeM) {
  out << "exact depth     " << fixed(summary.maxDepthM * 1e3, 3) << " mm ("
      << fixed(summary.maxDepthM / voxelSizeM, 2) << " voxels of " << fixed(voxelSizeM * 1e3, 3) << " mm)";
  if (summary.maxDepthM > 0.0) {
    out << " after frame " << summary.maxDepthFrame << " (t = " << fixed(summary.maxDepthAtS, 3) << " s), "
        << summary.maxDepthInto;
  }
  out << "; " << summary.framesWithPenetration << " of " << summary.checks << " checks had a probe inside\n"
      << "exact clearance "
      << (std::isinf(summary.minClearanceM)
              ? std::string("more than ") + std::to_string(kClearanceVoxels) + " voxels"
              : fixed(summary.minClearanceM * 1e3, 3) + " mm at t = " + fixed(summary.minClearanceAtS, 3) +
                    " s")
      << "\nexact checks    " << summary.checks << " ("
      << (everyFrames == 1 ? std::string("every frame from 0")
                           : "frames 0, " + std::to_string(everyFrames) + ", " +
                                 std::to_string(2 * everyFrames) + ", … and the last")
      << "), probes " << fixed(probeSpacingM * 1e3, 3) << " mm apart, " << fixed(summary.wallS, 2) << " s\n";
}

ExactChecks::ExactChecks(const Scene& scene, const SimModel& model, const SceneModelOptions& options,
                         double probeSpacingM, const ProgressFn& progress)
    : spacingM_(probeSpacingM) {
  // the moving objects as the model picked them (a group merged into one), the rest static
  std::vector<std::string> names;
  for (const MovingObjectModel& object : model.objects) names.push_back(object.name);
  selection_ = selectObjects(scene, names);
  const std::vector<const SceneObject*>& moving = selection_.picked;
  ExactBody staticBody;
  for (const SceneObject* object : selection_.rest) {
    for (const Part& part : object->parts) staticBody.meshesLocal.push_back(&part.mesh);
  }
  if (model.staticVoxmap) staticBody.voxmapLocal = &*model.staticVoxmap;

  const double steps = static_cast<double>(2 * moving.size() + 1);
  std::vector<ExactBody> bodies(moving.size());
  for (std::size_t i = 0; i < moving.size(); ++i) {
    for (const Part& part : moving[i]->parts) bodies[i].meshesLocal.push_back(&part.mesh);
    const Voxmap& own = model.objects[i].voxmap;
    if (own.grid().voxelSizeM > 0.0) {
      bodies[i].voxmapLocal = &own;
      continue;
    }
    ProgressFn stage;
    if (progress) stage = [&progress, i, steps](double f) { progress((static_cast<double>(i) + f) / steps); };
    ownVoxmaps_.push_back(std::make_unique<Voxmap>(movingSurfaceVoxmap(*moving[i], options, stage)));
    bodies[i].voxmapLocal = ownVoxmaps_.back().get();
  }

  movingProbes_.assign(moving.size(), 0);
  auto addPair = [&](int first, int second) {
    auto pair = std::make_unique<Pair>();
    pair->first = first;
    pair->second = second;
    const ExactBody& b = second == kStaticEnvironment ? staticBody : bodies[static_cast<std::size_t>(second)];
    pair->truth =
        std::make_unique<ExactPenetration>(bodies[static_cast<std::size_t>(first)], b, probeSpacingM);
    movingProbes_[static_cast<std::size_t>(first)] = pair->truth->probeCount(0);
    if (second != kStaticEnvironment)
      movingProbes_[static_cast<std::size_t>(second)] = pair->truth->probeCount(1);
    names_.push_back({model.objects[static_cast<std::size_t>(first)].name,
                      second == kStaticEnvironment ? std::string("static")
                                                   : model.objects[static_cast<std::size_t>(second)].name});
    samples_.push_back({first, second, {}});
    pairs_.push_back(std::move(pair));
    if (progress) progress((static_cast<double>(moving.size()) + static_cast<double>(pairs_.size())) / steps);
  };
  for (std::size_t i = 0; i < moving.size(); ++i) {
    if (!staticBody.meshesLocal.empty()) addPair(static_cast<int>(i), kStaticEnvironment);
    for (std::size_t j = i + 1; j < moving.size(); ++j) addPair(static_cast<int>(i), static_cast<int>(j));
  }
  if (progress) progress(1.0);
}

ExactChecks::~ExactChecks() = default;

const std::vector<ExactPairSample>& ExactChecks::measure(const SimModel& model, const SimState& state,
                                                         bool withClearance) {
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const Pair& pair = *pairs_[p];
    const Pose a = objectPose(model, state, static_cast<std::size_t>(pair.first));
    const Pose b = pair.second == kStaticEnvironment
                       ? Pose{}
                       : objectPose(model, state, static_cast<std::size_t>(pair.second));
    samples_[p].sample = pair.truth->measure(a, b, withClearance);
  }
  return samples_;
}

void ExactChecks::check(const SimModel& model, const SimState& state, ExactCheckSummary& summary,
                        bool withClearance) {
  const auto start = std::chrono::steady_clock::now();
  measure(model, state, withClearance);
  const double wallS = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary.add(samples_, names_, state.frame, state.timeS, wallS);
}

std::size_t ExactChecks::movingProbes(std::size_t object) const {
  return movingProbes_[object];
}

}  // namespace voxhap::cli

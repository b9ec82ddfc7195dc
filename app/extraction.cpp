#include "app/extraction.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "haptics/core/error.h"
#include "haptics/scene/object_selection.h"
#include "haptics/voxel/voxel_encoding.h"

namespace voxhap::cli {
namespace {

/// A polyline with arc-length projection.
class PathLine {
public:
  explicit PathLine(std::vector<glm::dvec3> points) : points_(std::move(points)) {
    lengthAt_.push_back(0.0);
    for (std::size_t i = 1; i < points_.size(); ++i) {
      lengthAt_.push_back(lengthAt_.back() + glm::length(points_[i] - points_[i - 1]));
    }
  }
  double length() const { return lengthAt_.back(); }
  /// Arc length of the point of the line nearest `p`.
  double progressOf(const glm::dvec3& p) const {
    double best = 0.0;
    double bestDistance = glm::length(p - points_[0]);
    for (std::size_t i = 1; i < points_.size(); ++i) {
      const glm::dvec3 d = points_[i] - points_[i - 1];
      const double l2 = glm::dot(d, d);
      const double u = l2 > 0.0 ? std::clamp(glm::dot(p - points_[i - 1], d) / l2, 0.0, 1.0) : 0.0;
      const double distance = glm::length(p - (points_[i - 1] + u * d));
      if (distance < bestDistance) {
        bestDistance = distance;
        best = lengthAt_[i - 1] + u * std::sqrt(l2);
      }
    }
    return best;
  }

private:
  std::vector<glm::dvec3> points_;
  std::vector<double> lengthAt_;
};

/// True when no point of `shell` at `pose` is within the static distance field.
bool clearOfEverything(const Pointshell& shell, const Pose& pose, const Voxmap& staticVoxmap) {
  return std::all_of(shell.positionsLocal.begin(), shell.positionsLocal.end(), [&](const glm::vec3& p) {
    return staticVoxmap.value(staticVoxmap.grid().voxelOf(apply(pose, glm::dvec3(p))), Field::Surface) ==
           kValueFar;
  });
}

}  // namespace

std::filesystem::path extractionScriptPath() {
  return std::filesystem::path(VOXHAP_ASSET_DIR) / "scripts" / "actuator-extract.txt";
}

ExtractionResult runExtraction(const Scene& scene, const MotionScript& script,
                               const ExtractionOptions& options, Console& console) {
  const auto wallStart = std::chrono::steady_clock::now();
  const std::vector<std::string> moving = {options.moving};
  const ObjectSelection selection = selectObjects(scene, moving);  // an object, or a group merged
  const SceneObject* actuator = selection.picked[0];

  BuiltScene built =
      buildScene(scene, moving, options.model, console.progress(options.label + ": preparing voxels"));
  const SimModel& model = built.model;
  if (!model.staticVoxmap)
    throw Error(scene.sourceName + ": nothing static to extract " + options.moving + " from");
  const Voxmap& staticVoxmap = *model.staticVoxmap;

  const double spacingM =
      options.probeSpacingM > 0.0 ? options.probeSpacingM : options.model.staticVoxelSizeM / kProbesPerVoxel;
  ExactChecks truth(scene, model, options.model, spacingM,
                    console.progress(options.label + ": preparing probes"));

  // the path of the actuator's centre, through the script's keyframes
  const Bounds bounds = actuator->bounds();
  const glm::dvec3 centreLocal = 0.5 * (bounds.min + bounds.max);
  std::vector<glm::dvec3> keyPoints;
  for (const MotionKeyframe& k : script.keyframes()) keyPoints.push_back(apply(k.handleWorld, centreLocal));
  const PathLine path(std::move(keyPoints));

  ExtractionResult r;
  r.points = model.objects[0].shell.positionsLocal.size();
  r.probesChecked = truth.movingProbes(0);
  r.probeSpacingM = spacingM;
  r.durationS = options.durationS.value_or(script.durationS());
  r.pathLengthM = path.length();
  const auto frames = static_cast<std::uint64_t>(std::llround(r.durationS / model.dtS));
  const std::uint64_t every = std::max<std::uint64_t>(options.penetrationEvery, 1);

  ScriptedDevice device(script, model.deviceLimits);
  HapticDevice* devices[] = {&device};
  LocalSimulation sim(model, std::move(built.staticPager));
  const SimState& state = sim.state;
  bool clear = false;
  // The states to measure are kept and measured after the run: probing between frames
  // evicts the frame's data from the caches, which slows the next frames, lowers the
  // online capacity and so changes the motion being measured.
  std::vector<SimState> toMeasure;
  toMeasure.reserve(static_cast<std::size_t>(frames / every + 2));
  const auto framesStart = std::chrono::steady_clock::now();
  runFrames(sim, devices, frames, r.stats, console.progress(options.label + ": simulating"),
            [&](std::uint64_t f, double) {
              const bool last = f + 1 == frames;
              const Pose pose = objectPose(model, state, 0);
              if (f % every == 0 || last) toMeasure.push_back(state);
              if (f % kClearCheckEveryFrames == 0 || last) {
                const bool nowClear = clearOfEverything(model.objects[0].shell, pose, staticVoxmap);
                if (nowClear && !clear) r.completionS = state.timeS;
                if (!nowClear) r.completionS.reset();
                clear = nowClear;
              }
            });
  r.framesWallS = std::chrono::duration<double>(std::chrono::steady_clock::now() - framesStart).count();
  const ProgressFn measuring = console.progress(options.label + ": measuring exact penetration");
  for (std::size_t i = 0; i < toMeasure.size(); ++i) {
    truth.check(model, toMeasure[i], r.exact);
    if (measuring && (i % 100 == 0 || i + 1 == toMeasure.size()))
      measuring(static_cast<double>(i + 1) / static_cast<double>(toMeasure.size()));
  }

  const Pose handle = script.sample(state.timeS);
  const glm::dvec3 handleCentre = apply(handle, centreLocal);
  const glm::dvec3 actuatorCentre = apply(objectPose(model, state, 0), centreLocal);
  r.handleProgressM = path.progressOf(handleCentre);
  r.actuatorProgressM = path.progressOf(actuatorCentre);
  r.finalLagM = glm::length(handleCentre - actuatorCentre);
  r.wallS = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
  return r;
}

}  // namespace voxhap::cli

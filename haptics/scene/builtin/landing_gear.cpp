// Landing gear: a maintenance scene of the paper's landing-gear class (DESIGN §6).
//
// Layout (world, metres, z up as exported from CAD; x fore-aft, y across, ground z = 0).
// Static triangles ≈ 2.71 M, the same for every seed:
// * main-strut (53 k): a vertical shock strut on x = y = 0 (cylinder r 0.165 m from z 1.75
//   to 4.26 with collars, chromed piston below), an axle yoke at z 0.66, torque links in
//   front (+x), and a trunnion beam along x at z 4.38 spanning x ∈ [-2.05, 2.05] with two
//   airframe fittings on top reaching z 4.8.
// * drag-brace (18 k): from the strut at z 2.30 aft and up via a knee at (-0.95, 0, 3.20)
//   to a lug under the trunnion at x -1.60, plus a lock link; side-brace (7 k): from the
//   strut at z 2.62 out and up to an airframe fitting at y -0.85.
// * wheel-and-brake (1.24 M): two grooved tyres (lathes) on an axle along y at z 0.66,
//   wheel centres y ±0.71, rims, brake housings, pistons and eight-disc stacks, axle nuts
//   reaching y ±0.95.
// * hydraulic-lines (0.93 M): brake lines routed by the seed down the aft side of the
//   strut to the brakes, with clamps; two wire bundles down its front quarters; ten coiled
//   hoses (helical tubes); and six fixed lines alongside the actuator (see below).
// * brackets (24 k): the actuator's two clevises, its collar on the strut, the post that
//   carries the rod-end clevis, the brace beneath the actuator, clamp bands on the braces
//   and post, and the plates of the seed-placed equipment on the strut.
// * bolts (0.42 M): hex bolts with washers on collars, fittings, rims, brakes, lugs, bands
//   and brackets; through bolts with nuts in the brace lugs. equipment (12 k): sensors.
// * actuator (dynamic, 40,840 triangles, 8 parts): a hydraulic actuator 0.90 × 0.20 ×
//   0.20 m lying along x at z 3.30, in front of the strut: head-end eye at x 0.30, rod-end
//   eye at x 1.13, eye axes vertical. Each eye sits between an upper and a lower clevis
//   plate (gap 6 mm each side, pins removed); the head-end clevis stands on a collar round
//   the strut, the rod-end one on a post hanging from the trunnion at x 1.38. A brace runs
//   below the actuator (z 3.08) from strut to post; three hydraulic lines run along x on
//   each side of it at y ±0.32 (z 3.22, 3.30, 3.38), each rising to the trunnion.
//
// Extraction path (extractionPathM): the eyes can only leave their clevises sideways, and
// straight sideways the lines are in the way, straight down the plates and the brace are.
// Slide 0.16 m toward -y (eyes out of the clevises, the actuator now beside the brace),
// drop 0.36 m (below the lines, beside the brace), then leave toward -y under the lines.
// Every fixed piece keeps ≥ 6 mm from the actuator on that path; seed-dependent pieces
// are kept ≥ 30 mm from the boxes swept by it (GearBuilder::clearOfKeepOut). No straight
// pull along an axis frees it (the tests check both).
//
// Same seed, same bytes: randomness comes from splitmix64 (Rng) with our own conversion
// to double, never from std:: distributions.

#include <algorithm>
#include <iterator>
#include <utility>

#include "haptics/scene/builtin/builtin_scenes.h"
#include "haptics/scene/builtin/landing_gear_parts.h"

namespace voxhap {
namespace landing_gear {
namespace {

/// Actuator bounding box in its local frame, m.
constexpr glm::dvec3 kActuatorLocalMin{-kEyeOuterRadiusM, -kActuatorHalfWidthM, -kActuatorHalfWidthM};
constexpr glm::dvec3 kActuatorLocalMax{kEyeSpacingM + kEyeOuterRadiusM, kActuatorHalfWidthM,
                                       kActuatorHalfWidthM};
/// Distance kept between seed-dependent pieces and the actuator's swept boxes, m.
constexpr double kKeepOutMarginM = 0.030;

}  // namespace

std::vector<glm::dvec3> extractionPathM() {
  return {{0.0, 0.0, 0.0}, {0.0, -0.16, 0.0}, {0.0, -0.16, -0.36}, {0.0, -1.25, -0.36}};
}

std::uint64_t Rng::next() {
  state_ += 0x9E3779B97F4A7C15ull;
  std::uint64_t z = state_;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double Rng::uniform() {
  return static_cast<double>(next() >> 11) * 0x1.0p-53;
}

std::uint32_t Rng::below(std::uint32_t n) {
  return static_cast<std::uint32_t>((next() >> 32) * n >> 32);
}

bool Box::overlaps(const Box& other) const {
  return min.x <= other.max.x && other.min.x <= max.x && min.y <= other.max.y && other.min.y <= max.y &&
         min.z <= other.max.z && other.min.z <= max.z;
}

Box Box::inflated(double marginM) const {
  return {min - glm::dvec3(marginM), max + glm::dvec3(marginM)};
}

GearBuilder::GearBuilder(std::uint64_t seed) : rng_(seed) {
  const std::vector<glm::dvec3> path = extractionPathM();
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const glm::dvec3 a = kActuatorOriginWorld + path[i];
    const glm::dvec3 b = kActuatorOriginWorld + path[i + 1];
    const Box swept{glm::min(a, b) + kActuatorLocalMin, glm::max(a, b) + kActuatorLocalMax};
    keepOut_.push_back(swept.inflated(kKeepOutMarginM));
  }
}

TriangleMesh& GearBuilder::part(const std::string& objectName, const std::string& partName,
                                const glm::vec4& color, ObjectRole role) {
  auto object = std::find_if(objects_.begin(), objects_.end(),
                             [&](const ObjectDraft& o) { return o.name == objectName; });
  if (object == objects_.end()) {
    objects_.push_back({objectName, role, {}});
    object = std::prev(objects_.end());
  }
  auto found = std::find_if(object->parts.begin(), object->parts.end(),
                            [&](const PartDraft& p) { return p.name == partName; });
  if (found == object->parts.end()) {
    object->parts.push_back({partName, color, {}});
    found = std::prev(object->parts.end());
  }
  return found->mesh;
}

bool GearBuilder::clearOfKeepOut(const Box& box) const {
  return std::none_of(keepOut_.begin(), keepOut_.end(), [&](const Box& k) { return k.overlaps(box); });
}

bool GearBuilder::placeClear(TriangleMesh& mesh, const std::function<void(Rng&, TriangleMesh&)>& attempt,
                             int maxAttempts) {
  const std::size_t vertexCount = mesh.positionsWorld.size();
  const std::size_t triangleCount = mesh.triangles.size();
  for (int i = 0; i < maxAttempts; ++i) {
    attempt(rng_, mesh);
    Box bounds{glm::dvec3(1e300), glm::dvec3(-1e300)};
    for (std::size_t v = vertexCount; v < mesh.positionsWorld.size(); ++v) {
      const glm::dvec3 p(mesh.positionsWorld[v]);
      bounds.min = glm::min(bounds.min, p);
      bounds.max = glm::max(bounds.max, p);
    }
    if (clearOfKeepOut(bounds)) return true;
    mesh.positionsWorld.resize(vertexCount);
    mesh.triangles.resize(triangleCount);
  }
  return false;
}

std::deque<ObjectDraft> GearBuilder::takeObjects() {
  return std::exchange(objects_, {});
}

}  // namespace landing_gear

Scene makeLandingGear(std::uint64_t seed, const ProgressFn& progress) {
  double reported = 0.0;
  auto report = [&](double fraction) {
    reported = std::max(reported, std::min(fraction, 1.0));
    if (progress) progress(reported);
  };
  report(0.0);

  // generating the geometry takes about a third of the time, checking it (makePart) the rest
  landing_gear::GearBuilder gear(seed);
  using BuildStep = void (*)(landing_gear::GearBuilder&);
  const BuildStep steps[] = {landing_gear::buildActuator,        landing_gear::buildActuatorSurroundings,
                             landing_gear::buildMainStrut,       landing_gear::buildBraces,
                             landing_gear::buildWheelsAndBrakes, landing_gear::buildHydraulicLines,
                             landing_gear::buildFasteners};
  constexpr double kBuildShare = 0.3;
  const double stepCount = static_cast<double>(std::size(steps));
  for (std::size_t i = 0; i < std::size(steps); ++i) {
    steps[i](gear);
    report(kBuildShare * static_cast<double>(i + 1) / stepCount);
  }

  std::deque<landing_gear::ObjectDraft> drafts = gear.takeObjects();
  std::size_t totalTriangles = 0;
  for (const auto& object : drafts) {
    for (const auto& part : object.parts) totalTriangles += part.mesh.triangles.size();
  }
  Scene scene;
  scene.sourceName = "landing-gear";
  std::size_t doneTriangles = 0;
  for (auto& draft : drafts) {
    SceneObject object;
    object.name = draft.name;
    object.settings.role = draft.role;
    for (auto& part : draft.parts) {
      doneTriangles += part.mesh.triangles.size();
      object.parts.push_back(makePart(part.name, part.color, std::move(part.mesh)));
      report(kBuildShare + (1.0 - kBuildShare) * static_cast<double>(doneTriangles) /
                               static_cast<double>(std::max<std::size_t>(totalTriangles, 1)));
    }
    scene.objects.push_back(std::move(object));
  }
  report(1.0);
  return scene;
}

}  // namespace voxhap

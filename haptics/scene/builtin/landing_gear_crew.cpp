// The landing gear for a crew of three: the gear with its actuator, a spare actuator and
// a spare hose, each for one user of a type-1 session (DESIGN §8).

#include <array>

#include "haptics/geometry/mesh_builder.h"
#include "haptics/scene/builtin/builtin_scenes.h"
#include "haptics/scene/builtin/landing_gear_parts.h"

namespace voxhap {
namespace {

constexpr glm::vec4 kHoseSilver{0.70f, 0.72f, 0.74f, 1.0f};
constexpr glm::vec4 kFittingBrass{0.78f, 0.62f, 0.28f, 1.0f};

SceneObject spareActuator(const SceneObject& actuator) {
  SceneObject spare;
  spare.name = "spare-actuator";
  spare.settings = actuator.settings;
  const glm::vec3 offset(landing_gear::kSpareActuatorOffsetM);
  for (const Part& part : actuator.parts) {
    TriangleMesh mesh = part.mesh;
    for (glm::vec3& p : mesh.positionsWorld) p += offset;
    spare.parts.push_back(makePart(part.name, part.baseColor, std::move(mesh)));
  }
  return spare;
}

/// A U of rigid line along x, opening upward, with a hex fitting on each end.
SceneObject spareHose() {
  using namespace landing_gear;
  constexpr double kLeftXM = 0.45;
  constexpr double kRightXM = 1.00;
  constexpr double kEndZM = kSpareHoseBottomZM + 0.15;
  const std::array<glm::dvec3, 4> corners = {glm::dvec3{kLeftXM, kSpareHoseYM, kEndZM},
                                             {kLeftXM, kSpareHoseYM, kSpareHoseBottomZM},
                                             {kRightXM, kSpareHoseYM, kSpareHoseBottomZM},
                                             {kRightXM, kSpareHoseYM, kEndZM}};
  TriangleMesh tube;
  appendPathTube(tube, glm::dmat4(1.0), filletedPolyline(corners, 0.05, 12), kSpareHoseRadiusM, 24);
  // each fitting a solid of its own part (ray parity per part), over the tube's end
  TriangleMesh fittings;
  for (const double x : {kLeftXM, kRightXM}) {
    appendHexPrism(fittings, frameAlongAxis({x, kSpareHoseYM, kEndZM - 0.03}, {0.0, 0.0, 1.0}), 0.032, 0.04);
  }
  SceneObject hose;
  hose.name = "spare-hose";
  hose.settings.role = ObjectRole::Dynamic;
  hose.parts.push_back(makePart("hose-line", kHoseSilver, std::move(tube)));
  hose.parts.push_back(makePart("hose-fittings", kFittingBrass, std::move(fittings)));
  return hose;
}

}  // namespace

Scene makeLandingGearCrew(std::uint64_t seed, const ProgressFn& progress) {
  Scene scene = makeLandingGear(seed, progress);
  scene.sourceName = "landing-gear-crew";
  scene.objects.push_back(spareActuator(*scene.find("actuator")));
  scene.objects.push_back(spareHose());
  return scene;
}

}  // namespace voxhap

#include "haptics/scene/builtin/builtin_scenes.h"

#include "haptics/core/error.h"

namespace voxhap {

std::vector<std::string> builtinSceneNames() {
  return {"ball-and-socket", "small-ball-and-socket", "peg-in-hole", "landing-gear", "landing-gear-crew"};
}

Scene makeBuiltinScene(const std::string& name, std::uint64_t seed, const ProgressFn& progress) {
  if (name == "ball-and-socket") return makeBallAndSocket();
  if (name == "small-ball-and-socket") {
    Scene scene = makeBallAndSocket(0.5 * kBallAndSocketRadiusM);
    scene.sourceName = name;
    return scene;
  }
  if (name == "peg-in-hole") return makePegInHole();
  if (name == "landing-gear") return makeLandingGear(seed, progress);
  if (name == "landing-gear-crew") return makeLandingGearCrew(seed, progress);
  std::string known;
  for (const std::string& candidate : builtinSceneNames()) {
    known += (known.empty() ? "" : ", ") + candidate;
  }
  throw Error("unknown built-in scene '" + name + "' (known: " + known + ")");
}

}  // namespace voxhap

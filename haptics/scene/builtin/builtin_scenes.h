#pragma once
/// Built-in scenes, generated procedurally and deterministically.
///
/// Small ones (ball-and-socket, peg-in-hole) are also committed as .glb under
/// `assets/`; the landing gear (≈ 2.7 M triangles) is generated on demand and
/// cached by the command line. Every mesh is closed and consistently oriented.
/// Coordinates are metres; the landing gear is Z-up, as exported from CAD.

#include <cstdint>
#include <string>
#include <vector>

#include "haptics/core/progress.h"
#include "haptics/scene/scene.h"

namespace voxhap {

/// The paper's ball radius (§7), m.
inline constexpr double kBallAndSocketRadiusM = 0.025;

/// Ball (radius `ballRadiusM`, 2048 triangles, dynamic) seated in a socket (≈ 2,176
/// triangles, static) whose spherical cavity has the ball's radius; every length scales
/// with the radius. The paper's text gives 25 mm (`ball-and-socket`), its Table 1's point
/// counts are those of 12.5 mm (`small-ball-and-socket`, DESIGN §6).
Scene makeBallAndSocket(double ballRadiusM = kBallAndSocketRadiusM);

/// A peg (dynamic) above a block (static) whose hole leaves ≈ 0.2 mm of radial
/// clearance, axes aligned, the peg's tip at the hole's mouth.
Scene makePegInHole();

/// A maintenance scene of landing-gear class: ≈ 4.1 × 1.9 × 4.8 m, ≈ 2.7 M static
/// triangles (struts, brackets, straight and helical tubes, bolts, a wheel-and-brake
/// stand-in) and a hydraulic actuator (≈ 0.9 × 0.2 × 0.2 m, ≈ 40,000 triangles,
/// dynamic, several coloured parts) installed among them. Same seed, same scene.
Scene makeLandingGear(std::uint64_t seed, const ProgressFn& progress = {});

/// The landing gear for a crew of three (type-1 sessions): makeLandingGear's scene, its
/// actuator to be pulled out as before, and two more dynamic objects waiting beyond the
/// gear's -y side, clear of it and of the extraction path: a spare actuator below where
/// the old one comes out and a spare hydraulic hose (a U of rigid line with end
/// fittings) above it. Same static objects, so the same static voxels (and cache).
Scene makeLandingGearCrew(std::uint64_t seed, const ProgressFn& progress = {});

/// The names accepted by makeBuiltinScene, in the order `--help` lists them.
std::vector<std::string> builtinSceneNames();

/// The built-in scene of that name ("ball-and-socket", "peg-in-hole", "landing-gear",
/// "landing-gear-crew"); the seed only matters to the landing gears.
/// Throws voxhap::Error naming the known scenes when the name is unknown.
Scene makeBuiltinScene(const std::string& name, std::uint64_t seed, const ProgressFn& progress = {});

}  // namespace voxhap

#pragma once
/// Internals of the landing-gear generator (landing_gear*.cpp): the layout constants
/// that the actuator, its surroundings and the tests share, a seeded random source, and a
/// builder that collects parts into objects while keeping seed-dependent clutter out of
/// the actuator's installed envelope and extraction corridor.
///
/// World frame: metres, z up, ground at z = 0, the main strut's axis is x = y = 0, the
/// axle runs along y. See the note at the top of landing_gear.cpp for the whole layout.

#include <cstdint>
#include <deque>
#include <functional>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "haptics/scene/scene.h"

namespace voxhap::landing_gear {

/// Where the actuator's local origin (the head-end eye's centre) sits when installed,
/// world, m. The actuator is not rotated: local x runs from the head-end eye to the
/// rod-end eye, local z is the eyes' (pin) axis.
inline constexpr glm::dvec3 kActuatorOriginWorld{0.30, 0.0, 3.30};
/// Distance between the two eyes' centres along local x, m.
inline constexpr double kEyeSpacingM = 0.83;
/// Outer radius and half height of both eyes, m.
inline constexpr double kEyeOuterRadiusM = 0.035;
inline constexpr double kEyeHalfHeightM = 0.020;
/// Bore of the eyes and of the clevis plates (the pins are out), m.
inline constexpr double kEyeBoreRadiusM = 0.016;
/// Gap between an eye's flat face and the clevis plate facing it, m.
inline constexpr double kClevisGapM = 0.006;
/// Clevis plates: square, centred on the eye's axis, m.
inline constexpr double kClevisPlateHalfWidthM = 0.060;
inline constexpr double kClevisPlateThicknessM = 0.020;
/// Half extent of the actuator's bounding box across its length (y and z), m.
inline constexpr double kActuatorHalfWidthM = 0.100;
/// The crew's scene (makeLandingGearCrew): where the spare actuator sits, as an offset
/// from the installed one, and the spare hose's U (world, m). Both wait beyond the gear's
/// -y side, 0.10 m below and 0.11 m above where extractionPathM leaves the actuator.
inline constexpr glm::dvec3 kSpareActuatorOffsetM{0.0, -1.25, -0.66};
inline constexpr double kSpareHoseYM = -1.25;
inline constexpr double kSpareHoseBottomZM = 3.16;  ///< of the U's centreline
inline constexpr double kSpareHoseRadiusM = 0.0125;

/// Brace joints, world, m: drag brace from the trunnion lug via the knee to the strut
/// collar; side brace from the strut up to its airframe fitting.
inline constexpr glm::dvec3 kDragBraceUpperWorld{-1.60, 0.0, 4.20};
inline constexpr glm::dvec3 kDragBraceKneeWorld{-0.95, 0.0, 3.20};
inline constexpr glm::dvec3 kDragBraceLowerWorld{-0.20, 0.0, 2.30};
inline constexpr glm::dvec3 kSideBraceLowerWorld{0.0, -0.19, 2.62};
inline constexpr glm::dvec3 kSideBraceUpperWorld{0.0, -0.82, 4.20};
/// Bar radii of the drag and side braces, m.
inline constexpr double kDragBraceRadiusM = 0.060;
inline constexpr double kSideBraceRadiusM = 0.050;
/// The post carrying the rod-end clevis: vertical, on (x, y) = (kPostXM, 0), radius m.
inline constexpr double kPostXM = 1.38;
inline constexpr double kPostRadiusM = 0.055;

/// The actuator's way out, as translations of the whole actuator from its installed pose
/// (world, m), visited in order: slide sideways out of both clevises, drop below the
/// hydraulic lines that run alongside, then leave sideways under them.
std::vector<glm::dvec3> extractionPathM();

/// splitmix64: a small, fast generator whose output is the same on every platform.
class Rng {
public:
  /// A generator whose sequence is fixed by `seed` (any value, 0 included).
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  /// The next 64 random bits.
  std::uint64_t next();
  /// Uniform in [0, 1), 53 random bits.
  double uniform();
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [0, n), n > 0.
  std::uint32_t below(std::uint32_t n);

private:
  std::uint64_t state_;
};

/// An axis-aligned box, world, m.
struct Box {
  glm::dvec3 min{0.0};  ///< lowest corner, world, m
  glm::dvec3 max{0.0};  ///< highest corner, world, m

  /// True when the boxes share interior or boundary points.
  bool overlaps(const Box& other) const;
  /// This box grown by `marginM` on every side.
  Box inflated(double marginM) const;
};

/// A part being generated: name, colour and its growing mesh.
struct PartDraft {
  std::string name;       ///< part (glTF node) name
  glm::vec4 color{1.0f};  ///< linear RGBA base colour
  TriangleMesh mesh;      ///< world frame, m
};

/// An object being generated.
struct ObjectDraft {
  std::string name;                      ///< object name, unique in the scene
  ObjectRole role = ObjectRole::Static;  ///< static scenery or the dynamic actuator
  std::deque<PartDraft> parts;           ///< a deque, so that references to parts stay valid
};

/// Collects the parts of the scene and places seed-dependent pieces away from the
/// keep-out boxes (the actuator's installed envelope and its extraction corridor).
class GearBuilder {
public:
  /// An empty scene whose random choices follow `seed`; the keep-out boxes are the boxes
  /// swept by the actuator along extractionPathM(), grown by 30 mm.
  explicit GearBuilder(std::uint64_t seed);

  /// The mesh of part `partName` of object `objectName`, created (with `color`, and the
  /// object with `role`) on first use. References stay valid until `takeObjects`.
  TriangleMesh& part(const std::string& objectName, const std::string& partName, const glm::vec4& color,
                     ObjectRole role = ObjectRole::Static);

  /// The seeded random source for layout choices.
  Rng& rng() { return rng_; }

  /// Boxes that seed-dependent geometry must stay out of (world, m).
  const std::vector<Box>& keepOut() const { return keepOut_; }
  /// True when `box` misses every keep-out box.
  bool clearOfKeepOut(const Box& box) const;

  /// Calls `attempt(rng, mesh)` to append one seed-dependent piece; if the bounds of the
  /// vertices it added touch a keep-out box, removes them and tries again with fresh
  /// random numbers, up to `maxAttempts` times. Returns whether a piece was kept.
  bool placeClear(TriangleMesh& mesh, const std::function<void(Rng&, TriangleMesh&)>& attempt,
                  int maxAttempts = 64);

  /// The objects built so far, in creation order; leaves the builder empty.
  std::deque<ObjectDraft> takeObjects();

private:
  Rng rng_;
  std::vector<Box> keepOut_;
  std::deque<ObjectDraft> objects_;
};

/// Builds the dynamic actuator (object "actuator") in its installed pose.
void buildActuator(GearBuilder& gear);
/// Builds the actuator's fixed surroundings: the clevis brackets and their post, the
/// brace beneath it and the hydraulic lines along both sides of it.
void buildActuatorSurroundings(GearBuilder& gear);
/// Builds the main strut, trunnion, torque links and axle yoke.
void buildMainStrut(GearBuilder& gear);
/// Builds the drag brace and side brace with their lugs.
void buildBraces(GearBuilder& gear);
/// Builds the wheels (tyres, rims), brake disc stacks and housings, and the axle.
void buildWheelsAndBrakes(GearBuilder& gear);
/// Builds the seed-routed rigid lines, coiled hoses and their clamps.
void buildHydraulicLines(GearBuilder& gear);
/// Builds bolts, nuts and washers on flanges, collars, rims and brackets, and the
/// seed-placed equipment brackets.
void buildFasteners(GearBuilder& gear);

/// A pure translation by `offsetWorld`, m.
glm::dmat4 translation(const glm::dvec3& offsetWorld);

/// Appends a round bar from `fromWorld` to `toWorld` (a lathe): radius `radiusM`, with
/// end bosses of radius `bossRadiusM` and length `bossLengthM` at both ends and 45°
/// shoulders between boss and bar (bossRadiusM >= radiusM).
void appendBar(TriangleMesh& mesh, const glm::dvec3& fromWorld, const glm::dvec3& toWorld, double radiusM,
               double bossRadiusM, double bossLengthM, int segments);

/// Appends a hex-head bolt (a single closed lathe: shank, chamfered tip, hex head) whose
/// head's underside is at `originWorld`, the shank running along -`axisWorld`.
void appendBolt(TriangleMesh& mesh, const glm::dvec3& originWorld, const glm::dvec3& axisWorld,
                double shankRadiusM, double shankLengthM);

}  // namespace voxhap::landing_gear

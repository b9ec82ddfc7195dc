// The landing gear's hydraulic actuator (the dynamic object) and the fixed pieces around
// it: clevises, post, lower brace and the hydraulic lines alongside. Nothing here depends
// on the seed, so the clearances below hold for every seed (the tests measure them).
//
// Actuator frame (local, m): x from the head-end eye's centre (x = 0) to the rod-end eye's
// centre (x = 0.83), z along the eyes' bores. Installed it is only translated, to
// kActuatorOriginWorld. Bounding box: x ∈ [-0.035, 0.865], y and z ∈ [-0.1, 0.1].
//
// Clearances in the installed pose: eye faces to clevis plates 6 mm; eye rims to the
// clevis bases 15 mm; the necks (r 18 mm) and the rod end's hex (r 30 mm) to the plates
// ≥ 8 mm; the square end caps and tie-rod nuts to the plates ≥ 10 mm; the lower brace
// 80 mm below the lowest fitting; the lines at y ±0.32 m more than 0.2 m to the side.

#include <array>
#include <numbers>
#include <vector>

#include "haptics/geometry/mesh_builder.h"
#include "haptics/scene/builtin/landing_gear_parts.h"

namespace voxhap::landing_gear {
namespace {

constexpr char kActuator[] = "actuator";
constexpr glm::vec4 kPaintGrey{0.55f, 0.58f, 0.55f, 1.0f};
constexpr glm::vec4 kChrome{0.85f, 0.86f, 0.88f, 1.0f};
constexpr glm::vec4 kSteel{0.45f, 0.46f, 0.48f, 1.0f};
constexpr glm::vec4 kBrass{0.78f, 0.62f, 0.28f, 1.0f};
constexpr glm::vec4 kCapBlue{0.22f, 0.32f, 0.52f, 1.0f};
constexpr glm::vec4 kBracketGreen{0.36f, 0.45f, 0.33f, 1.0f};
constexpr glm::vec4 kLineSilver{0.70f, 0.72f, 0.74f, 1.0f};
constexpr glm::vec4 kClampBlue{0.20f, 0.35f, 0.70f, 1.0f};

// tessellation of the actuator, chosen for ≈ 40,000 triangles in all
constexpr int kEyeSegments = 384;
constexpr int kBarrelSegments = 768;
constexpr int kCapSegments = 256;
constexpr int kRodSegments = 384;
constexpr int kRodEndSegments = 240;
constexpr int kFittingSegments = 84;
constexpr int kTieRodSegments = 32;

constexpr double kCapHalfWidthM = 0.085;
constexpr double kTieRodOffsetM = 0.068;  // from the axis, along y and z

/// A lathe whose local z runs along the actuator's x axis, in the installed pose.
glm::dmat4 alongActuator(double xLocal) {
  return frameAlongAxis(kActuatorOriginWorld + glm::dvec3(xLocal, 0.0, 0.0), {1.0, 0.0, 0.0});
}

void appendEye(TriangleMesh& mesh, double xLocal) {
  const double ri = kEyeBoreRadiusM;
  const double ro = kEyeOuterRadiusM;
  const double h = kEyeHalfHeightM;
  constexpr double kChamferM = 0.002;
  const ProfilePoint profile[] = {{ri + kChamferM, -h}, {ro - kChamferM, -h}, {ro, -h + kChamferM},
                                  {ro, h - kChamferM},  {ro - kChamferM, h},  {ri + kChamferM, h},
                                  {ri, h - kChamferM},  {ri, -h + kChamferM}};
  appendLathe(mesh, translation(kActuatorOriginWorld + glm::dvec3(xLocal, 0.0, 0.0)), profile, kEyeSegments);
}

/// A hydraulic port: boss, hex, tube stub and flare nut along `direction` from the axis,
/// ending exactly kActuatorHalfWidthM from it.
void appendFitting(TriangleMesh& mesh, double xLocal, const glm::dvec3& direction) {
  const ProfilePoint profile[] = {{0.0, 0.050},
                                  {0.014, 0.050},
                                  {0.014, 0.072},
                                  {0.0125, 0.072, 6},
                                  {0.0125, 0.084, 6},
                                  {0.0065, 0.084},
                                  {0.0065, 0.093},
                                  {0.0090, 0.093, 6},
                                  {0.0090, 0.0985, 6},
                                  {0.0075, kActuatorHalfWidthM},
                                  {0.0, kActuatorHalfWidthM}};
  appendLathe(mesh, frameAlongAxis(kActuatorOriginWorld + glm::dvec3(xLocal, 0.0, 0.0), direction), profile,
              kFittingSegments);
}

void appendClevis(GearBuilder& gear, double eyeXLocal, double baseFromXWorld, double baseToXWorld) {
  TriangleMesh& plates = gear.part("brackets", "actuator-clevises", kBracketGreen);
  const glm::dvec3 eye = kActuatorOriginWorld + glm::dvec3(eyeXLocal, 0.0, 0.0);
  const double innerFace = kEyeHalfHeightM + kClevisGapM;
  const HoledBlockSpec plate{kClevisPlateHalfWidthM, kClevisPlateThicknessM, kEyeBoreRadiusM,
                             kClevisPlateThicknessM};
  appendBlockWithHole(plates, translation(eye + glm::dvec3(0.0, 0.0, innerFace)), plate, 64);
  appendBlockWithHole(plates, translation(eye - glm::dvec3(0.0, 0.0, innerFace + kClevisPlateThicknessM)),
                      plate, 64);
  const double outerFace = innerFace + kClevisPlateThicknessM;
  // the base runs through both plates: a part of its own, so that each part's surface
  // bounds one solid and ray parity inside each part stays right
  TriangleMesh& bases = gear.part("brackets", "actuator-clevis-bases", kBracketGreen);
  appendBox(bases, translation({0.5 * (baseFromXWorld + baseToXWorld), 0.0, eye.z}),
            {0.5 * (baseToXWorld - baseFromXWorld), kClevisPlateHalfWidthM, outerFace});
}

}  // namespace

void buildActuator(GearBuilder& gear) {
  constexpr ObjectRole kDynamic = ObjectRole::Dynamic;
  {
    TriangleMesh& eyes = gear.part(kActuator, "head-end-eye", kSteel, kDynamic);
    appendEye(eyes, 0.0);
  }
  {
    TriangleMesh& barrel = gear.part(kActuator, "barrel", kPaintGrey, kDynamic);
    const ProfilePoint profile[] = {{0.0, 0.025},   {0.018, 0.025}, {0.018, 0.078}, {0.057, 0.078},
                                    {0.060, 0.081}, {0.060, 0.543}, {0.057, 0.546}, {0.0, 0.546}};
    appendLathe(barrel, alongActuator(0.0), profile, kBarrelSegments);
  }
  {
    TriangleMesh& caps = gear.part(kActuator, "end-caps", kCapBlue, kDynamic);
    const double corner = kCapHalfWidthM * std::numbers::sqrt2;
    const ProfilePoint headCap[] = {{0.045, 0.080}, {corner, 0.080, 4}, {corner, 0.124, 4}, {0.045, 0.124}};
    appendLathe(caps, alongActuator(0.0), headCap, kCapSegments);
    const ProfilePoint glandCap[] = {{0.030, 0.500}, {corner, 0.500, 4}, {corner, 0.548, 4}, {0.030, 0.548}};
    appendLathe(caps, alongActuator(0.0), glandCap, kCapSegments);
    const ProfilePoint wiper[] = {
        {0.027, 0.5475}, {0.036, 0.5475}, {0.036, 0.552}, {0.033, 0.556}, {0.027, 0.556}};
    appendLathe(caps, alongActuator(0.0), wiper, kCapSegments);
  }
  {
    TriangleMesh& tieRods = gear.part(kActuator, "tie-rods", kSteel, kDynamic);
    for (int k = 0; k < 4; ++k) {
      const glm::dvec3 offset(0.0, (k & 1) ? kTieRodOffsetM : -kTieRodOffsetM,
                              (k & 2) ? kTieRodOffsetM : -kTieRodOffsetM);
      const glm::dvec3 start = kActuatorOriginWorld + offset + glm::dvec3(0.066, 0.0, 0.0);
      appendCylinder(tieRods, frameAlongAxis(start, {1.0, 0.0, 0.0}), 0.006, 0.500, kTieRodSegments);
      appendHexPrism(tieRods, frameAlongAxis(start + glm::dvec3(0.004, 0.0, 0.0), {1.0, 0.0, 0.0}), 0.017,
                     0.0095);
      appendHexPrism(tieRods, frameAlongAxis(start + glm::dvec3(0.4835, 0.0, 0.0), {1.0, 0.0, 0.0}), 0.017,
                     0.0095);
    }
  }
  {
    TriangleMesh& rod = gear.part(kActuator, "piston-rod", kChrome, kDynamic);
    const ProfilePoint profile[] = {
        {0.0, 0.549}, {0.024, 0.549}, {0.025, 0.550}, {0.025, 0.738}, {0.0, 0.738}};
    appendLathe(rod, alongActuator(0.0), profile, kRodSegments);
  }
  {
    TriangleMesh& rodEnd = gear.part(kActuator, "rod-end", kSteel, kDynamic);
    const ProfilePoint profile[] = {{0.0, 0.736},   {0.030, 0.736, 6}, {0.030, 0.756, 6},
                                    {0.018, 0.760}, {0.018, 0.806},    {0.0, 0.806}};
    appendLathe(rodEnd, alongActuator(0.0), profile, kRodEndSegments);
    TriangleMesh& eye = gear.part(kActuator, "rod-end-eye", kSteel, kDynamic);
    appendEye(eye, kEyeSpacingM);
  }
  {
    TriangleMesh& fittings = gear.part(kActuator, "ports-and-fittings", kBrass, kDynamic);
    appendFitting(fittings, 0.16, {0.0, 0.0, 1.0});
    appendFitting(fittings, 0.47, {0.0, 0.0, 1.0});
    appendFitting(fittings, 0.30, {0.0, 1.0, 0.0});
    appendFitting(fittings, 0.30, {0.0, -1.0, 0.0});
    appendFitting(fittings, 0.30, {0.0, 0.0, -1.0});
  }
}

void buildActuatorSurroundings(GearBuilder& gear) {
  // clevises: the head-end one on a collar round the strut, the rod-end one on the post
  appendClevis(gear, 0.0, 0.12, 0.25);
  appendClevis(gear, kEyeSpacingM, 1.18, 1.33);
  {
    TriangleMesh& collar = gear.part("brackets", "actuator-collar", kBracketGreen);
    appendHollowCylinder(collar, translation({0.0, 0.0, 3.20}), 0.1655, 0.195, 0.20, 256);
  }
  {
    TriangleMesh& post = gear.part("brackets", "actuator-post", kBracketGreen);
    const ProfilePoint profile[] = {
        {0.0, 2.93}, {kPostRadiusM - 0.01, 2.93}, {kPostRadiusM, 2.94}, {kPostRadiusM, 4.30}, {0.0, 4.30}};
    appendLathe(post, translation({kPostXM, 0.0, 0.0}), profile, 192);
    const ProfilePoint brace[] = {{0.0, 0.15},   {0.055, 0.15}, {0.055, 0.20}, {0.040, 0.22},
                                  {0.040, 1.28}, {0.055, 1.30}, {0.055, 1.34}, {0.0, 1.34}};
    appendLathe(post, frameAlongAxis({0.0, 0.0, 3.08}, {1.0, 0.0, 0.0}), brace, 192);
  }
  // three lines on each side, nested so that the lower ones rise outside the upper ones
  TriangleMesh& lines = gear.part("hydraulic-lines", "rigid-lines", kLineSilver);
  TriangleMesh& clamps = gear.part("hydraulic-lines", "line-clamps", kClampBlue);
  constexpr double kLineRadiusM = 0.0125;
  constexpr std::array<double, 3> kLineZ = {3.38, 3.30, 3.22};
  for (const double side : {-1.0, 1.0}) {
    for (std::size_t k = 0; k < kLineZ.size(); ++k) {
      const double xLeft = 0.02 - 0.035 * static_cast<double>(k);
      const double xRight = 1.50 + 0.035 * static_cast<double>(k);
      const double y = 0.32 * side;
      const glm::dvec3 corners[] = {{xLeft, 0.05 * side, 4.30}, {xLeft, y, 4.30},
                                    {xLeft, y, kLineZ[k]},      {xRight, y, kLineZ[k]},
                                    {xRight, y, 4.30},          {xRight, 0.05 * side, 4.30}};
      const std::vector<glm::dvec3> path = filletedPolyline(corners, 0.05, 12);
      appendPathTube(lines, glm::dmat4(1.0), path, kLineRadiusM, 24);
      for (const double x : {0.45, 0.75, 1.05, 1.35}) {
        appendTorus(clamps, frameAlongAxis({x, y, kLineZ[k]}, {1.0, 0.0, 0.0}), kLineRadiusM + 0.0032, 0.0025,
                    64, 16);
      }
    }
  }
}

}  // namespace voxhap::landing_gear

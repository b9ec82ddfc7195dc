// The landing gear's seed-dependent pieces: rigid hydraulic lines, wire bundles and
// coiled hoses with their clamps, bolts, and equipment brackets. The seed moves lines,
// coils and equipment, and turns bolt circles; every piece is checked against the
// builder's keep-out boxes (the actuator's envelope and extraction corridor) and is
// re-drawn until it misses them. Counts do not depend on the seed.

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "haptics/geometry/mesh_builder.h"
#include "haptics/scene/builtin/landing_gear_parts.h"

namespace voxhap::landing_gear {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;

constexpr glm::vec4 kLineSilver{0.70f, 0.72f, 0.74f, 1.0f};
constexpr glm::vec4 kHoseBlack{0.12f, 0.12f, 0.13f, 1.0f};
constexpr glm::vec4 kClampBlue{0.20f, 0.35f, 0.70f, 1.0f};
constexpr glm::vec4 kWireOrange{0.85f, 0.45f, 0.15f, 1.0f};
constexpr glm::vec4 kBoltSteel{0.30f, 0.31f, 0.33f, 1.0f};
constexpr glm::vec4 kWasherZinc{0.66f, 0.68f, 0.64f, 1.0f};
constexpr glm::vec4 kNutSteel{0.40f, 0.40f, 0.42f, 1.0f};
constexpr glm::vec4 kBracketGreen{0.47f, 0.55f, 0.40f, 1.0f};
constexpr glm::vec4 kSensorBlack{0.15f, 0.15f, 0.16f, 1.0f};
constexpr glm::vec4 kConnectorYellow{0.80f, 0.70f, 0.20f, 1.0f};

constexpr double kStrutRadiusM = 0.165;
constexpr double kAxleZ = 0.66;

// tessellation (the main knobs of the static triangle count)
constexpr int kLineSegments = 24;
constexpr int kWireSegments = 12;
constexpr int kHoseSegments = 32;
constexpr int kHoseSamplesPerTurn = 96;
constexpr int kClampMajorSegments = 64;
constexpr int kClampMinorSegments = 16;
constexpr std::size_t kEquipmentCount = 40;
// rings of equipment slots on the strut, clear of the collars (z 2.20-2.40, 3.18-3.42,
// 3.98-4.22) by more than the brackets' half height (0.06 m)
constexpr double kEquipmentRingZ[] = {1.95, 2.10, 2.50, 2.65, 2.80, 2.95, 3.10, 3.50, 3.65, 3.80};

glm::dvec3 onCircle(double radiusM, double angleRad, double z) {
  return {radiusM * std::cos(angleRad), radiusM * std::sin(angleRad), z};
}

/// Whether a tube of radius `radiusM` along `path` misses every keep-out box.
bool tubeClear(const GearBuilder& gear, const std::vector<glm::dvec3>& path, double radiusM) {
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const Box span{glm::min(path[i], path[i + 1]), glm::max(path[i], path[i + 1])};
    if (!gear.clearOfKeepOut(span.inflated(radiusM))) return false;
  }
  return true;
}

/// Seven wires (one in the middle, six around it, `spacingM` apart) following `path`,
/// carried round bends by parallel transport so that they never touch.
void appendWireBundle(TriangleMesh& mesh, const std::vector<glm::dvec3>& path, double wireRadiusM,
                      double spacingM) {
  const std::size_t n = path.size();
  std::vector<glm::dvec3> u(n);
  std::vector<glm::dvec3> v(n);
  for (std::size_t j = 0; j < n; ++j) {
    const glm::dvec3 in = j > 0 ? glm::normalize(path[j] - path[j - 1]) : glm::dvec3(0.0);
    const glm::dvec3 out = j + 1 < n ? glm::normalize(path[j + 1] - path[j]) : glm::dvec3(0.0);
    const glm::dvec3 t = glm::normalize(in + out);
    const glm::dvec3 previous = j > 0 ? u[j - 1] : glm::dvec3(0.0, 0.0, 1.0);
    glm::dvec3 projected = previous - glm::dot(previous, t) * t;
    if (glm::length(projected) < 1e-6) projected = glm::dvec3(1.0, 0.0, 0.0) - t.x * t;
    u[j] = glm::normalize(projected);
    v[j] = glm::cross(t, u[j]);
  }
  std::vector<glm::dvec3> wire(n);
  for (int k = 0; k < 7; ++k) {
    const double angle = 2.0 * kPi * static_cast<double>(k) / 6.0;
    const double ou = k == 6 ? 0.0 : spacingM * std::cos(angle);
    const double ov = k == 6 ? 0.0 : spacingM * std::sin(angle);
    for (std::size_t j = 0; j < n; ++j) wire[j] = path[j] + ou * u[j] + ov * v[j];
    appendPathTube(mesh, glm::dmat4(1.0), wire, wireRadiusM, kWireSegments);
  }
}

/// A bolt with a washer under its head on a surface at `surfaceWorld` facing `normalWorld`.
void appendBoltSet(GearBuilder& gear, const glm::dvec3& surfaceWorld, const glm::dvec3& normalWorld,
                   double shankRadiusM, double shankLengthM) {
  const glm::dvec3 n = glm::normalize(normalWorld);
  const double washerThickness = 0.25 * shankRadiusM;
  // everything lies within 2·shank radius of the axis, from the shank's tip to the head's top
  const glm::dvec3 tip = surfaceWorld - shankLengthM * n;
  const glm::dvec3 top = surfaceWorld + (1.6 * shankRadiusM + 0.0003) * n;
  const Box reach = Box{glm::min(tip, top), glm::max(tip, top)}.inflated(2.0 * shankRadiusM);
  if (!gear.clearOfKeepOut(reach)) return;
  appendHollowCylinder(gear.part("bolts", "washers", kWasherZinc), frameAlongAxis(surfaceWorld, n),
                       shankRadiusM + 0.0004, 2.0 * shankRadiusM, washerThickness, 32);
  appendBolt(gear.part("bolts", "bolts", kBoltSteel), surfaceWorld + (washerThickness + 0.0002) * n, n,
             shankRadiusM, shankLengthM);
}

/// A hex nut on a surface at `surfaceWorld` facing `normalWorld`, round a shank.
void appendNut(GearBuilder& gear, const glm::dvec3& surfaceWorld, const glm::dvec3& normalWorld,
               double shankRadiusM) {
  const double corner = 1.7 * shankRadiusM * 2.0 / std::sqrt(3.0);
  const ProfilePoint nut[] = {{shankRadiusM + 0.0004, 0.0},
                              {corner, 0.0, 6},
                              {corner, 0.9 * shankRadiusM, 6},
                              {shankRadiusM + 0.0004, 0.9 * shankRadiusM}};
  appendLathe(gear.part("bolts", "nuts", kNutSteel), frameAlongAxis(surfaceWorld, normalWorld), nut, 24);
}

/// `count` bolts on a circle of radius `circleRadiusM` in the plane z = 0 of `frame`,
/// heads toward +z, turned by a random phase.
void appendBoltCircle(GearBuilder& gear, const glm::dmat4& frame, double circleRadiusM, int count,
                      double shankRadiusM, double shankLengthM) {
  const double phase = gear.rng().uniform(0.0, 2.0 * kPi / static_cast<double>(count));
  const glm::dvec3 normal = glm::normalize(glm::dvec3(frame[2]));
  for (int k = 0; k < count; ++k) {
    const double angle = phase + 2.0 * kPi * static_cast<double>(k) / static_cast<double>(count);
    const glm::dvec3 local = onCircle(circleRadiusM, angle, 0.0);
    appendBoltSet(gear, glm::dvec3(frame * glm::dvec4(local, 1.0)), normal, shankRadiusM, shankLengthM);
  }
}

/// A rows × columns grid of bolts on a flat face: centre, outward normal, the in-face
/// directions and pitches.
void appendBoltGrid(GearBuilder& gear, const glm::dvec3& centre, const glm::dvec3& normal,
                    const glm::dvec3& along, const glm::dvec3& across, int rows, int columns, double pitchM,
                    double shankRadiusM) {
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      const double a = (static_cast<double>(c) - 0.5 * static_cast<double>(columns - 1)) * pitchM;
      const double b = (static_cast<double>(r) - 0.5 * static_cast<double>(rows - 1)) * pitchM;
      appendBoltSet(gear, centre + a * along + b * across, normal, shankRadiusM, 4.0 * shankRadiusM);
    }
  }
}

}  // namespace

void buildHydraulicLines(GearBuilder& gear) {
  TriangleMesh& lines = gear.part("hydraulic-lines", "rigid-lines", kLineSilver);
  TriangleMesh& hoses = gear.part("hydraulic-lines", "coiled-hoses", kHoseBlack);
  TriangleMesh& clamps = gear.part("hydraulic-lines", "line-clamps", kClampBlue);
  TriangleMesh& wires = gear.part("hydraulic-lines", "wire-bundles", kWireOrange);
  Rng& rng = gear.rng();
  constexpr std::array<double, 3> kLineRadii = {0.005, 0.006, 0.008};

  // brake lines: from the trunnion housing down the aft side of the strut to the brakes
  for (const double side : {-1.0, 1.0}) {
    for (int attempt = 0; attempt < 64; ++attempt) {
      const double lowZ = rng.uniform(1.15, 1.35);
      std::vector<std::vector<glm::dvec3>> paths;
      std::vector<double> radii;
      std::vector<glm::dvec3> verticalLegs;
      for (int k = 0; k < 4; ++k) {
        const double angle = kPi - side * (35.0 + 10.0 * k + rng.uniform(-3.0, 3.0)) * kDegree;
        const double radius = 0.30 + rng.uniform(-0.008, 0.008);
        const glm::dvec3 down = onCircle(radius, angle, 0.0);
        const glm::dvec3 corners[] = {onCircle(0.15, angle, 4.30),
                                      onCircle(radius, angle, 4.12),
                                      down + glm::dvec3(0.0, 0.0, lowZ),
                                      {down.x, side * 0.40, lowZ - 0.15},
                                      {-0.205 + 0.035 * k, side * 0.47, 0.72}};
        paths.push_back(filletedPolyline(corners, 0.06, 16));
        verticalLegs.push_back(down);
        radii.push_back(kLineRadii[rng.below(3)]);
      }
      bool clear = true;
      for (std::size_t k = 0; k < paths.size(); ++k) clear = clear && tubeClear(gear, paths[k], radii[k]);
      if (!clear) continue;
      for (std::size_t k = 0; k < paths.size(); ++k) {
        appendPathTube(lines, glm::dmat4(1.0), paths[k], radii[k], kLineSegments);
        // clamps round the long vertical leg
        for (int c = 0; c < 6; ++c) {
          const double z = 1.55 + 0.42 * c + rng.uniform(-0.05, 0.05);
          appendTorus(clamps, translation(verticalLegs[k] + glm::dvec3(0.0, 0.0, z)), radii[k] + 0.0032,
                      0.0025, kClampMajorSegments, kClampMinorSegments);
        }
      }
      break;
    }
  }

  // wire bundles down the front quarters of the strut to the axle yoke
  for (const double side : {-1.0, 1.0}) {
    gear.placeClear(wires, [&](Rng& r, TriangleMesh& mesh) {
      const double angle = side * (60.0 + r.uniform(-4.0, 4.0)) * kDegree;
      const glm::dvec3 corners[] = {onCircle(0.12, angle, 4.30),
                                    onCircle(0.30, angle, 4.10),
                                    onCircle(0.30, angle, 1.30 + r.uniform(-0.05, 0.05)),
                                    {0.08, side * 0.20, 0.75}};
      appendWireBundle(mesh, filletedPolyline(corners, 0.08, 16), 0.003, 0.007);
    });
  }

  // coiled hoses: beside the brakes (axis across), aft of the strut and by the drag brace
  struct Coil {
    glm::dvec3 start;
    glm::dvec3 axis;
  };
  std::vector<Coil> coils;
  for (const double side : {-1.0, 1.0}) {
    coils.push_back({{0.30, side * 0.23, 1.10}, {0.0, side, 0.0}});
    coils.push_back({{-0.42, side * 0.32, 1.70}, {0.0, 0.0, 1.0}});
    coils.push_back({{-1.20, side * 0.25, 3.50}, {0.0, 0.0, 1.0}});
    coils.push_back({{-0.60, side * 0.30, 2.10}, {0.0, 0.0, 1.0}});
    coils.push_back({{-1.20, side * 0.25, 3.85}, {0.0, 0.0, 1.0}});
  }
  for (const Coil& coil : coils) {
    gear.placeClear(hoses, [&](Rng& r, TriangleMesh& mesh) {
      const glm::dvec3 jitter(r.uniform(-0.03, 0.03), 0.0, r.uniform(-0.03, 0.03));
      const HelixSpec helix{0.040, 0.020, 12.0, 0.006};
      appendHelixTube(mesh, frameAlongAxis(coil.start + jitter, coil.axis), helix, kHoseSamplesPerTurn,
                      kHoseSegments);
    });
  }
}

void buildFasteners(GearBuilder& gear) {
  Rng& rng = gear.rng();
  const glm::dvec3 ex(1.0, 0.0, 0.0);
  const glm::dvec3 ey(0.0, 1.0, 0.0);
  const glm::dvec3 ez(0.0, 0.0, 1.0);

  // wheels: hub bolts outboard, rim tie bolts on the web, brake housing bolts inboard
  for (const double side : {-1.0, 1.0}) {
    const glm::dvec3 axis(0.0, side, 0.0);
    const glm::dvec3 centre(0.0, side * 0.71, kAxleZ);
    appendBoltCircle(gear, frameAlongAxis(centre + 0.12 * axis, axis), 0.115, 20, 0.007, 0.05);
    appendBoltCircle(gear, frameAlongAxis(centre + 0.02 * axis, axis), 0.20, 30, 0.006, 0.03);
    appendBoltCircle(gear, frameAlongAxis(centre - 0.275 * axis, -axis), 0.16, 16, 0.006, 0.04);
  }
  // collars on the strut: radial bolts
  for (const auto& [z, radius] : {std::pair{2.30, 0.180}, std::pair{4.10, 0.185}, std::pair{3.30, 0.195}}) {
    const double phase = rng.uniform(0.0, 2.0 * kPi / 24.0);
    for (int k = 0; k < 24; ++k) {
      const double angle = phase + 2.0 * kPi * static_cast<double>(k) / 24.0;
      appendBoltSet(gear, onCircle(radius, angle, z), onCircle(1.0, angle, 0.0), 0.006, 0.03);
    }
  }
  // trunnion housing and airframe fittings: bolt grids on their ±y faces
  for (const double side : {-1.0, 1.0}) {
    const glm::dvec3 normal = side * ey;
    appendBoltGrid(gear, {0.0, side * 0.20, 4.38}, normal, ex, ez, 4, 7, 0.055, 0.008);
    for (const double x : {-1.80, 1.80}) {
      appendBoltGrid(gear, {x, side * 0.16, 4.59}, normal, ex, ez, 6, 4, 0.06, 0.008);
    }
    // axle yoke faces fore and aft
    appendBoltGrid(gear, {side * 0.16, 0.0, kAxleZ}, side * ex, ey, ez, 3, 5, 0.07, 0.008);
    // clevis bases of the actuator: bolts on their ±y faces, away from the eyes
    appendBoltGrid(gear, {0.165, side * 0.06, 3.30}, normal, ex, ez, 2, 2, 0.05, 0.006);
    appendBoltGrid(gear, {1.275, side * 0.06, 3.30}, normal, ex, ez, 2, 2, 0.05, 0.006);
  }
  // bolt circles on the faces of the trunnion bearings in the airframe fittings
  for (const double x : {-1.80, 1.80}) {
    for (const double side : {-1.0, 1.0}) {
      appendBoltCircle(gear, frameAlongAxis({x + side * 0.13, 0.0, 4.38}, side * ex), 0.148, 16, 0.006, 0.03);
    }
  }
  // clamp bands round the braces and the post, each with six radial bolts
  TriangleMesh& bands = gear.part("brackets", "clamp-bands", kBracketGreen);
  struct Band {
    glm::dvec3 from;
    glm::dvec3 to;
    double barRadiusM;
  };
  const Band bandBars[] = {{kDragBraceUpperWorld, kDragBraceKneeWorld, kDragBraceRadiusM},
                           {kDragBraceKneeWorld, kDragBraceLowerWorld, kDragBraceRadiusM},
                           {kSideBraceLowerWorld, kSideBraceUpperWorld, kSideBraceRadiusM},
                           {{kPostXM, 0.0, 3.45}, {kPostXM, 0.0, 4.25}, kPostRadiusM}};
  for (const Band& bar : bandBars) {
    for (const double along : {0.3, 0.7}) {
      const glm::dvec3 axis = glm::normalize(bar.to - bar.from);
      const glm::dvec3 centre = bar.from + along * (bar.to - bar.from);
      const glm::dmat4 frame = frameAlongAxis(centre - 0.025 * axis, axis);
      const double outer = bar.barRadiusM + 0.012;
      appendHollowCylinder(bands, frame, bar.barRadiusM + 0.0005, outer, 0.05, 256);
      const double phase = rng.uniform(0.0, 2.0 * kPi / 6.0);
      for (int k = 0; k < 6; ++k) {
        const double angle = phase + 2.0 * kPi * static_cast<double>(k) / 6.0;
        const glm::dvec3 radial =
            std::cos(angle) * glm::dvec3(frame[0]) + std::sin(angle) * glm::dvec3(frame[1]);
        appendBoltSet(gear, centre + outer * radial, radial, 0.005, 0.012);
      }
    }
  }
  // through bolts in the brace lugs, nut on the far side
  const std::array<std::pair<glm::dvec3, double>, 3> lugBolts = {std::pair{kDragBraceUpperWorld, 0.10},
                                                                 std::pair{kDragBraceLowerWorld, 0.10},
                                                                 std::pair{kDragBraceKneeWorld, 0.11}};
  for (const auto& [lug, halfThickness] : lugBolts) {
    appendBoltSet(gear, lug + halfThickness * ey, ey, 0.022, 2.0 * halfThickness + 0.05);
    appendNut(gear, lug - (halfThickness + 0.0002) * ey, -ey, 0.022);
  }

  // equipment brackets on the strut cylinder: plate, sensor, connector, four bolts
  TriangleMesh& plates = gear.part("brackets", "equipment-brackets", kBracketGreen);
  TriangleMesh& sensors = gear.part("equipment", "sensors", kSensorBlack);
  TriangleMesh& connectors = gear.part("equipment", "connectors", kConnectorYellow);
  const std::array<glm::dvec3, 4> avoid = {kDragBraceLowerWorld, kSideBraceLowerWorld,
                                           glm::dvec3(-0.14, 0.10, 2.75), glm::dvec3(0.17, 0.0, 1.84)};

  // slots: eight per ring, rings between the collars, each ring turned by the seed; the
  // seed then picks kEquipmentCount of the slots that are clear
  std::vector<std::pair<double, double>> slots;  // (angle, z)
  for (const double z : kEquipmentRingZ) {
    const double phase = rng.uniform(0.0, 2.0 * kPi / 8.0);
    for (int k = 0; k < 8; ++k) {
      const double angle = phase + 2.0 * kPi * static_cast<double>(k) / 8.0;
      const glm::dvec3 centre = onCircle(kStrutRadiusM + 0.004, angle, z);
      bool ok = gear.clearOfKeepOut(Box{centre - glm::dvec3(0.09), centre + glm::dvec3(0.09)});
      for (const glm::dvec3& a : avoid) ok = ok && glm::length(a - centre) > 0.20;
      if (ok) slots.emplace_back(angle, z);
    }
  }
  for (std::size_t i = 0; i < slots.size() && i < kEquipmentCount; ++i) {
    std::swap(slots[i], slots[i + rng.below(static_cast<std::uint32_t>(slots.size() - i))]);
    const auto [angle, z] = slots[i];
    const glm::dvec3 normal = onCircle(1.0, angle, 0.0);
    const glm::dvec3 centre = onCircle(kStrutRadiusM + 0.004, angle, z);
    const glm::dvec3 tangent(-normal.y, normal.x, 0.0);
    const glm::dmat4 frame(glm::dvec4(tangent, 0.0), glm::dvec4(ez, 0.0), glm::dvec4(normal, 0.0),
                           glm::dvec4(centre, 1.0));
    appendBox(plates, frame, {0.04, 0.06, 0.006});
    appendCylinder(sensors, frameAlongAxis(centre + 0.004 * normal, normal), 0.022, 0.042, 64);
    appendHexPrism(connectors, frameAlongAxis(centre + 0.045 * normal, normal), 0.02, 0.016);
    for (const double a : {-0.028, 0.028}) {
      for (const double b : {-0.045, 0.045}) {
        appendBoltSet(gear, centre + 0.006 * normal + a * tangent + b * ez, normal, 0.004, 0.02);
      }
    }
  }
}

}  // namespace voxhap::landing_gear

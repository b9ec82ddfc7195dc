// The landing gear's fixed structure: main strut, trunnion, torque links, braces, wheels,
// brakes and axle. Nothing here depends on the seed. Layout: see landing_gear.cpp.

#include "haptics/scene/builtin/landing_gear_parts.h"

#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "haptics/geometry/mesh_builder.h"

namespace voxhap::landing_gear {
namespace {

constexpr double kPi = std::numbers::pi;

constexpr glm::vec4 kStrutGrey{0.62f, 0.64f, 0.66f, 1.0f};
constexpr glm::vec4 kChrome{0.86f, 0.87f, 0.89f, 1.0f};
constexpr glm::vec4 kDarkGrey{0.35f, 0.36f, 0.38f, 1.0f};
constexpr glm::vec4 kPrimerGreen{0.47f, 0.55f, 0.40f, 1.0f};
constexpr glm::vec4 kRubber{0.08f, 0.08f, 0.09f, 1.0f};
constexpr glm::vec4 kAluminium{0.75f, 0.76f, 0.78f, 1.0f};
constexpr glm::vec4 kCarbon{0.20f, 0.18f, 0.17f, 1.0f};
constexpr glm::vec4 kBrakeSteel{0.50f, 0.44f, 0.40f, 1.0f};

constexpr double kAxleZ = 0.66;
constexpr double kWheelCentreY = 0.71;
constexpr double kTrunnionZ = 4.38;
constexpr double kTrunnionHalfLengthM = 2.05;
constexpr int kTyreSegments = 1024;
constexpr std::size_t kTyreSectionPoints = 256;

/// A lug: a square block with a through hole whose axis is `axisWorld`, centred on
/// `centreWorld`, `thicknessM` along the axis.
void appendLug(TriangleMesh& mesh, const glm::dvec3& centreWorld, const glm::dvec3& axisWorld,
               double halfWidthM, double thicknessM, double holeRadiusM) {
  const glm::dvec3 axis = glm::normalize(axisWorld);
  appendBlockWithHole(mesh, frameAlongAxis(centreWorld - 0.5 * thicknessM * axis, axis),
                      {halfWidthM, thicknessM, holeRadiusM, thicknessM}, 64);
}

/// A box centred on `centreWorld` whose local z runs along `axisWorld`.
void appendOrientedBox(TriangleMesh& mesh, const glm::dvec3& centreWorld, const glm::dvec3& axisWorld,
                       const glm::dvec3& halfExtentsM) {
  appendBox(mesh, frameAlongAxis(centreWorld, axisWorld), halfExtentsM);
}

/// The tyre's cross-section in the wheel's (radius, axial) plane: an ellipse round the
/// carcass centre (0.46 m out, 0.20 m radial and 0.19 m axial half-axes) with four
/// circumferential tread grooves, counter-clockwise.
std::vector<ProfilePoint> tyreCrossSection() {
  constexpr double kCentreM = 0.46;
  constexpr double kRadialHalfAxisM = 0.20;
  constexpr double kAxialHalfAxisM = 0.19;
  constexpr double kGrooveDepthM = 0.008;
  constexpr double kGrooveHalfWidthM = 0.010;
  constexpr double kGrooveCentresM[] = {-0.090, -0.032, 0.032, 0.090};
  std::vector<ProfilePoint> section(kTyreSectionPoints);
  for (std::size_t m = 0; m < section.size(); ++m) {
    const double angle = 2.0 * kPi * static_cast<double>(m) / static_cast<double>(section.size());
    const double axial = kAxialHalfAxisM * std::sin(angle);
    double depth = 0.0;
    if (std::cos(angle) > 0.6) {
      for (const double centre : kGrooveCentresM) {
        const double t = (axial - centre) / kGrooveHalfWidthM;
        if (std::abs(t) < 1.0) depth = kGrooveDepthM * (1.0 - t * t) * (1.0 - t * t);
      }
    }
    section[m] = {kCentreM + (kRadialHalfAxisM - depth) * std::cos(angle), axial};
  }
  return section;
}

}  // namespace

glm::dmat4 translation(const glm::dvec3& offsetWorld) {
  glm::dmat4 m(1.0);
  m[3] = glm::dvec4(offsetWorld, 1.0);
  return m;
}

void appendBar(TriangleMesh& mesh, const glm::dvec3& fromWorld, const glm::dvec3& toWorld, double radiusM,
               double bossRadiusM, double bossLengthM, int segments) {
  const double length = glm::length(toWorld - fromWorld);
  const double shoulder = bossRadiusM - radiusM;
  const ProfilePoint profile[] = {{0.0, 0.0},
                                  {bossRadiusM, 0.0},
                                  {bossRadiusM, bossLengthM},
                                  {radiusM, bossLengthM + shoulder},
                                  {radiusM, length - bossLengthM - shoulder},
                                  {bossRadiusM, length - bossLengthM},
                                  {bossRadiusM, length},
                                  {0.0, length}};
  appendLathe(mesh, frameAlongAxis(fromWorld, toWorld - fromWorld), profile, segments);
}

void appendBolt(TriangleMesh& mesh, const glm::dvec3& originWorld, const glm::dvec3& axisWorld,
                double shankRadiusM, double shankLengthM) {
  const double rs = shankRadiusM;
  const double chamfer = 0.15 * rs;
  const double headCorner = 1.7 * rs * 2.0 / std::sqrt(3.0);  // across flats 3.4·rs
  const double headHeight = 1.3 * rs;
  const ProfilePoint profile[] = {{0.0, -shankLengthM},
                                  {rs - chamfer, -shankLengthM},
                                  {rs, -shankLengthM + chamfer},
                                  {rs, 0.0},
                                  {headCorner, 0.0, 6},
                                  {headCorner, headHeight, 6},
                                  {0.0, headHeight}};
  appendLathe(mesh, frameAlongAxis(originWorld, axisWorld), profile, 36);
}

void buildMainStrut(GearBuilder& gear) {
  {
    // the cylinder is bored from below for the piston (bore r 0.1125 up to z 2.10)
    TriangleMesh& cylinder = gear.part("main-strut", "strut-cylinder", kStrutGrey);
    const ProfilePoint profile[] = {{0.1125, 1.75}, {0.150, 1.75}, {0.165, 1.77}, {0.165, 2.20},
                                    {0.180, 2.22},  {0.180, 2.38}, {0.165, 2.40}, {0.165, 3.98},
                                    {0.185, 4.00},  {0.185, 4.20}, {0.165, 4.22}, {0.165, 4.26},
                                    {0.0, 4.26},    {0.0, 2.10},   {0.1125, 2.10}};
    appendLathe(cylinder, glm::dmat4(1.0), profile, 1024);
  }
  {
    TriangleMesh& piston = gear.part("main-strut", "strut-piston", kChrome);
    const ProfilePoint profile[] = {{0.0, 0.80}, {0.110, 0.80}, {0.110, 2.045}, {0.105, 2.05}, {0.0, 2.05}};
    appendLathe(piston, glm::dmat4(1.0), profile, 1024);
  }
  {
    TriangleMesh& yoke = gear.part("main-strut", "axle-yoke", kStrutGrey);
    appendBlockWithHole(yoke, frameAlongAxis({0.0, -0.21, kAxleZ}, {0.0, 1.0, 0.0}),
                        {0.16, 0.42, 0.078, 0.42}, 256);
  }
  {
    // torque links in front of the strut: upper link, lower link, apex joint
    TriangleMesh& links = gear.part("main-strut", "torque-links", kDarkGrey);
    const glm::dvec3 top(0.20, 0.0, 1.84);
    const glm::dvec3 apex(0.40, 0.0, 1.34);
    const glm::dvec3 bottom(0.20, 0.0, 0.78);
    for (const auto& [a, b] : {std::pair{top, apex}, std::pair{apex, bottom}}) {
      const double halfLength = 0.5 * glm::length(b - a);
      for (const double y : {-0.045, 0.045}) {
        const glm::dvec3 offset(0.0, y, 0.0);
        appendOrientedBox(links, 0.5 * (a + b) + offset, b - a, {0.02, 0.012, halfLength});
      }
    }
    TriangleMesh& pins = gear.part("main-strut", "torque-link-pins", kChrome);
    for (const glm::dvec3& joint : {top, apex, bottom}) {
      appendCylinder(pins, frameAlongAxis(joint - glm::dvec3(0.0, 0.075, 0.0), {0.0, 1.0, 0.0}), 0.018, 0.15,
                     96);
    }
    TriangleMesh& lugs = gear.part("main-strut", "torque-link-lugs", kStrutGrey);
    appendLug(lugs, {0.17, 0.0, 1.84}, {0.0, 1.0, 0.0}, 0.045, 0.06, 0.0185);
    appendLug(lugs, {0.17, 0.0, 0.78}, {0.0, 1.0, 0.0}, 0.045, 0.06, 0.0185);
  }
  {
    TriangleMesh& trunnion = gear.part("main-strut", "trunnion-beam", kStrutGrey);
    const double h = kTrunnionHalfLengthM;
    const ProfilePoint profile[] = {
        {0.0, -h},         {0.090, -h},       {0.100, -h + 0.01}, {0.100, -h + 0.10}, {0.120, -h + 0.12},
        {0.120, h - 0.12}, {0.100, h - 0.10}, {0.100, h - 0.01},  {0.090, h},         {0.0, h}};
    appendLathe(trunnion, frameAlongAxis({0.0, 0.0, kTrunnionZ}, {1.0, 0.0, 0.0}), profile, 768);
    TriangleMesh& housing = gear.part("main-strut", "trunnion-housing", kDarkGrey);
    appendBox(housing, translation({0.0, 0.0, 4.38}), {0.22, 0.20, 0.16});
    TriangleMesh& fittings = gear.part("main-strut", "airframe-fittings", kPrimerGreen);
    for (const double x : {-1.80, 1.80}) {
      appendBox(fittings, translation({x, 0.0, 4.59}), {0.14, 0.16, 0.21});
      appendHollowCylinder(fittings, frameAlongAxis({x - 0.13, 0.0, kTrunnionZ}, {1.0, 0.0, 0.0}), 0.1205,
                           0.175, 0.26, 256);
    }
  }
}

void buildBraces(GearBuilder& gear) {
  {
    // drag brace: trunnion lug → knee → strut collar, aft of the strut
    TriangleMesh& tubes = gear.part("drag-brace", "drag-brace-tubes", kStrutGrey);
    const glm::dvec3 upper = kDragBraceUpperWorld;
    const glm::dvec3 knee = kDragBraceKneeWorld;
    const glm::dvec3 lower = kDragBraceLowerWorld;
    // both halves end 20 mm inside the knee joint, so their caps never share a vertex
    appendBar(tubes, upper, knee - 0.02 * glm::normalize(knee - upper), kDragBraceRadiusM, 0.075, 0.08, 512);
    appendBar(tubes, knee + 0.02 * glm::normalize(lower - knee), lower, kDragBraceRadiusM, 0.075, 0.08, 512);
    TriangleMesh& lugs = gear.part("drag-brace", "drag-brace-lugs", kDarkGrey);
    appendLug(lugs, upper, {0.0, 1.0, 0.0}, 0.09, 0.20, 0.025);
    appendLug(lugs, lower, {0.0, 1.0, 0.0}, 0.09, 0.20, 0.025);
    appendHollowCylinder(lugs, frameAlongAxis(knee - glm::dvec3(0.0, 0.11, 0.0), {0.0, 1.0, 0.0}), 0.025,
                         0.085, 0.22, 256);
    // lock link from the knee down to the strut
    appendBar(tubes, knee + glm::dvec3(0.0, 0.14, -0.05), {-0.14, 0.10, 2.75}, 0.025, 0.035, 0.05, 192);
  }
  {
    TriangleMesh& tubes = gear.part("side-brace", "side-brace-tubes", kStrutGrey);
    const glm::dvec3 lower = kSideBraceLowerWorld;
    const glm::dvec3 upper = kSideBraceUpperWorld;
    appendBar(tubes, lower, upper, kSideBraceRadiusM, 0.065, 0.08, 512);
    TriangleMesh& fittings = gear.part("side-brace", "side-brace-fittings", kPrimerGreen);
    appendBox(fittings, translation({0.0, -0.85, 4.25}), {0.10, 0.10, 0.10});
    appendLug(fittings, lower, {1.0, 0.0, 0.0}, 0.08, 0.16, 0.022);
  }
}

void buildWheelsAndBrakes(GearBuilder& gear) {
  const std::vector<ProfilePoint> tyreSection = tyreCrossSection();
  TriangleMesh& tyres = gear.part("wheel-and-brake", "tyres", kRubber);
  TriangleMesh& rims = gear.part("wheel-and-brake", "rims", kAluminium);
  TriangleMesh& discs = gear.part("wheel-and-brake", "brake-discs", kCarbon);
  TriangleMesh& housings = gear.part("wheel-and-brake", "brake-housings", kBrakeSteel);
  TriangleMesh& pistons = gear.part("wheel-and-brake", "brake-pistons", kChrome);
  for (const double side : {-1.0, 1.0}) {
    // local z points outboard; z < 0 is the inboard (brake) side of the wheel
    const glm::dmat4 wheel = frameAlongAxis({0.0, side * kWheelCentreY, kAxleZ}, {0.0, side, 0.0});
    appendLathe(tyres, wheel, tyreSection, kTyreSegments);
    const ProfilePoint rim[] = {{0.080, -0.12}, {0.150, -0.12}, {0.150, -0.02}, {0.245, -0.02},
                                {0.245, -0.19}, {0.300, -0.19}, {0.300, -0.17}, {0.260, -0.17},
                                {0.260, 0.17},  {0.300, 0.17},  {0.300, 0.19},  {0.245, 0.19},
                                {0.245, 0.02},  {0.150, 0.02},  {0.150, 0.12},  {0.080, 0.12}};
    appendLathe(rims, wheel, rim, 768);
    // eight discs between hub and rim barrel, inboard of the web
    for (int k = 0; k < 8; ++k) {
      const double z0 = -0.170 + 0.017 * static_cast<double>(k);
      const ProfilePoint disc[] = {{0.156, z0}, {0.236, z0}, {0.236, z0 + 0.013}, {0.156, z0 + 0.013}};
      appendLathe(discs, wheel, disc, 768);
    }
    const ProfilePoint housing[] = {{0.085, -0.275}, {0.225, -0.275}, {0.235, -0.265}, {0.235, -0.205},
                                    {0.225, -0.195}, {0.150, -0.195}, {0.150, -0.125}, {0.130, -0.125},
                                    {0.130, -0.195}, {0.085, -0.195}};
    appendLathe(housings, wheel, housing, 768);
    for (int k = 0; k < 10; ++k) {
      const double angle = 2.0 * kPi * (static_cast<double>(k) + 0.5) / 10.0;
      const glm::dvec4 local(0.19 * std::cos(angle), 0.19 * std::sin(angle), -0.300, 1.0);
      appendCylinder(pistons, frameAlongAxis(glm::dvec3(wheel * local), {0.0, side, 0.0}), 0.020, 0.028, 96);
    }
  }
  TriangleMesh& axle = gear.part("wheel-and-brake", "axle", kChrome);
  const ProfilePoint axleProfile[] = {{0.0, -0.93},   {0.055, -0.93}, {0.060, -0.925}, {0.060, -0.90},
                                      {0.075, -0.89}, {0.075, 0.89},  {0.060, 0.90},   {0.060, 0.925},
                                      {0.055, 0.93},  {0.0, 0.93}};
  appendLathe(axle, frameAlongAxis({0.0, 0.0, kAxleZ}, {0.0, 1.0, 0.0}), axleProfile, 512);
  TriangleMesh& nuts = gear.part("wheel-and-brake", "axle-nuts", kDarkGrey);
  for (const double side : {-1.0, 1.0}) {
    const ProfilePoint nut[] = {{0.0605, 0.0}, {0.098, 0.0, 6}, {0.098, 0.045, 6}, {0.0605, 0.045}};
    appendLathe(nuts, frameAlongAxis({0.0, side * 0.905, kAxleZ}, {0.0, side, 0.0}), nut, 96);
  }
}

}  // namespace voxhap::landing_gear

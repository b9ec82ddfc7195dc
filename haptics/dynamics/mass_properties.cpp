#include "haptics/dynamics/mass_properties.h"

#include <array>
#include <cmath>
#include <sstream>
#include <string>

#include "haptics/core/error.h"

namespace voxhap {
namespace {

/// Volume integrals of 1, x, y, z, x², y², z², xy, yz, zx over a solid, in coordinates
/// relative to a reference point (unit density).
using VolumeIntegrals = std::array<double, 10>;

/// Eberly's subexpressions for one coordinate of a triangle's three vertices.
struct Subexpressions {
  double f1, f2, f3, g0, g1, g2;
};

Subexpressions subexpressions(double w0, double w1, double w2) {
  const double temp0 = w0 + w1;
  const double temp1 = w0 * w0;
  const double temp2 = temp1 + w1 * temp0;
  Subexpressions s{};
  s.f1 = temp0 + w2;
  s.f2 = temp2 + w2 * s.f1;
  s.f3 = w0 * temp1 + w1 * temp2 + w2 * s.f2;
  s.g0 = s.f2 + w0 * (s.f1 + w0);
  s.g1 = s.f2 + w1 * (s.f1 + w1);
  s.g2 = s.f2 + w2 * (s.f1 + w2);
  return s;
}

// Exact polyhedral mass properties after D. Eberly, "Polyhedral Mass Properties
// (Revisited)", Geometric Tools (2002), itself a simplification of B. Mirtich, "Fast and
// Accurate Computation of Polyhedral Mass Properties", JGT 1(2), 1996. The divergence
// theorem turns each volume integral ∫ x^a y^b z^c dV into a sum over the boundary
// triangles of a polynomial in their vertex coordinates, weighted by the (unnormalised)
// outward normal; the sums are exact for a closed, outward-oriented polyhedron.
// Coordinates are taken relative to `referenceWorld` (the object's bounds centre), so
// that objects placed far from the world origin lose no precision to cancellation.
VolumeIntegrals integrate(const TriangleMesh& mesh, const glm::dvec3& referenceWorld) {
  VolumeIntegrals sum{};
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 p0 = glm::dvec3(mesh.positionsWorld[t.x]) - referenceWorld;
    const glm::dvec3 p1 = glm::dvec3(mesh.positionsWorld[t.y]) - referenceWorld;
    const glm::dvec3 p2 = glm::dvec3(mesh.positionsWorld[t.z]) - referenceWorld;
    const glm::dvec3 d = glm::cross(p1 - p0, p2 - p0);
    const Subexpressions x = subexpressions(p0.x, p1.x, p2.x);
    const Subexpressions y = subexpressions(p0.y, p1.y, p2.y);
    const Subexpressions z = subexpressions(p0.z, p1.z, p2.z);
    sum[0] += d.x * x.f1;
    sum[1] += d.x * x.f2;
    sum[2] += d.y * y.f2;
    sum[3] += d.z * z.f2;
    sum[4] += d.x * x.f3;
    sum[5] += d.y * y.f3;
    sum[6] += d.z * z.f3;
    sum[7] += d.x * (p0.y * x.g0 + p1.y * x.g1 + p2.y * x.g2);
    sum[8] += d.y * (p0.z * y.g0 + p1.z * y.g1 + p2.z * y.g2);
    sum[9] += d.z * (p0.x * z.g0 + p1.x * z.g1 + p2.x * z.g2);
  }
  constexpr std::array<double, 10> kScale = {1.0 / 6,  1.0 / 24, 1.0 / 24,  1.0 / 24,  1.0 / 60,
                                             1.0 / 60, 1.0 / 60, 1.0 / 120, 1.0 / 120, 1.0 / 120};
  for (std::size_t i = 0; i < sum.size(); ++i) sum[i] *= kScale[i];
  return sum;
}

std::string quoted(const std::string& s) {
  return "'" + s + "'";
}

std::string formatNumber(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

}  // namespace

double objectDensityKgPerM3(const SceneObject& object) {
  return object.settings.densityKgPerM3.value_or(kDefaultDensityKgPerM3);
}

MassProperties computeMassProperties(const SceneObject& object, double densityKgPerM3) {
  const std::string where = "object " + quoted(object.name);
  if (!(densityKgPerM3 > 0.0) || !std::isfinite(densityKgPerM3)) {
    throw Error(where + ": density must be a positive number of kg/m³, got " + formatNumber(densityKgPerM3));
  }
  const Bounds bounds = object.bounds();
  if (bounds.empty()) throw Error(where + " has no triangles, so no volume, mass or inertia");
  const glm::dvec3 reference = 0.5 * (bounds.min + bounds.max);

  VolumeIntegrals total{};
  for (const Part& part : object.parts) {
    const std::string partWhere = where + " part " + quoted(part.name);
    const MeshTopology& topology = part.topology;
    if (!topology.closed()) {
      throw Error(partWhere + " is open (" + std::to_string(topology.boundaryEdges) + " boundary and " +
                  std::to_string(topology.nonManifoldEdges) +
                  " non-manifold edges), so its volume, mass and inertia are undefined");
    }
    if (!topology.consistentlyOriented()) {
      throw Error(partWhere + " is not consistently oriented (" + std::to_string(topology.misorientedEdges) +
                  " edges join flipped triangles), so its volume, mass and inertia are undefined");
    }
    const VolumeIntegrals integrals = integrate(part.mesh, reference);
    if (!(integrals[0] > 0.0)) {
      throw Error(partWhere + " encloses a volume of " + formatNumber(integrals[0]) +
                  " m³, not a positive one (is the mesh inside out?)");
    }
    for (std::size_t i = 0; i < total.size(); ++i) total[i] += integrals[i];
  }
  const double volume = total[0];
  if (!(volume > 0.0) || !std::isfinite(volume)) {
    throw Error(where + " encloses no positive volume (" + formatNumber(volume) + " m³)");
  }

  // centre of mass relative to the reference point, then second moments about it
  const glm::dvec3 c(total[1] / volume, total[2] / volume, total[3] / volume);
  const double xx = total[4] - volume * c.x * c.x;
  const double yy = total[5] - volume * c.y * c.y;
  const double zz = total[6] - volume * c.z * c.z;
  const double xy = total[7] - volume * c.x * c.y;
  const double yz = total[8] - volume * c.y * c.z;
  const double zx = total[9] - volume * c.z * c.x;

  MassProperties result;
  result.volumeM3 = volume;
  result.massKg = densityKgPerM3 * volume;
  result.comLocal = reference + c;
  glm::dmat3 inertia;  // column-major: inertia[column][row]
  inertia[0] = glm::dvec3(yy + zz, -xy, -zx);
  inertia[1] = glm::dvec3(-xy, zz + xx, -yz);
  inertia[2] = glm::dvec3(-zx, -yz, xx + yy);
  result.inertiaAboutComKgM2 = densityKgPerM3 * inertia;
  return result;
}

}  // namespace voxhap

#include "haptics/dynamics/mass_properties.h"

#include <cmath>
#include <limits>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "haptics/geometry/mesh_builder.h"
#include "support/rigid_body_fixtures.h"

namespace voxhap {
namespace {

using test::boxObject;

/// Closed-form inertia of a solid box about its centre, local axes.
glm::dmat3 boxInertia(double massKg, const glm::dvec3& h) {
  glm::dmat3 i(0.0);
  i[0][0] = massKg / 3.0 * (h.y * h.y + h.z * h.z);
  i[1][1] = massKg / 3.0 * (h.z * h.z + h.x * h.x);
  i[2][2] = massKg / 3.0 * (h.x * h.x + h.y * h.y);
  return i;
}

void expectMatrixNear(const glm::dmat3& actual, const glm::dmat3& expected, double tolerance) {
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) {
      EXPECT_NEAR(actual[c][r], expected[c][r], tolerance) << "element " << r << "," << c;
    }
  }
}

void expectThrowsMentioning(const SceneObject& object, double density, const std::string& what) {
  try {
    computeMassProperties(object, density);
    FAIL() << "no error; expected one mentioning " << what;
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'" + object.name + "'"), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(MassProperties, BoxMatchesClosedForm) {
  // half extents exact in float, so the polyhedron is exactly the box
  const glm::dvec3 h(0.5, 0.25, 0.125);
  const MassProperties mp = computeMassProperties(boxObject(h), 1000.0);
  EXPECT_DOUBLE_EQ(mp.volumeM3, 8.0 * h.x * h.y * h.z);
  EXPECT_DOUBLE_EQ(mp.massKg, 125.0);
  EXPECT_NEAR(glm::length(mp.comLocal), 0.0, 1e-15);
  expectMatrixNear(mp.inertiaAboutComKgM2, boxInertia(125.0, h), 1e-12);
}

TEST(MassProperties, BoxFarFromOriginLosesNoPrecision) {
  // corners at 99.5 and 100.5 m are exact floats; integrating about the object's own
  // centre keeps the result as exact as at the origin
  const glm::dvec3 h(0.5, 0.25, 0.125);
  const glm::dvec3 centre(100.0, -100.0, 50.0);
  const MassProperties mp =
      computeMassProperties(boxObject(h, glm::translate(glm::dmat4(1.0), centre)), 1000.0);
  EXPECT_DOUBLE_EQ(mp.massKg, 125.0);
  EXPECT_NEAR(glm::length(mp.comLocal - centre), 0.0, 1e-13);
  expectMatrixNear(mp.inertiaAboutComKgM2, boxInertia(125.0, h), 1e-12);
}

TEST(MassProperties, GeodesicSphereLiesBetweenInscribedAndCircumscribedBalls) {
  const double radius = 0.05;
  const double density = 7850.0;
  TriangleMesh mesh;
  appendGeodesicSphere(mesh, glm::dmat4(1.0), radius, 4);
  // the polyhedron contains the ball touching its faces and lies in the ball through its
  // vertices; volume and every moment of inertia about the centre are monotone in the set
  double inner = radius;
  double outer = 0.0;
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 a(mesh.positionsWorld[t.x]), b(mesh.positionsWorld[t.y]), c(mesh.positionsWorld[t.z]);
    inner = std::min(inner, std::abs(glm::dot(glm::normalize(glm::cross(b - a, c - a)), a)));
  }
  for (const glm::vec3& p : mesh.positionsWorld) outer = std::max(outer, glm::length(glm::dvec3(p)));
  SceneObject sphere{"sphere", {}, {makePart("ball", glm::vec4(1.0f), mesh)}};
  const MassProperties mp = computeMassProperties(sphere, density);

  const auto ballVolume = [](double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r; };
  const auto ballInertia = [&](double r) { return 0.4 * density * ballVolume(r) * r * r; };
  EXPECT_GT(mp.volumeM3, ballVolume(inner));
  EXPECT_LT(mp.volumeM3, ballVolume(outer));
  // against the analytic sphere: within the tessellation error 3·(1 − r_in/r)
  EXPECT_NEAR(mp.volumeM3 / ballVolume(radius), 1.0, 3.0 * (1.0 - inner / radius));
  EXPECT_LT(glm::length(mp.comLocal), 1e-9 * radius);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_GT(mp.inertiaAboutComKgM2[axis][axis], ballInertia(inner));
    EXPECT_LT(mp.inertiaAboutComKgM2[axis][axis], ballInertia(outer));
    // octahedral symmetry makes the tensor isotropic
    EXPECT_NEAR(mp.inertiaAboutComKgM2[axis][axis] / mp.inertiaAboutComKgM2[0][0], 1.0, 1e-6);
    EXPECT_NEAR(mp.inertiaAboutComKgM2[axis][(axis + 1) % 3], 0.0, 1e-6 * mp.inertiaAboutComKgM2[0][0]);
  }
}

TEST(MassProperties, RotatedOffsetBoxHasRotatedInertiaAboutItsCentre) {
  const glm::dvec3 h(0.04, 0.02, 0.01);
  const glm::dvec3 offset(0.7, -0.3, 1.2);
  const glm::dquat rotation = glm::angleAxis(0.7, glm::normalize(glm::dvec3(1.0, 2.0, -0.5)));
  const glm::dmat3 r = glm::mat3_cast(rotation);
  glm::dmat4 localToWorld(r);
  localToWorld[3] = glm::dvec4(offset, 1.0);
  const MassProperties mp = computeMassProperties(boxObject(h, localToWorld), 2000.0);

  const double mass = 2000.0 * 8.0 * h.x * h.y * h.z;
  // positions are floats: ~1e-7 relative
  EXPECT_NEAR(mp.massKg / mass, 1.0, 1e-5);
  EXPECT_NEAR(glm::length(mp.comLocal - offset), 0.0, 1e-6);
  const glm::dmat3 expected = r * boxInertia(mass, h) * glm::transpose(r);
  expectMatrixNear(mp.inertiaAboutComKgM2, expected, 1e-5 * expected[0][0]);
}

TEST(MassProperties, PartsCombineByTheParallelAxisTheorem) {
  // two boxes as two parts of one object (exact floats)
  const glm::dvec3 ha(0.25, 0.125, 0.125), hb(0.125, 0.25, 0.5);
  const glm::dvec3 ca(-1.0, 0.5, 0.0), cb(2.0, 0.0, -0.75);
  TriangleMesh a, b;
  appendBox(a, glm::translate(glm::dmat4(1.0), ca), ha);
  appendBox(b, glm::translate(glm::dmat4(1.0), cb), hb);
  SceneObject object{"dumbbell", {}, {makePart("a", glm::vec4(1.0f), a), makePart("b", glm::vec4(1.0f), b)}};
  const double density = 500.0;
  const MassProperties mp = computeMassProperties(object, density);

  const double ma = density * 8.0 * ha.x * ha.y * ha.z;
  const double mb = density * 8.0 * hb.x * hb.y * hb.z;
  const glm::dvec3 com = (ma * ca + mb * cb) / (ma + mb);
  // Steiner: I_about_com = I_own + m·(|d|²·E − d·dᵀ), d = part centre − object centre of mass
  const auto steiner = [](double m, const glm::dvec3& d) {
    return m * (glm::dot(d, d) * glm::dmat3(1.0) - glm::outerProduct(d, d));
  };
  const glm::dmat3 expected =
      boxInertia(ma, ha) + steiner(ma, ca - com) + boxInertia(mb, hb) + steiner(mb, cb - com);
  EXPECT_DOUBLE_EQ(mp.massKg, ma + mb);
  EXPECT_NEAR(glm::length(mp.comLocal - com), 0.0, 1e-14);
  expectMatrixNear(mp.inertiaAboutComKgM2, expected, 1e-12 * expected[0][0]);
  EXPECT_NE(mp.inertiaAboutComKgM2[0][2], 0.0);  // products of inertia appear off-centre
}

TEST(MassProperties, OpenMeshThrowsNamingObjectAndPart) {
  SceneObject box = boxObject(glm::dvec3(0.1), glm::dmat4(1.0), "lid");
  TriangleMesh mesh = box.parts[0].mesh;
  mesh.triangles.pop_back();
  box.parts[0] = makePart("lid part", glm::vec4(1.0f), mesh);
  expectThrowsMentioning(box, 1000.0, "part 'lid part' is open");
}

TEST(MassProperties, InsideOutMeshThrows) {
  SceneObject box = boxObject(glm::dvec3(0.1), glm::dmat4(1.0), "inverted");
  TriangleMesh mesh = box.parts[0].mesh;
  for (glm::uvec3& t : mesh.triangles) std::swap(t.y, t.z);
  box.parts[0] = makePart("inverted part", glm::vec4(1.0f), mesh);
  ASSERT_TRUE(box.closed());
  ASSERT_TRUE(box.consistentlyOriented());
  expectThrowsMentioning(box, 1000.0, "inside out");
}

TEST(MassProperties, PartlyFlippedMeshThrows) {
  SceneObject box = boxObject(glm::dvec3(0.1), glm::dmat4(1.0), "patchy");
  TriangleMesh mesh = box.parts[0].mesh;
  std::swap(mesh.triangles[0].y, mesh.triangles[0].z);
  box.parts[0] = makePart("patchy part", glm::vec4(1.0f), mesh);
  expectThrowsMentioning(box, 1000.0, "not consistently oriented");
}

TEST(MassProperties, ObjectWithoutTrianglesThrows) {
  SceneObject empty{"ghost", {}, {}};
  expectThrowsMentioning(empty, 1000.0, "no triangles");
}

TEST(MassProperties, NonPositiveOrNonFiniteDensityThrows) {
  const SceneObject box = boxObject(glm::dvec3(0.1), glm::dmat4(1.0), "weightless");
  for (double density :
       {0.0, -7850.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    expectThrowsMentioning(box, density, "density");
  }
}

TEST(MassProperties, DensityDefaultsToSteelUnlessTheObjectSetsOne) {
  SceneObject box = boxObject(glm::dvec3(0.1));
  EXPECT_EQ(objectDensityKgPerM3(box), kDefaultDensityKgPerM3);
  EXPECT_EQ(kDefaultDensityKgPerM3, 7850.0);
  box.settings.densityKgPerM3 = 2700.0;
  EXPECT_EQ(objectDensityKgPerM3(box), 2700.0);
}

}  // namespace
}  // namespace voxhap

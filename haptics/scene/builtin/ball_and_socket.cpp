// Ball-and-socket: the paper's first benchmark (DESIGN §6). A ball of radius 25 mm
// (2048 triangles; every length below scales with the radius asked for) sits in a socket whose spherical
// cavity has the same radius and the same centre, so the two surfaces mate; the cavity wraps 35° past the
// ball's equator, so the ball is captured and can only turn in place. Ball centre at the origin, z up,
// metres.
//
// Both polyhedra have their vertices on the 25 mm sphere and their faces inside it (by at
// most 0.10 mm for either), so the ball's vertices poke through the cavity's facets by up
// to 0.1 mm: mating surfaces are handled by displacing the pointshell (DESIGN §4.3).

#include <numbers>

#include "haptics/geometry/mesh_builder.h"
#include "haptics/scene/builtin/builtin_scenes.h"

namespace voxhap {
namespace {

constexpr int kBallSubdivisions = 4;  // 8·4^4 = 2048 triangles
constexpr double kSocketOuterRadiusM = 0.040;
constexpr double kSocketBottomDepthM = 0.040;  // bottom face 15 mm below the cavity's pole
constexpr double kOpeningAboveEquatorDeg = 35.0;
constexpr int kSocketSegments = 64;
constexpr int kSocketCavityRings = 15;  // 64·(4 + 2·15) = 2176 triangles
/// The ball's points, inward along their normals, m. The ball and its cavity have their
/// vertices on one sphere, a press fit: with surface planes, points on the ball's surface
/// would press on the cavity all round and the ball could not turn.
constexpr double kBallPointOffsetM = -0.0005;

}  // namespace

Scene makeBallAndSocket(double ballRadiusM) {
  const glm::dmat4 identity(1.0);
  const double scale = ballRadiusM / kBallAndSocketRadiusM;
  Scene scene;
  scene.sourceName = "ball-and-socket";

  TriangleMesh ballMesh;
  appendGeodesicSphere(ballMesh, identity, ballRadiusM, kBallSubdivisions);
  SceneObject ball;
  ball.name = "ball";
  ball.settings.role = ObjectRole::Dynamic;
  ball.settings.pointOffsetM = kBallPointOffsetM * scale;
  ball.parts.push_back(makePart("ball", glm::vec4(0.78f, 0.80f, 0.84f, 1.0f), std::move(ballMesh)));

  TriangleMesh socketMesh;
  const SocketSpec socketSpec{ballRadiusM, kSocketOuterRadiusM * scale, kSocketBottomDepthM * scale,
                              kOpeningAboveEquatorDeg * std::numbers::pi / 180.0};
  appendSphericalSocket(socketMesh, identity, socketSpec, kSocketSegments, kSocketCavityRings);
  SceneObject socket;
  socket.name = "socket";
  socket.settings.role = ObjectRole::Static;
  socket.parts.push_back(makePart("socket", glm::vec4(0.72f, 0.52f, 0.30f, 1.0f), std::move(socketMesh)));

  scene.objects.push_back(std::move(ball));
  scene.objects.push_back(std::move(socket));
  return scene;
}

}  // namespace voxhap

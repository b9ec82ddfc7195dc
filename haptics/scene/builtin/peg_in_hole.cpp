// Peg-in-hole: a round peg (radius 10 mm, 60 mm long, 0.5 mm × 45° chamfer at the tip)
// hangs 1 mm above the mouth of a blind hole in a square block, axes aligned on z.
//
// Clearance. The hole's vertices lie on a circle of radius 10.2 mm, the peg's on 10 mm, so
// the nominal radial clearance is 0.2 mm a side. Flat facets cut inside their circle by
// the sagitta r·(1 - cos(π/n)); the peg's facets only shrink the peg, while the hole's bring
// its wall closer: with n = 128 segments the hole's facets sit at 10.2·cos(π/128) =
// 10.1969 mm from the axis, so the least clearance between the polygonal surfaces is
// 0.1969 mm (≥ 0.18 mm), wherever the peg's vertices face the middle of a hole facet.

#include "haptics/geometry/mesh_builder.h"
#include "haptics/scene/builtin/builtin_scenes.h"

namespace voxhap {
namespace {

constexpr double kPegRadiusM = 0.010;
constexpr double kPegLengthM = 0.060;
constexpr double kPegChamferM = 0.0005;
constexpr double kClearanceM = 0.0002;
constexpr double kHoleRadiusM = kPegRadiusM + kClearanceM;
constexpr double kHoleDepthM = 0.030;
constexpr double kBlockHalfWidthM = 0.030;
constexpr double kBlockHeightM = 0.040;
constexpr double kPegLiftM = 0.001;  // gap between the peg's tip and the block's top face
constexpr int kSegments = 128;

}  // namespace

Scene makePegInHole() {
  Scene scene;
  scene.sourceName = "peg-in-hole";

  // the block's top face (the hole's mouth) is the plane z = 0
  TriangleMesh blockMesh;
  glm::dmat4 blockToWorld(1.0);
  blockToWorld[3] = glm::dvec4(0.0, 0.0, -kBlockHeightM, 1.0);
  appendBlockWithHole(blockMesh, blockToWorld, {kBlockHalfWidthM, kBlockHeightM, kHoleRadiusM, kHoleDepthM},
                      kSegments);

  TriangleMesh pegMesh;
  glm::dmat4 pegToWorld(1.0);
  pegToWorld[3] = glm::dvec4(0.0, 0.0, kPegLiftM, 1.0);
  const ProfilePoint pegProfile[] = {{0.0, 0.0},
                                     {kPegRadiusM - kPegChamferM, 0.0},
                                     {kPegRadiusM, kPegChamferM},
                                     {kPegRadiusM, kPegLengthM - kPegChamferM},
                                     {kPegRadiusM - kPegChamferM, kPegLengthM},
                                     {0.0, kPegLengthM}};
  appendLathe(pegMesh, pegToWorld, pegProfile, kSegments);

  SceneObject peg;
  peg.name = "peg";
  peg.settings.role = ObjectRole::Dynamic;
  peg.parts.push_back(makePart("peg", glm::vec4(0.80f, 0.80f, 0.82f, 1.0f), std::move(pegMesh)));

  SceneObject block;
  block.name = "block";
  block.settings.role = ObjectRole::Static;
  block.parts.push_back(makePart("block", glm::vec4(0.35f, 0.45f, 0.60f, 1.0f), std::move(blockMesh)));

  scene.objects.push_back(std::move(peg));
  scene.objects.push_back(std::move(block));
  return scene;
}

}  // namespace voxhap

// glTF loader on good files: storage forms, primitive forms, transforms, names,
// colours, Voxhap extras, topology checks and the round trip through the writer.

#include "haptics/scene/gltf_loader.h"

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "haptics/geometry/mesh_topology.h"
#include "haptics/scene/gltf_writer.h"
#include "tests/support/gltf_fixtures.h"

namespace voxhap {
namespace {

namespace fs = std::filesystem;
using test::BufferStorage;
using test::GltfDoc;
using test::MeshData;
using test::TempDir;

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& line : lines) out += line + "\n";
  return out;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// The warnings that contain `part`.
std::vector<std::string> warningsWith(const Scene& scene, const std::string& part) {
  std::vector<std::string> out;
  for (const std::string& w : scene.warnings) {
    if (contains(w, part)) out.push_back(w);
  }
  return out;
}

std::vector<glm::uvec3> triangles(const std::vector<std::uint32_t>& flat) {
  std::vector<glm::uvec3> out;
  for (std::size_t i = 0; i + 2 < flat.size(); i += 3) out.emplace_back(flat[i], flat[i + 1], flat[i + 2]);
  return out;
}

/// The only part of the only object, after checking that there is exactly one.
const Part& onlyPart(const Scene& scene) {
  EXPECT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects.at(0).parts.size(), 1u);
  return scene.objects.at(0).parts.at(0);
}

void expectNear(const glm::vec3& actual, const glm::vec3& expected, float tolerance = 1e-6f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance) << "x of " << testing::PrintToString(actual);
  EXPECT_NEAR(actual.y, expected.y, tolerance) << "y of " << testing::PrintToString(actual);
  EXPECT_NEAR(actual.z, expected.z, tolerance) << "z of " << testing::PrintToString(actual);
}

/// Checks that `scene` is exactly the unit cube as one clean object named `name`.
void expectUnitCube(const Scene& scene, const std::string& name) {
  EXPECT_TRUE(scene.warnings.empty()) << joined(scene.warnings);
  ASSERT_EQ(scene.objects.size(), 1u);
  const SceneObject& object = scene.objects[0];
  EXPECT_EQ(object.name, name);
  EXPECT_EQ(object.settings.role, ObjectRole::Static);
  ASSERT_EQ(object.parts.size(), 1u);
  const Part& part = object.parts[0];
  const MeshData cube = test::unitCube();
  EXPECT_EQ(part.name, name);
  EXPECT_EQ(part.mesh.positionsWorld, cube.positions);
  EXPECT_EQ(part.mesh.triangles, triangles(cube.indices));
  EXPECT_EQ(part.degenerateTrianglesDropped, 0u);
  EXPECT_TRUE(part.topology.closed());
  EXPECT_TRUE(part.topology.consistentlyOriented());
  EXPECT_DOUBLE_EQ(signedVolume(part.mesh), 1.0);
  EXPECT_EQ(scene.triangleCount(), 12u);
}

// ---- storage forms ----------------------------------------------------------

TEST(GltfLoader, LoadsGltfWithEmbeddedDataUriBuffer) {
  TempDir dir;
  const fs::path file = test::writeDoc(test::singleMeshDoc(test::unitCube(), "cube"), dir.path(), "scene",
                                       BufferStorage::DataUri);
  const Scene scene = loadGltfScene(file);
  expectUnitCube(scene, "cube");
  EXPECT_EQ(scene.sourceName, file.string());
}

TEST(GltfLoader, LoadsGltfWithExternalBuffer) {
  TempDir dir;
  const fs::path file = test::writeDoc(test::singleMeshDoc(test::unitCube(), "cube"), dir.path(), "scene",
                                       BufferStorage::External);
  ASSERT_TRUE(fs::exists(dir / "scene.bin"));
  expectUnitCube(loadGltfScene(file), "cube");
}

TEST(GltfLoader, LoadsExternalBufferRelativeToTheFileNotTheWorkingDirectory) {
  TempDir dir;
  fs::create_directories(dir / "models");
  const fs::path file = test::writeDoc(test::singleMeshDoc(test::unitCube(), "cube"), dir / "models", "scene",
                                       BufferStorage::External);
  const fs::path before = fs::current_path();
  fs::current_path(dir.path());
  Scene scene;
  EXPECT_NO_THROW(scene = loadGltfScene(fs::path("models") / "scene.gltf"));
  fs::current_path(before);
  expectUnitCube(scene, "cube");
  EXPECT_TRUE(fs::exists(file));
}

TEST(GltfLoader, LoadsGlb) {
  TempDir dir;
  const fs::path file =
      test::writeDoc(test::singleMeshDoc(test::unitCube(), "cube"), dir.path(), "scene", BufferStorage::Glb);
  expectUnitCube(loadGltfScene(file), "cube");
}

TEST(GltfLoader, DecidesGlbByContentNotByExtension) {
  TempDir dir;
  const fs::path glb =
      test::writeDoc(test::singleMeshDoc(test::unitCube(), "cube"), dir.path(), "scene", BufferStorage::Glb);
  const fs::path misnamed = dir / "really_a_glb.gltf";
  fs::copy_file(glb, misnamed);
  expectUnitCube(loadGltfScene(misnamed), "cube");
}

TEST(GltfLoader, LoadsGltfStartingWithAByteOrderMarkAndWhitespace) {
  TempDir dir;
  const fs::path file = test::writeDoc(test::singleMeshDoc(test::unitCube(), "cube"), dir.path(), "bom",
                                       BufferStorage::DataUri);
  std::vector<unsigned char> bytes = {0xEF, 0xBB, 0xBF, '\n', ' ', '\t'};
  const std::vector<unsigned char> json = test::readBytes(file);
  bytes.insert(bytes.end(), json.begin(), json.end());
  test::writeBytes(file, bytes);
  expectUnitCube(loadGltfScene(file), "cube");
}

// ---- primitive forms --------------------------------------------------------

TEST(GltfLoader, LoadsNonIndexedPrimitive) {
  const MeshData cube = test::unitCube();
  std::vector<glm::vec3> soup;
  for (std::uint32_t i : cube.indices) soup.push_back(cube.positions[i]);
  GltfDoc doc;
  doc.addMeshNode(doc.addMesh(doc.addPositions(soup), -1), "soup");
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "soup", BufferStorage::Glb));

  const Part& part = onlyPart(scene);
  EXPECT_EQ(part.mesh.positionsWorld, soup);
  ASSERT_EQ(part.mesh.triangles.size(), 12u);
  for (std::uint32_t t = 0; t < 12; ++t) {
    EXPECT_EQ(part.mesh.triangles[t], glm::uvec3(3 * t, 3 * t + 1, 3 * t + 2));
  }
  // welding by position makes the triangle soup a closed surface
  EXPECT_TRUE(part.topology.closed());
  EXPECT_TRUE(part.topology.consistentlyOriented());
  EXPECT_TRUE(scene.warnings.empty()) << joined(scene.warnings);
}

/// The cube stored after `unused` padding vertices, its indices shifted by as much,
/// so that the index values need every byte of `indexType`.
void expectCubeWithIndexType(int indexType, std::uint32_t unused) {
  MeshData cube = test::unitCube();
  MeshData padded;
  padded.positions.assign(unused, glm::vec3(0.5f));  // inside the cube, referenced by nothing
  padded.positions.insert(padded.positions.end(), cube.positions.begin(), cube.positions.end());
  for (std::uint32_t i : cube.indices) padded.indices.push_back(i + unused);

  GltfDoc doc;
  doc.addMeshNode(doc.addMesh(padded, -1, indexType), "cube");
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "cube", BufferStorage::Glb));
  const Part& part = onlyPart(scene);
  EXPECT_EQ(part.mesh.triangles, triangles(padded.indices));
  EXPECT_TRUE(part.topology.closed());
  EXPECT_DOUBLE_EQ(signedVolume(part.mesh), 1.0);
}

TEST(GltfLoader, ReadsUnsignedByteIndices) {
  expectCubeWithIndexType(test::kUnsignedByte, 200);
}

TEST(GltfLoader, ReadsUnsignedShortIndices) {
  expectCubeWithIndexType(test::kUnsignedShort, 300);
}

TEST(GltfLoader, ReadsUnsignedIntIndices) {
  expectCubeWithIndexType(test::kUnsignedInt, 70000);
}

TEST(GltfLoader, ConvertsTriangleStripToTriangles) {
  // the strip 0 1 2 3 0 1 wraps a tetrahedron: its four triangles close it
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}};
  GltfDoc doc;
  const int p = doc.addPositions(positions);
  const int i = doc.addIndices({0, 1, 2, 3, 0, 1}, test::kUnsignedShort);
  doc.addMeshNode(doc.addMesh(p, i, test::kModeTriangleStrip), "strip");
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "strip", BufferStorage::DataUri));

  const Part& part = onlyPart(scene);
  const std::vector<glm::uvec3> expected = {{0, 1, 2}, {2, 1, 3}, {2, 3, 0}, {0, 3, 1}};
  EXPECT_EQ(part.mesh.triangles, expected);
  EXPECT_TRUE(part.topology.closed());
  EXPECT_TRUE(part.topology.consistentlyOriented());
  EXPECT_NEAR(signedVolume(part.mesh), 1.0 / 6.0, 1e-12);
  EXPECT_TRUE(scene.warnings.empty()) << joined(scene.warnings);
}

TEST(GltfLoader, ConvertsTriangleFanToTrianglesAndMergesPrimitivesOfOneMesh) {
  // primitive 0: a fan around the apex (three sides); primitive 1: the base triangle
  const std::vector<glm::vec3> positions = {{0, 0, 1}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  GltfDoc doc;
  const int p = doc.addPositions(positions);
  const int fan = doc.addIndices({0, 1, 2, 3, 1}, test::kUnsignedByte);
  const int base = doc.addIndices({1, 3, 2}, test::kUnsignedByte);
  const int mesh = doc.addMesh(p, fan, test::kModeTriangleFan);
  doc.json["meshes"][0]["primitives"].push_back(
      {{"attributes", {{"POSITION", p}}}, {"indices", base}, {"mode", test::kModeTriangles}});
  doc.addMeshNode(mesh, "fan");
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "fan", BufferStorage::DataUri));

  const Part& part = onlyPart(scene);
  // primitive 1's vertices follow primitive 0's in the part
  const std::vector<glm::uvec3> expected = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {5, 7, 6}};
  EXPECT_EQ(part.mesh.triangles, expected);
  EXPECT_EQ(part.mesh.positionsWorld.size(), 8u);
  EXPECT_TRUE(part.topology.closed());
  EXPECT_TRUE(part.topology.consistentlyOriented());
  EXPECT_NEAR(signedVolume(part.mesh), 1.0 / 6.0, 1e-12);
  EXPECT_TRUE(scene.warnings.empty()) << joined(scene.warnings);
}

TEST(GltfLoader, ReadsInterleavedPositionsWithByteStride) {
  // each vertex: position (12 bytes) then a normal (12 bytes) that must not leak in
  const MeshData tet = test::tetrahedron();
  std::vector<float> interleaved;
  for (const glm::vec3& p : tet.positions) {
    interleaved.insert(interleaved.end(), {p.x, p.y, p.z, 99.0f, -99.0f, 42.0f});
  }
  GltfDoc doc;
  const int view = doc.addBufferView(interleaved.data(), interleaved.size() * sizeof(float), 24);
  const int positions = doc.addAccessor(view, test::kFloat, tet.positions.size(), "VEC3", 0);
  doc.addAccessor(view, test::kFloat, tet.positions.size(), "VEC3", 12);  // the normals
  const int indices = doc.addIndices(tet.indices);
  doc.addMeshNode(doc.addMesh(positions, indices), "tet");
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "tet", BufferStorage::Glb));

  const Part& part = onlyPart(scene);
  EXPECT_EQ(part.mesh.positionsWorld, tet.positions);
  EXPECT_EQ(part.mesh.triangles, triangles(tet.indices));
  EXPECT_TRUE(part.topology.closed());
}

// ---- transforms -------------------------------------------------------------

TEST(GltfLoader, BakesTranslationRotationScaleHierarchyToWorld) {
  // parent: translate (10,0,0); child: scale (2,1,1) then rotate 90° about +z
  GltfDoc doc;
  const int mesh = doc.addMesh(test::tetrahedron());
  const int parent = doc.addNode({{"name", "parent"}, {"translation", {10.0, 0.0, 0.0}}});
  const double h = std::sqrt(0.5);
  const int child = doc.addNode(
      {{"name", "child"}, {"mesh", mesh}, {"rotation", {0.0, 0.0, h, h}}, {"scale", {2.0, 1.0, 1.0}}});
  doc.addChild(parent, child);
  doc.addRoot(parent);
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "trs", BufferStorage::Glb));

  const Part& part = onlyPart(scene);
  EXPECT_EQ(part.name, "child");
  ASSERT_EQ(part.mesh.positionsWorld.size(), 4u);
  // local T·R·S: S first, then R, then the parent's T
  expectNear(part.mesh.positionsWorld[0], {10, 0, 0});
  expectNear(part.mesh.positionsWorld[1], {10, 2, 0});
  expectNear(part.mesh.positionsWorld[2], {9, 0, 0});
  expectNear(part.mesh.positionsWorld[3], {10, 0, 1});
  EXPECT_GT(signedVolume(part.mesh), 0.0);
}

TEST(GltfLoader, BakesMatrixUnderTranslatedParentToWorld) {
  // child matrix (column-major): x→y, y→−x, z→z, then translate (1,2,3); parent: +10 z
  GltfDoc doc;
  const int mesh = doc.addMesh(test::tetrahedron());
  const int parent = doc.addNode({{"name", "parent"}, {"translation", {0.0, 0.0, 10.0}}});
  const int child = doc.addNode(
      {{"name", "child"},
       {"mesh", mesh},
       {"matrix", {0.0, 1.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 2.0, 3.0, 1.0}}});
  doc.addChild(parent, child);
  doc.addRoot(parent);
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "matrix", BufferStorage::DataUri));

  const Part& part = onlyPart(scene);
  const std::vector<glm::vec3> expected = {{1, 2, 13}, {1, 3, 13}, {0, 2, 13}, {1, 2, 14}};
  EXPECT_EQ(part.mesh.positionsWorld, expected);
  EXPECT_NEAR(signedVolume(part.mesh), 1.0 / 6.0, 1e-9);
}

TEST(GltfLoader, MirroredScaleKeepsOutwardOrientation) {
  GltfDoc doc;
  const int mesh = doc.addMesh(test::unitCube());
  doc.addRoot(doc.addNode({{"name", "mirrored"}, {"mesh", mesh}, {"scale", {-1.0, 1.0, 1.0}}}));
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "mirror", BufferStorage::Glb));

  const Part& part = onlyPart(scene);
  EXPECT_EQ(part.mesh.positionsWorld[1], glm::vec3(-1, 0, 0));
  EXPECT_DOUBLE_EQ(signedVolume(part.mesh), 1.0);
  EXPECT_TRUE(part.topology.closed());
  EXPECT_TRUE(part.topology.consistentlyOriented());
  EXPECT_TRUE(scene.warnings.empty()) << joined(scene.warnings);
}

TEST(GltfLoader, MirroredMatrixUnderParentKeepsOutwardOrientation) {
  // the mirror sits in the child's matrix (z → −z) under a translated parent
  GltfDoc doc;
  const int mesh = doc.addMesh(test::unitCube());
  const int parent = doc.addNode({{"name", "parent"}, {"translation", {0.0, 5.0, 0.0}}});
  const int child = doc.addNode(
      {{"name", "mirrored"},
       {"mesh", mesh},
       {"matrix", {1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0}}});
  doc.addChild(parent, child);
  doc.addRoot(parent);
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "mirror", BufferStorage::Glb));

  const Part& part = onlyPart(scene);
  EXPECT_EQ(part.mesh.positionsWorld[6], glm::vec3(1, 6, -1));
  EXPECT_DOUBLE_EQ(signedVolume(part.mesh), 1.0);
  EXPECT_TRUE(part.topology.consistentlyOriented());
}

TEST(GltfLoader, TwoMirrorsCancelAndKeepOutwardOrientation) {
  GltfDoc doc;
  const int mesh = doc.addMesh(test::unitCube());
  const int parent = doc.addNode({{"name", "parent"}, {"scale", {-1.0, 1.0, 1.0}}});
  const int child = doc.addNode({{"name", "child"}, {"mesh", mesh}, {"scale", {1.0, -1.0, 1.0}}});
  doc.addChild(parent, child);
  doc.addRoot(parent);
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "mirror2", BufferStorage::Glb));

  const Part& part = onlyPart(scene);
  EXPECT_EQ(part.mesh.positionsWorld[6], glm::vec3(-1, -1, 1));
  EXPECT_DOUBLE_EQ(signedVolume(part.mesh), 1.0);
  EXPECT_EQ(part.mesh.triangles, triangles(test::unitCube().indices));  // no winding swap
}

// ---- names and colours ------------------------------------------------------

TEST(GltfLoader, NamesPartsAfterTheirNodes) {
  GltfDoc doc;
  doc.addMeshNode(doc.addMesh(test::unitCube()), "left wheel");
  doc.addMeshNode(doc.addMesh(test::tetrahedron()), "spoiler");
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "names", BufferStorage::Glb));

  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[0].parts.at(0).name, "left wheel");
  EXPECT_EQ(scene.objects[1].parts.at(0).name, "spoiler");
}

TEST(GltfLoader, NamesUnnamedNodeAfterItsIndex) {
  GltfDoc doc;
  doc.addNode({{"name", "unused"}});
  doc.addNode({{"name", "also unused"}});
  doc.addMeshNode(doc.addMesh(test::unitCube()), "");  // node 2, no name
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "unnamed", BufferStorage::Glb));

  const Part& part = onlyPart(scene);
  EXPECT_EQ(part.name, "node 2");
  EXPECT_EQ(scene.objects[0].name, "node 2");
}

TEST(GltfLoader, TakesPartColourFromMaterialBaseColorFactor) {
  GltfDoc doc;
  const int red = doc.addMaterial({0.8f, 0.1f, 0.2f, 0.5f}, "red");
  doc.addMeshNode(doc.addMesh(test::unitCube(), red), "cube");
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "color", BufferStorage::Glb));

  EXPECT_EQ(onlyPart(scene).baseColor, glm::vec4(0.8f, 0.1f, 0.2f, 0.5f));
}

TEST(GltfLoader, PartWithoutMaterialIsWhite) {
  GltfDoc doc;
  doc.addMaterial({0.8f, 0.1f, 0.2f, 1.0f}, "unused red");
  doc.addMeshNode(doc.addMesh(test::unitCube()), "cube");
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "white", BufferStorage::Glb));

  EXPECT_EQ(onlyPart(scene).baseColor, glm::vec4(1.0f));
}

// ---- Voxhap extras and logical objects -------------------------------------

TEST(GltfLoader, ReadsVoxhapExtras) {
  GltfDoc doc;
  const int node = doc.addMeshNode(doc.addMesh(test::unitCube()), "cube node");
  doc.node(node)["extras"] = test::voxhapExtras({{"role", "dynamic"},
                                                 {"object", "x"},
                                                 {"density", 7800},
                                                 {"point_offset", -0.0005},
                                                 {"force_layer", 5}});
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "extras", BufferStorage::Glb));

  ASSERT_EQ(scene.objects.size(), 1u);
  const SceneObject& object = scene.objects[0];
  EXPECT_EQ(object.name, "x");
  EXPECT_EQ(object.settings.role, ObjectRole::Dynamic);
  ASSERT_TRUE(object.settings.densityKgPerM3.has_value());
  EXPECT_DOUBLE_EQ(*object.settings.densityKgPerM3, 7800.0);
  EXPECT_EQ(object.settings.pointOffsetM, -0.0005);
  EXPECT_EQ(object.settings.forceLayer, std::uint8_t{5});
  EXPECT_EQ(object.parts.at(0).name, "cube node");
  EXPECT_EQ(scene.triangleCount(ObjectRole::Dynamic), 12u);
  EXPECT_EQ(scene.triangleCount(ObjectRole::Static), 0u);
  EXPECT_EQ(scene.find("x"), &object);
  EXPECT_TRUE(scene.warnings.empty()) << joined(scene.warnings);
}

TEST(GltfLoader, MergesNodesNamingTheSameObjectKeepingPartColours) {
  GltfDoc doc;
  const int red = doc.addMaterial({1, 0, 0, 1});
  const int blue = doc.addMaterial({0, 0, 1, 1});
  const int a = doc.addMeshNode(doc.addMesh(test::unitCube(), red), "arm upper");
  const int b = doc.addMeshNode(doc.addMesh(test::tetrahedron(), blue), "arm lower");
  doc.addMeshNode(doc.addMesh(test::tetrahedron()), "table");
  doc.node(a)["extras"] = test::voxhapExtras({{"role", "dynamic"}, {"object", "arm"}});
  doc.node(b)["extras"] = test::voxhapExtras({{"role", "dynamic"}, {"object", "arm"}});
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "merge", BufferStorage::Glb));

  ASSERT_EQ(scene.objects.size(), 2u);
  const SceneObject* arm = scene.find("arm");
  ASSERT_NE(arm, nullptr);
  EXPECT_EQ(arm->settings.role, ObjectRole::Dynamic);
  ASSERT_EQ(arm->parts.size(), 2u);
  EXPECT_EQ(arm->parts[0].name, "arm upper");
  EXPECT_EQ(arm->parts[0].baseColor, glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(arm->parts[1].name, "arm lower");
  EXPECT_EQ(arm->parts[1].baseColor, glm::vec4(0, 0, 1, 1));
  EXPECT_EQ(arm->triangleCount(), 16u);
  ASSERT_NE(scene.find("table"), nullptr);
  EXPECT_EQ(scene.find("table")->settings.role, ObjectRole::Static);
}

TEST(GltfLoader, ChildrenInheritTheirAncestorsVoxhapSettings) {
  // robot (settings, no mesh) → body (mesh) → wrist (no mesh) → finger (mesh)
  GltfDoc doc;
  const int robot = doc.addNode(
      {{"name", "robot"}, {"extras", test::voxhapExtras({{"role", "dynamic"}, {"density", 2700}})}});
  const int body = doc.addNode({{"name", "body"}, {"mesh", doc.addMesh(test::unitCube())}});
  const int wrist = doc.addNode({{"name", "wrist"}, {"translation", {0.0, 0.0, 3.0}}});
  const int finger = doc.addNode({{"name", "finger"}, {"mesh", doc.addMesh(test::tetrahedron())}});
  doc.addChild(robot, body);
  doc.addChild(body, wrist);
  doc.addChild(wrist, finger);
  doc.addRoot(robot);
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "inherit", BufferStorage::Glb));

  ASSERT_EQ(scene.objects.size(), 1u);
  const SceneObject& object = scene.objects[0];
  EXPECT_EQ(object.name, "robot");
  EXPECT_EQ(object.settings.role, ObjectRole::Dynamic);
  EXPECT_EQ(object.settings.densityKgPerM3, 2700.0);
  ASSERT_EQ(object.parts.size(), 2u);
  EXPECT_EQ(object.parts[0].name, "body");
  EXPECT_EQ(object.parts[1].name, "finger");
  EXPECT_EQ(object.parts[1].mesh.positionsWorld[0], glm::vec3(0, 0, 3));
}

TEST(GltfLoader, NearestAncestorWithSettingsWins) {
  GltfDoc doc;
  const int robot = doc.addNode(
      {{"name", "robot"}, {"extras", test::voxhapExtras({{"role", "dynamic"}, {"object", "robot"}})}});
  const int body = doc.addNode({{"name", "body"}, {"mesh", doc.addMesh(test::unitCube())}});
  const int tool = doc.addNode({{"name", "tool"},
                                {"mesh", doc.addMesh(test::tetrahedron())},
                                {"extras", test::voxhapExtras({{"role", "static"}, {"object", "tool"}})}});
  doc.addChild(robot, body);
  doc.addChild(robot, tool);
  doc.addRoot(robot);
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "nearest", BufferStorage::Glb));

  ASSERT_EQ(scene.objects.size(), 2u);
  ASSERT_NE(scene.find("robot"), nullptr);
  ASSERT_NE(scene.find("tool"), nullptr);
  EXPECT_EQ(scene.find("robot")->settings.role, ObjectRole::Dynamic);
  EXPECT_EQ(scene.find("robot")->parts.at(0).name, "body");
  EXPECT_EQ(scene.find("tool")->settings.role, ObjectRole::Static);
  EXPECT_EQ(scene.find("tool")->parts.at(0).name, "tool");
}

TEST(GltfLoader, WithoutExtrasEveryMeshNodeIsAStaticObjectNamedAfterIt) {
  GltfDoc doc;
  const int floor = doc.addMeshNode(doc.addMesh(test::unitCube()), "floor");
  const int lamp = doc.addNode({{"name", "lamp"}, {"mesh", doc.addMesh(test::tetrahedron())}});
  doc.addChild(floor, lamp);  // a child with a mesh is an object of its own too
  doc.addMeshNode(doc.addMesh(test::tetrahedron()), "chair");
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "plain", BufferStorage::Glb));

  ASSERT_EQ(scene.objects.size(), 3u);
  for (const char* name : {"floor", "lamp", "chair"}) {
    const SceneObject* object = scene.find(name);
    ASSERT_NE(object, nullptr) << name;
    EXPECT_EQ(object->settings.role, ObjectRole::Static) << name;
    EXPECT_FALSE(object->settings.densityKgPerM3.has_value()) << name;
    ASSERT_EQ(object->parts.size(), 1u) << name;
    EXPECT_EQ(object->parts[0].name, name);
  }
  EXPECT_EQ(scene.triangleCount(ObjectRole::Static), 20u);
  EXPECT_TRUE(scene.warnings.empty()) << joined(scene.warnings);
}

TEST(GltfLoader, NumbersDuplicateObjectNamesWithAWarning) {
  GltfDoc doc;
  doc.addMeshNode(doc.addMesh(test::unitCube()), "box");
  doc.addMeshNode(doc.addMesh(test::tetrahedron()), "box");
  doc.addMeshNode(doc.addMesh(test::tetrahedron()), "box");
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "dupes", BufferStorage::Glb));

  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_EQ(scene.objects[0].name, "box");
  EXPECT_EQ(scene.objects[1].name, "box (2)");
  EXPECT_EQ(scene.objects[2].name, "box (3)");
  EXPECT_EQ(scene.objects[0].triangleCount(), 12u);
  const std::vector<std::string> warnings = warningsWith(scene, "numbered");
  ASSERT_EQ(warnings.size(), 1u) << joined(scene.warnings);
  EXPECT_TRUE(contains(warnings[0], "'box (2)', 'box (3)'")) << warnings[0];
}

// ---- groups: nodes without mesh or extras that hold parts ------------------

TEST(GltfLoader, ANodeWithoutMeshOrExtrasHoldingPartsIsAGroup) {
  TempDir dir;
  const Scene scene =
      loadGltfScene(test::writeDoc(test::pistonAssemblyDoc(), dir.path(), "piston", BufferStorage::Glb));

  ASSERT_EQ(scene.objects.size(), 3u);  // every mesh node is still an object of its own
  EXPECT_EQ(scene.objects[0].name, "crown");
  EXPECT_EQ(scene.objects[1].name, "pin");
  EXPECT_EQ(scene.objects[2].name, "block");
  for (const SceneObject& object : scene.objects) EXPECT_FALSE(object.namedByExtras) << object.name;
  ASSERT_EQ(scene.groups.size(), 1u);
  EXPECT_EQ(scene.groups[0].name, "piston");
  EXPECT_EQ(scene.groups[0].objects, (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(scene.findGroup("piston"), &scene.groups[0]);
  EXPECT_EQ(scene.findGroup("crown"), nullptr);
  EXPECT_EQ(scene.find("piston"), nullptr);
  EXPECT_TRUE(scene.warnings.empty()) << joined(scene.warnings);
}

TEST(GltfLoader, NestedGroupsAreListedParentFirstAndEmptyOnesAreNot) {
  // engine → (piston → crown, pin), rod; a lone "empty" node holds nothing
  GltfDoc doc = test::pistonAssemblyDoc();
  const int engine = doc.addNode({{"name", "engine"}});
  const int piston = doc.nodeNamed("piston");
  doc.json["scenes"][0]["nodes"] = nlohmann::json::array({engine, doc.nodeNamed("block")});
  doc.addChild(engine, piston);
  doc.addChild(engine, doc.addNode({{"name", "rod"}, {"mesh", doc.addMesh(test::tetrahedron())}}));
  doc.addRoot(doc.addNode({{"name", "empty"}}));
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "engine", BufferStorage::Glb));

  ASSERT_EQ(scene.groups.size(), 2u);
  EXPECT_EQ(scene.groups[0].name, "engine");
  EXPECT_EQ(scene.groups[1].name, "piston");
  const std::size_t crown = static_cast<std::size_t>(scene.find("crown") - scene.objects.data());
  const std::size_t pin = static_cast<std::size_t>(scene.find("pin") - scene.objects.data());
  const std::size_t rod = static_cast<std::size_t>(scene.find("rod") - scene.objects.data());
  EXPECT_EQ(scene.groups[0].objects, (std::vector<std::size_t>{crown, pin, rod}));
  EXPECT_EQ(scene.groups[1].objects, (std::vector<std::size_t>{crown, pin}));
  EXPECT_EQ(scene.findGroup("empty"), nullptr);
}

TEST(GltfLoader, NodesInsideAnObjectNamedByExtrasAreNoGroups) {
  // robot (extras) → wrist (no mesh) → finger: the wrist is part of the robot
  GltfDoc doc;
  const int robot = doc.addNode({{"name", "robot"}, {"extras", test::voxhapExtras({{"role", "dynamic"}})}});
  const int wrist = doc.addNode({{"name", "wrist"}});
  doc.addChild(robot, wrist);
  doc.addChild(wrist, doc.addNode({{"name", "finger"}, {"mesh", doc.addMesh(test::tetrahedron())}}));
  doc.addRoot(robot);
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "robot", BufferStorage::Glb));

  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_TRUE(scene.objects[0].namedByExtras);
  EXPECT_TRUE(scene.groups.empty());
}

TEST(GltfLoader, AGroupNamedLikeAnObjectIsNumberedWithAWarning) {
  GltfDoc doc = test::pistonAssemblyDoc();
  doc.node(doc.nodeNamed("piston"))["name"] = "block";
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "clash", BufferStorage::Glb));

  ASSERT_NE(scene.find("block"), nullptr);  // the object keeps its name
  ASSERT_EQ(scene.groups.size(), 1u);
  EXPECT_EQ(scene.groups[0].name, "block (2)");
  const std::vector<std::string> warnings = warningsWith(scene, "groups share a name");
  ASSERT_EQ(warnings.size(), 1u) << joined(scene.warnings);
  EXPECT_TRUE(contains(warnings[0], "'block (2)'")) << warnings[0];
}

// ---- topology ---------------------------------------------------------------

TEST(GltfLoader, CubeIsClosedAndConsistentlyOriented) {
  TempDir dir;
  const Scene scene = loadGltfScene(
      test::writeDoc(test::singleMeshDoc(test::unitCube(), "cube"), dir.path(), "cube", BufferStorage::Glb));

  const SceneObject& object = scene.objects.at(0);
  EXPECT_TRUE(object.closed());
  EXPECT_TRUE(object.consistentlyOriented());
  EXPECT_EQ(object.parts.at(0).topology.boundaryEdges, 0u);
  EXPECT_EQ(object.parts.at(0).topology.nonManifoldEdges, 0u);
  EXPECT_EQ(object.parts.at(0).topology.misorientedEdges, 0u);
  EXPECT_TRUE(warningsWith(scene, "open").empty()) << joined(scene.warnings);
}

TEST(GltfLoader, CubeMissingATriangleIsOpenWithAWarningNamingObjectPartAndPlace) {
  MeshData cube = test::unitCube();
  cube.indices.erase(cube.indices.begin(), cube.indices.begin() + 3);  // triangle 0 3 2, at z = 0
  GltfDoc doc;
  const int node = doc.addMeshNode(doc.addMesh(cube), "lid part");
  doc.node(node)["extras"] = test::voxhapExtras({{"object", "crate"}});
  TempDir dir;
  const fs::path file = test::writeDoc(doc, dir.path(), "open", BufferStorage::Glb);
  const Scene scene = loadGltfScene(file);

  const Part& part = onlyPart(scene);
  EXPECT_FALSE(scene.objects[0].closed());
  EXPECT_FALSE(part.topology.closed());
  EXPECT_EQ(part.topology.boundaryEdges, 3u);
  EXPECT_EQ(part.topology.nonManifoldEdges, 0u);
  EXPECT_TRUE(part.topology.consistentlyOriented());
  // the open edge reported is one of the removed triangle's
  ASSERT_TRUE(part.topology.firstOpenEdgeWorld.has_value());
  const glm::vec3 at = *part.topology.firstOpenEdgeWorld;
  const std::vector<glm::vec3> midpoints = {{0, 0.5f, 0}, {0.5f, 1, 0}, {0.5f, 0.5f, 0}};
  EXPECT_NE(std::find(midpoints.begin(), midpoints.end(), at), midpoints.end()) << testing::PrintToString(at);

  const std::vector<std::string> warnings = warningsWith(scene, "open");
  ASSERT_EQ(warnings.size(), 1u) << joined(scene.warnings);
  const std::string& w = warnings[0];
  EXPECT_TRUE(contains(w, file.string())) << w;
  EXPECT_TRUE(contains(w, "'crate'")) << w;
  EXPECT_TRUE(contains(w, "'lid part'")) << w;
  EXPECT_TRUE(contains(w, "3 boundary")) << w;
  EXPECT_TRUE(contains(w, "near (")) << w;
  EXPECT_EQ(w.find('\n'), std::string::npos) << w;
}

TEST(GltfLoader, FlippedTriangleIsNotConsistentlyOriented) {
  MeshData cube = test::unitCube();
  std::swap(cube.indices[13], cube.indices[14]);  // triangle 4 (y = 0) turned inside out
  GltfDoc doc;
  doc.addMeshNode(doc.addMesh(cube), "cube");
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "flipped", BufferStorage::Glb));

  const Part& part = onlyPart(scene);
  EXPECT_TRUE(part.topology.closed());
  EXPECT_FALSE(part.topology.consistentlyOriented());
  EXPECT_EQ(part.topology.misorientedEdges, 3u);
  EXPECT_FALSE(scene.objects[0].consistentlyOriented());
  const std::vector<std::string> warnings = warningsWith(scene, "not consistently oriented");
  ASSERT_EQ(warnings.size(), 1u) << joined(scene.warnings);
  EXPECT_TRUE(contains(warnings[0], "'cube'")) << warnings[0];
}

// ---- progress ---------------------------------------------------------------

TEST(GltfLoader, ReportsProgressRisingToOne) {
  GltfDoc doc;
  for (int i = 0; i < 4; ++i) doc.addMeshNode(doc.addMesh(test::tetrahedron()), test::numbered("t", i));
  TempDir dir;
  std::vector<double> reported;
  loadGltfScene(test::writeDoc(doc, dir.path(), "progress", BufferStorage::Glb),
                [&](double fraction) { reported.push_back(fraction); });
  ASSERT_FALSE(reported.empty());
  for (std::size_t i = 0; i < reported.size(); ++i) {
    EXPECT_GE(reported[i], 0.0);
    EXPECT_LE(reported[i], 1.0);
    if (i > 0) {
      EXPECT_GE(reported[i], reported[i - 1]);
    }
  }
  EXPECT_DOUBLE_EQ(reported.back(), 1.0);
}

TEST(GltfLoader, ReportsProgressUpToOneWhenSomeNodesAreOutsideTheScene) {
  GltfDoc doc = test::singleMeshDoc(test::unitCube(), "cube");
  for (int i = 0; i < 3; ++i) doc.addNode({{"name", test::numbered("spare ", i)}});  // in no scene
  TempDir dir;
  std::vector<double> reported;
  loadGltfScene(test::writeDoc(doc, dir.path(), "spare", BufferStorage::Glb),
                [&](double fraction) { reported.push_back(fraction); });
  ASSERT_FALSE(reported.empty());
  EXPECT_DOUBLE_EQ(reported.back(), 1.0);
}

// ---- what Voxhap ignores ----------------------------------------------------

TEST(GltfLoader, MissingTextureIsAWarningNotAnError) {
  GltfDoc doc = test::singleMeshDoc(test::unitCube(), "cube");
  doc.json["images"] = {{{"uri", "no_such_texture.png"}}};
  doc.json["textures"] = {{{"source", 0}}};
  doc.json["materials"] = {
      {{"pbrMetallicRoughness",
        {{"baseColorFactor", {0.5, 0.5, 0.5, 1.0}}, {"baseColorTexture", {{"index", 0}}}}}}};
  doc.json["meshes"][0]["primitives"][0]["material"] = 0;
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "textured", BufferStorage::Glb));

  EXPECT_EQ(scene.triangleCount(), 12u);
  EXPECT_EQ(onlyPart(scene).baseColor, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
  EXPECT_EQ(warningsWith(scene, "no_such_texture.png").size(), 1u) << joined(scene.warnings);
}

// ---- round trip through the writer -----------------------------------------

/// A scene with a two-part dynamic object (two colours, a density, a point offset, a
/// force layer, a transform),
/// a static object and an unnamed node.
GltfDoc richDoc() {
  GltfDoc doc;
  const int red = doc.addMaterial({0.9f, 0.1f, 0.1f, 1.0f});
  const int green = doc.addMaterial({0.1f, 0.8f, 0.2f, 0.75f});
  const int arm = doc.addNode({{"name", "arm"},
                               {"translation", {0.0, 1.0, 0.0}},
                               {"extras", test::voxhapExtras({{"role", "dynamic"},
                                                              {"object", "arm"},
                                                              {"density", 7800},
                                                              {"point_offset", -0.0002},
                                                              {"force_layer", 4}})}});
  const int upper = doc.addNode({{"name", "upper"}, {"mesh", doc.addMesh(test::unitCube(), red)}});
  const int lower = doc.addNode({{"name", "lower"},
                                 {"mesh", doc.addMesh(test::tetrahedron(), green)},
                                 {"translation", {0.0, 0.0, -2.0}},
                                 {"scale", {0.5, 0.5, 0.5}}});
  doc.addChild(arm, upper);
  doc.addChild(arm, lower);
  doc.addRoot(arm);
  doc.addMeshNode(doc.addMesh(test::unitCube()), "table");
  doc.addMeshNode(doc.addMesh(test::tetrahedron()), "");
  return doc;
}

void expectSameScene(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (std::size_t o = 0; o < a.objects.size(); ++o) {
    const SceneObject& x = a.objects[o];
    const SceneObject& y = b.objects[o];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.settings.role, y.settings.role) << x.name;
    EXPECT_EQ(x.settings.densityKgPerM3, y.settings.densityKgPerM3) << x.name;
    EXPECT_EQ(x.settings.pointOffsetM, y.settings.pointOffsetM) << x.name;
    EXPECT_EQ(x.settings.forceLayer, y.settings.forceLayer) << x.name;
    ASSERT_EQ(x.parts.size(), y.parts.size()) << x.name;
    for (std::size_t p = 0; p < x.parts.size(); ++p) {
      EXPECT_EQ(x.parts[p].name, y.parts[p].name) << x.name;
      EXPECT_EQ(x.parts[p].baseColor, y.parts[p].baseColor) << x.parts[p].name;
      EXPECT_EQ(x.parts[p].mesh.positionsWorld, y.parts[p].mesh.positionsWorld) << x.parts[p].name;
      EXPECT_EQ(x.parts[p].mesh.triangles, y.parts[p].mesh.triangles) << x.parts[p].name;
    }
  }
}

TEST(GltfLoader, RoundTripsThroughWriteGlb) {
  TempDir dir;
  const Scene original = loadGltfScene(test::writeDoc(richDoc(), dir.path(), "rich", BufferStorage::DataUri));
  ASSERT_EQ(original.objects.size(), 3u);  // arm, table, node 4
  ASSERT_EQ(original.objects[0].parts.size(), 2u);
  EXPECT_TRUE(original.warnings.empty()) << joined(original.warnings);

  const fs::path written = dir / "written.glb";
  writeGlbFile(original, written);
  const Scene reloaded = loadGltfScene(written);
  EXPECT_TRUE(reloaded.warnings.empty()) << joined(reloaded.warnings);
  expectSameScene(original, reloaded);
  EXPECT_EQ(reloaded.objects[0].name, "arm");
  EXPECT_EQ(reloaded.objects[0].settings.role, ObjectRole::Dynamic);
  EXPECT_EQ(reloaded.objects[0].settings.densityKgPerM3, 7800.0);
  EXPECT_EQ(reloaded.objects[0].settings.forceLayer, std::uint8_t{4});
  EXPECT_EQ(reloaded.objects[0].parts[1].baseColor, glm::vec4(0.1f, 0.8f, 0.2f, 0.75f));
  EXPECT_EQ(reloaded.objects[2].name, "node 4");
}

TEST(GltfLoader, RoundTripKeepsNumberedDuplicateNamesDistinct) {
  GltfDoc doc;
  doc.addMeshNode(doc.addMesh(test::unitCube()), "box");
  doc.addMeshNode(doc.addMesh(test::tetrahedron()), "box");
  TempDir dir;
  const Scene original = loadGltfScene(test::writeDoc(doc, dir.path(), "dupes", BufferStorage::Glb));
  const fs::path written = dir / "written.glb";
  writeGlbFile(original, written);
  const Scene reloaded = loadGltfScene(written);
  expectSameScene(original, reloaded);
  EXPECT_TRUE(reloaded.warnings.empty()) << joined(reloaded.warnings);
}

TEST(GltfLoader, WriteGlbIsByteIdenticalOnTwoCalls) {
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(richDoc(), dir.path(), "rich", BufferStorage::Glb));
  const std::vector<unsigned char> first = writeGlb(scene);
  const std::vector<unsigned char> second = writeGlb(scene);
  ASSERT_GT(first.size(), 20u);
  EXPECT_EQ(std::memcmp(first.data(), "glTF", 4), 0);
  EXPECT_EQ(first, second);
  // and what was written is what writeGlbFile puts on disk
  writeGlbFile(scene, dir / "out.glb");
  EXPECT_EQ(test::readBytes(dir / "out.glb"), first);
}

TEST(GltfLoader, WriteGlbProducesAWellFormedContainer) {
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(richDoc(), dir.path(), "rich", BufferStorage::Glb));
  const std::vector<unsigned char> glb = writeGlb(scene);
  ASSERT_GE(glb.size(), 28u);
  EXPECT_EQ(test::getU32(glb, 4), 2u);                                            // version
  EXPECT_EQ(test::getU32(glb, test::GlbLayout::kTotalLengthOffset), glb.size());  // honest length
  const std::uint32_t jsonLength = test::getU32(glb, test::GlbLayout::kJsonChunkLengthOffset);
  EXPECT_EQ(jsonLength % 4, 0u);
  EXPECT_EQ(test::getU32(glb, 16), 0x4E4F534Au);  // "JSON"
  const test::GlbLayout layout = test::glbLayout(glb);
  ASSERT_NE(layout.binChunkLengthOffset, 0u);
  const std::uint32_t binLength = test::getU32(glb, layout.binChunkLengthOffset);
  EXPECT_EQ(binLength % 4, 0u);
  EXPECT_EQ(test::getU32(glb, layout.binChunkLengthOffset + 4), 0x004E4942u);  // "BIN\0"
  EXPECT_EQ(layout.binChunkDataOffset + binLength, glb.size());
  // and the JSON parses, names the generator and has the objects as root nodes
  const std::string jsonText(glb.begin() + test::GlbLayout::kJsonChunkDataOffset,
                             glb.begin() + test::GlbLayout::kJsonChunkDataOffset + jsonLength);
  const nlohmann::json json = nlohmann::json::parse(jsonText);
  EXPECT_EQ(json.at("asset").at("version"), "2.0");
  EXPECT_EQ(json.at("scenes").at(0).at("nodes").size(), scene.objects.size());
}

}  // namespace
}  // namespace voxhap

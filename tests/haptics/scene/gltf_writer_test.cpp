#include "haptics/scene/gltf_writer.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "haptics/scene/gltf_loader.h"

namespace voxhap {
namespace {

namespace fs = std::filesystem;

Scene tetrahedronScene() {
  TriangleMesh mesh;
  mesh.positionsWorld = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  Scene scene;
  scene.sourceName = "tetrahedron";
  SceneObject object{"tet", {ObjectRole::Dynamic, 2700.0, -0.0005, 6}, {}};
  object.parts.push_back(makePart("tet", glm::vec4(0.5f, 0.25f, 1.0f, 1.0f), mesh));
  scene.objects.push_back(object);
  return scene;
}

TEST(GltfWriter, WritesAtomicallyAndLeavesNoPartialFile) {
  const fs::path dir = fs::temp_directory_path() / ("voxhap-writer-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "tet.glb";
  writeGlbFile(tetrahedronScene(), file);
  EXPECT_TRUE(fs::exists(file));
  EXPECT_FALSE(fs::exists(dir / "tet.glb.partial"));
  const Scene back = loadGltfScene(file);
  ASSERT_EQ(back.objects.size(), 1u);
  EXPECT_EQ(back.objects[0].settings.role, ObjectRole::Dynamic);
  EXPECT_EQ(back.objects[0].settings.densityKgPerM3, 2700.0);
  EXPECT_EQ(back.objects[0].settings.pointOffsetM, -0.0005);
  EXPECT_EQ(back.objects[0].settings.forceLayer, std::uint8_t{6});
  EXPECT_EQ(back.objects[0].parts[0].baseColor, glm::vec4(0.5f, 0.25f, 1.0f, 1.0f));
  fs::remove_all(dir);
}

TEST(GltfWriter, UnwritablePlaceIsAClearError) {
  const fs::path file = fs::temp_directory_path() / "voxhap-no-such-dir" / "x" / "tet.glb";
  try {
    writeGlbFile(tetrahedronScene(), file);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(file.parent_path()));
}

}  // namespace
}  // namespace voxhap

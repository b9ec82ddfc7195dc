// Picking the objects to move: an object by its name, or a group of a CAD file whose
// objects merge into one; and the clear refusals.
#include "haptics/scene/object_selection.h"

#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "haptics/scene/gltf_loader.h"
#include "support/gltf_fixtures.h"

namespace voxhap {
namespace {

using test::BufferStorage;
using test::GltfDoc;

class SceneObjectSelection : public ::testing::Test {
protected:
  Scene load(const GltfDoc& doc) {
    return loadGltfScene(test::writeDoc(doc, dir_.path(), "piston", BufferStorage::Glb));
  }

  /// The message selectObjects throws for `names`, or "" when it picks them.
  std::string refusal(const Scene& scene, const std::vector<std::string>& names) {
    try {
      selectObjects(scene, names);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }

  test::TempDir dir_;
};

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST_F(SceneObjectSelection, AGroupMergesItsObjectsIntoOneKeepingPartColours) {
  const Scene scene = load(test::pistonAssemblyDoc());
  const std::vector<std::string> names = {"piston"};
  const ObjectSelection s = selectObjects(scene, names);

  ASSERT_EQ(s.picked.size(), 1u);
  const SceneObject& piston = *s.picked[0];
  EXPECT_EQ(piston.name, "piston");
  EXPECT_EQ(piston.settings.role, ObjectRole::Dynamic);
  EXPECT_FALSE(piston.settings.densityKgPerM3.has_value());  // the default density
  ASSERT_EQ(piston.parts.size(), 2u);
  EXPECT_EQ(piston.parts[0].name, "crown");
  EXPECT_EQ(piston.parts[0].baseColor, glm::vec4(0.8f, 0.1f, 0.1f, 1.0f));
  EXPECT_EQ(piston.parts[1].name, "pin");
  EXPECT_EQ(piston.parts[1].baseColor, glm::vec4(0.1f, 0.2f, 0.9f, 1.0f));
  EXPECT_EQ(piston.triangleCount(),
            scene.find("crown")->triangleCount() + scene.find("pin")->triangleCount());
  ASSERT_EQ(s.rest.size(), 1u);
  EXPECT_EQ(s.rest[0], scene.find("block"));
}

TEST_F(SceneObjectSelection, AnObjectNameStillPicksThatObjectAlone) {
  const Scene scene = load(test::pistonAssemblyDoc());
  const std::vector<std::string> names = {"pin", "block"};
  const ObjectSelection s = selectObjects(scene, names);

  EXPECT_EQ(s.picked, (std::vector<const SceneObject*>{scene.find("pin"), scene.find("block")}));
  EXPECT_EQ(s.rest, (std::vector<const SceneObject*>{scene.find("crown")}));
  EXPECT_TRUE(s.merged.empty());
}

TEST_F(SceneObjectSelection, AnUnknownNameListsTheObjectsAndGroupsThatCanMove) {
  const Scene scene = load(test::pistonAssemblyDoc());
  const std::string message = refusal(scene, {"wrench"});
  EXPECT_TRUE(contains(message, "no object or group named 'wrench'")) << message;
  EXPECT_TRUE(contains(message, "objects: crown, pin, block; groups: piston (crown, pin)")) << message;
}

TEST_F(SceneObjectSelection, NamesThatHoldTheSameObjectAreRefused) {
  GltfDoc doc = test::pistonAssemblyDoc();
  const int engine = doc.addNode({{"name", "engine"}});
  doc.json["scenes"][0]["nodes"] = nlohmann::json::array({engine, doc.nodeNamed("block")});
  doc.addChild(engine, doc.nodeNamed("piston"));
  const Scene scene = load(doc);

  std::string message = refusal(scene, {"piston", "pin"});
  EXPECT_TRUE(contains(message, "'piston' and 'pin' both hold object 'pin'")) << message;
  message = refusal(scene, {"engine", "piston"});  // nested groups
  EXPECT_TRUE(contains(message, "'engine' and 'piston' both hold object 'crown'")) << message;
  message = refusal(scene, {"piston", "piston"});
  EXPECT_TRUE(contains(message, "'piston' is moved twice")) << message;
  EXPECT_EQ(refusal(scene, {"piston", "block"}), "");
}

TEST_F(SceneObjectSelection, AGroupHoldingAnObjectNamedByExtrasIsRefused) {
  GltfDoc doc = test::pistonAssemblyDoc();
  doc.node(doc.nodeNamed("crown"))["extras"] =
      test::voxhapExtras({{"object", "crown head"}, {"density", 2700}});
  const Scene scene = load(doc);
  ASSERT_NE(scene.findGroup("piston"), nullptr);  // still a group of the file

  const std::string message = refusal(scene, {"piston"});
  EXPECT_TRUE(contains(message, "group 'piston' holds object 'crown head'")) << message;
  EXPECT_TRUE(contains(message, "move 'crown head', or put the extras on node 'piston'")) << message;
  EXPECT_FALSE(groupMoveProblem(scene, *scene.findGroup("piston")).empty());
  EXPECT_FALSE(contains(movableNames(scene), "groups")) << movableNames(scene);
  EXPECT_EQ(refusal(scene, {"crown head", "pin"}), "");  // its objects still move one by one
}

TEST_F(SceneObjectSelection, AGroupIsOneObjectWhereverTheNamesPutIt) {
  // a scene made in code: objects a, b, c and a group g of a and c, picked second
  Scene scene;
  scene.sourceName = "test";
  for (const char* name : {"a", "b", "c"}) {
    TriangleMesh mesh;
    mesh.positionsWorld = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.triangles = {{0, 1, 2}};
    scene.objects.push_back({name, {}, {makePart(name, glm::vec4(1.0f), mesh)}});
  }
  scene.groups.push_back({"g", {0, 2}});
  const std::vector<std::string> names = {"b", "g"};
  const ObjectSelection s = selectObjects(scene, names);
  ASSERT_EQ(s.picked.size(), 2u);
  EXPECT_EQ(s.picked[0], &scene.objects[1]);
  EXPECT_EQ(s.picked[1]->name, "g");
  EXPECT_EQ(s.picked[1]->parts.size(), 2u);
  EXPECT_TRUE(s.rest.empty());
}

}  // namespace
}  // namespace voxhap

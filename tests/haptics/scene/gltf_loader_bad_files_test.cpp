// glTF loader on bad files: every one throws voxhap::Error with one line that names
// the file and the problem, without crashing, hanging or allocating absurd amounts
// (the ASan build checks the last; a hang shows as the test's timeout).

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "haptics/core/error.h"
#include "haptics/scene/gltf_loader.h"
#include "tests/support/gltf_fixtures.h"

namespace voxhap {
namespace {

namespace fs = std::filesystem;
using test::BufferStorage;
using test::GlbLayout;
using test::GltfDoc;
using test::MeshData;
using test::TempDir;
using Json = nlohmann::json;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& line : lines) out += line + "\n";
  return out;
}

/// Loads `file` expecting voxhap::Error; checks that the message is one line, names
/// the file and contains every one of `parts`. Returns the message.
std::string expectLoadError(const fs::path& file, const std::vector<std::string>& parts) {
  std::string message;
  try {
    const Scene scene = loadGltfScene(file);
    ADD_FAILURE() << file << " loaded (" << scene.objects.size() << " objects); expected an error with '"
                  << (parts.empty() ? "" : parts[0]) << "'";
    return {};
  } catch (const Error& e) {
    message = e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << file << " threw something other than voxhap::Error: " << e.what();
    return {};
  }
  EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
  EXPECT_EQ(message.find('\r'), std::string::npos) << "not one line: " << message;
  EXPECT_TRUE(contains(message, file.string())) << "does not name the file: " << message;
  // look for the parts outside the file's path, which contains the test's name
  std::string rest = message;
  for (std::size_t at; (at = rest.find(file.string())) != std::string::npos;)
    rest.erase(at, file.string().size());
  for (const std::string& part : parts) {
    EXPECT_TRUE(contains(rest, part)) << "missing '" << part << "' in: " << message;
  }
  EXPECT_LT(message.size(), 1000u) << "absurdly long: " << message.substr(0, 300) << "…";
  return message;
}

/// A cube in the given storage with a JSON mutation, written to `dir`.
fs::path cubeFile(const TempDir& dir, BufferStorage storage, const test::JsonMutator& mutate = {},
                  const std::string& stem = "bad") {
  return test::writeDoc(test::singleMeshDoc(test::unitCube(), "cube"), dir.path(), stem, storage, mutate);
}

/// The GLB bytes of a valid cube file.
std::vector<unsigned char> cubeGlb() {
  const GltfDoc doc = test::singleMeshDoc(test::unitCube(), "cube");
  return test::packGlb(test::finishedJson(doc, BufferStorage::Glb).dump(), doc.bin);
}

std::vector<unsigned char> randomBytes(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<unsigned char> out(n);
  for (unsigned char& b : out) b = static_cast<unsigned char>(rng() & 0xFF);
  return out;
}

// ---- not a readable file ----------------------------------------------------

TEST(GltfLoaderBadFiles, MissingFile) {
  TempDir dir;
  expectLoadError(dir / "nothing_here.gltf", {"no such file"});
}

TEST(GltfLoaderBadFiles, DirectoryInsteadOfAFile) {
  TempDir dir;
  fs::create_directories(dir / "folder.glb");
  expectLoadError(dir / "folder.glb", {"not a regular file"});
}

TEST(GltfLoaderBadFiles, FifoInsteadOfAFile) {
  TempDir dir;
  ASSERT_EQ(::mkfifo((dir / "pipe.glb").c_str(), 0600), 0);
  expectLoadError(dir / "pipe.glb", {"not a regular file"});  // and no hang waiting for a writer
}

TEST(GltfLoaderBadFiles, EmptyFile) {
  TempDir dir;
  test::writeText(dir / "blank.gltf", "");
  expectLoadError(dir / "blank.gltf", {"is empty"});
}

// ---- not glTF at all --------------------------------------------------------

TEST(GltfLoaderBadFiles, RandomText) {
  TempDir dir;
  test::writeText(dir / "notes.gltf", "Lorem ipsum dolor sit amet,\nconsectetur adipiscing elit.\n");
  expectLoadError(dir / "notes.gltf", {"not a glTF file"});
}

TEST(GltfLoaderBadFiles, PngHeader) {
  TempDir dir;
  std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n',
                                    0,    0,   0,   13,  'I',  'H',  'D',  'R'};
  const std::vector<unsigned char> rest = randomBytes(200, 1);
  png.insert(png.end(), rest.begin(), rest.end());
  test::writeBytes(dir / "texture.glb", png);
  expectLoadError(dir / "texture.glb", {"not a glTF file"});
}

TEST(GltfLoaderBadFiles, RandomBinary) {
  TempDir dir;
  std::vector<unsigned char> bytes = randomBytes(4096, 2);
  bytes[0] = 0x00;  // make sure it starts neither with "glTF" nor with '{'
  test::writeBytes(dir / "noise.glb", bytes);
  expectLoadError(dir / "noise.glb", {"not a glTF file"});
}

TEST(GltfLoaderBadFiles, InvalidJson) {
  TempDir dir;
  test::writeText(dir / "broken.gltf", R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 0,)");
  expectLoadError(dir / "broken.gltf", {"not valid glTF", "parse error", "column 52"});
}

TEST(GltfLoaderBadFiles, JsonThatIsNotGltf) {
  TempDir dir;
  test::writeText(dir / "package.gltf", R"({"name": "left-pad", "version": "1.3.0"})");
  expectLoadError(dir / "package.gltf", {"not valid glTF", "asset"});
}

TEST(GltfLoaderBadFiles, GlbWithInvalidJsonChunk) {
  TempDir dir;
  const GltfDoc doc = test::singleMeshDoc(test::unitCube(), "cube");
  test::writeBytes(dir / "broken.glb", test::packGlb(R"({"asset": {"version": "2.0"}, "nodes": [)", doc.bin));
  expectLoadError(dir / "broken.glb", {"not valid glTF binary", "parse error"});
}

/// `depth` nested arrays as the extras of the file's root object.
std::string deeplyNestedJson(std::size_t depth) {
  std::string text =
      test::finishedJson(test::singleMeshDoc(test::unitCube(), "cube"), BufferStorage::DataUri).dump();
  text.insert(text.size() - 1, ",\"extras\":" + std::string(depth, '[') + std::string(depth, ']'));
  return text;
}

TEST(GltfLoaderBadFiles, DeeplyNestedJson) {
  TempDir dir;
  test::writeText(dir / "deep.gltf", deeplyNestedJson(100000));
  expectLoadError(dir / "deep.gltf", {"JSON nested deeper than 256 levels"});
}

TEST(GltfLoaderBadFiles, DeeplyNestedJsonInGlb) {
  TempDir dir;
  const GltfDoc doc = test::singleMeshDoc(test::unitCube(), "cube");
  std::string text = test::finishedJson(doc, BufferStorage::Glb).dump();
  text.insert(text.size() - 1, ",\"extras\":" + std::string(100000, '{') + std::string(100000, '}'));
  test::writeBytes(dir / "deep.glb", test::packGlb(text, doc.bin));
  expectLoadError(dir / "deep.glb", {"JSON nested deeper than 256 levels"});
}

TEST(GltfLoaderBadFiles, JsonNestedToTheLimitLoads) {
  TempDir dir;
  test::writeText(dir / "deep.gltf", deeplyNestedJson(255));  // 256 levels with the root object
  EXPECT_EQ(loadGltfScene(dir / "deep.gltf").triangleCount(), 12u);
}

TEST(GltfLoaderBadFiles, BracketsInsideJsonStringsDoNotCountAsNesting) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::DataUri, [](Json& j) {
    j["nodes"][0]["extras"] = {{"note", std::string(5000, '[') + "\\\"" + std::string(5000, '{')}};
  });
  EXPECT_EQ(loadGltfScene(file).triangleCount(), 12u);
}

// ---- GLB container ----------------------------------------------------------

/// Writes the first `keep` bytes of a valid cube GLB and expects a truncation error.
void expectTruncatedGlb(std::size_t keep) {
  SCOPED_TRACE(test::numbered("kept bytes: ", keep));
  TempDir dir;
  std::vector<unsigned char> glb = cubeGlb();
  ASSERT_LT(keep, glb.size());
  glb.resize(keep);
  test::writeBytes(dir / "cut.glb", glb);
  expectLoadError(dir / "cut.glb", {"truncated"});
}

TEST(GltfLoaderBadFiles, GlbTruncatedInsideHeader) {
  for (std::size_t keep : {4u, 7u, 11u}) expectTruncatedGlb(keep);
}

TEST(GltfLoaderBadFiles, GlbTruncatedInsideJsonChunkHeader) {
  for (std::size_t keep : {12u, 16u, 19u}) expectTruncatedGlb(keep);
}

TEST(GltfLoaderBadFiles, GlbTruncatedInsideJsonChunk) {
  for (std::size_t keep : {20u, 21u, 60u}) expectTruncatedGlb(keep);
}

TEST(GltfLoaderBadFiles, GlbTruncatedInsideBinChunk) {
  const std::vector<unsigned char> glb = cubeGlb();
  const GlbLayout layout = test::glbLayout(glb);
  ASSERT_GT(layout.binChunkDataOffset, 0u);
  for (std::size_t keep : {layout.binChunkLengthOffset + 4, layout.binChunkDataOffset + 1, glb.size() - 4}) {
    expectTruncatedGlb(keep);
  }
}

TEST(GltfLoaderBadFiles, GlbWithAbsurdTotalLength) {
  TempDir dir;
  std::vector<unsigned char> glb = cubeGlb();
  test::putU32(glb, GlbLayout::kTotalLengthOffset, 0xFFFFFFF0u);
  test::writeBytes(dir / "long.glb", glb);
  expectLoadError(dir / "long.glb", {"truncated", "4294967280"});
}

TEST(GltfLoaderBadFiles, GlbWithAbsurdJsonChunkLength) {
  TempDir dir;
  std::vector<unsigned char> glb = cubeGlb();
  test::putU32(glb, GlbLayout::kJsonChunkLengthOffset, 0xFFFFFFF0u);
  test::writeBytes(dir / "json.glb", glb);
  expectLoadError(dir / "json.glb", {"JSON chunk", "4294967280"});
}

TEST(GltfLoaderBadFiles, GlbWithAbsurdBinChunkLength) {
  TempDir dir;
  std::vector<unsigned char> glb = cubeGlb();
  test::putU32(glb, test::glbLayout(glb).binChunkLengthOffset, 0xFFFFFFF0u);
  test::writeBytes(dir / "bin.glb", glb);
  expectLoadError(dir / "bin.glb", {"BIN chunk", "4294967280"});
}

TEST(GltfLoaderBadFiles, GlbWithUnsupportedVersion) {
  TempDir dir;
  std::vector<unsigned char> glb = cubeGlb();
  test::putU32(glb, 4, 1);
  test::writeBytes(dir / "v1.glb", glb);
  expectLoadError(dir / "v1.glb", {"version 1"});
}

TEST(GltfLoaderBadFiles, GlbWithFirstChunkNotJson) {
  TempDir dir;
  std::vector<unsigned char> glb = cubeGlb();
  glb[16] = 'X';
  test::writeBytes(dir / "chunk.glb", glb);
  expectLoadError(dir / "chunk.glb", {"JSON"});
}

TEST(GltfLoaderBadFiles, GlbBufferLongerThanBinChunk) {
  TempDir dir;
  const fs::path file =
      cubeFile(dir, BufferStorage::Glb, [](Json& j) { j["buffers"][0]["byteLength"] = 100000; });
  expectLoadError(file, {"byteLength"});
}

// ---- buffers ----------------------------------------------------------------

TEST(GltfLoaderBadFiles, MissingExternalBuffer) {
  TempDir dir;
  const fs::path file =
      cubeFile(dir, BufferStorage::External, [](Json& j) { j["buffers"][0]["uri"] = "missing.bin"; });
  expectLoadError(file, {"missing.bin", "not found"});
}

TEST(GltfLoaderBadFiles, MissingExternalBufferIsNotTakenFromTheWorkingDirectory) {
  TempDir dir;
  fs::create_directories(dir / "models");
  const fs::path file = test::writeDoc(test::singleMeshDoc(test::unitCube(), "cube"), dir / "models", "scene",
                                       BufferStorage::External);
  fs::rename(dir / "models" / "scene.bin", dir / "scene.bin");  // now only in the working directory
  const fs::path before = fs::current_path();
  fs::current_path(dir.path());
  expectLoadError(file, {"scene.bin", "not found"});
  fs::current_path(before);
}

TEST(GltfLoaderBadFiles, ExternalBufferShorterThanByteLength) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::External);
  std::vector<unsigned char> bin = test::readBytes(dir / "bad.bin");
  bin.resize(bin.size() - 16);
  test::writeBytes(dir / "bad.bin", bin);
  expectLoadError(file, {"bad.bin", std::to_string(bin.size())});
}

TEST(GltfLoaderBadFiles, DataUriOfTheWrongLengthGivesAShortMessage) {
  // a megabyte of base64 must not end up in the message
  MeshData cube = test::unitCube();
  cube.positions.resize(60000, glm::vec3(0.5f));
  GltfDoc doc = test::singleMeshDoc(cube, "cube");
  TempDir dir;
  const fs::path file = test::writeDoc(doc, dir.path(), "bad", BufferStorage::DataUri, [](Json& j) {
    j["buffers"][0]["byteLength"] = j["buffers"][0]["byteLength"].get<std::size_t>() + 4;
  });
  ASSERT_GT(fs::file_size(file), 500000u);
  expectLoadError(file, {"Failed to decode 'uri'", "data:application/octet-stream;base64,"});
}

TEST(GltfLoaderBadFiles, BufferUriPointingAtDevZero) {
  if (!fs::is_character_file("/dev/zero")) GTEST_SKIP() << "no /dev/zero here";
  TempDir dir;
  fs::create_symlink("/dev/zero", dir / "zero.bin");
  const fs::path file =
      cubeFile(dir, BufferStorage::External, [](Json& j) { j["buffers"][0]["uri"] = "zero.bin"; });
  expectLoadError(file, {"zero.bin", "not a regular file"});
}

TEST(GltfLoaderBadFiles, BufferUriPointingAtDevZeroByRelativePath) {
  if (!fs::is_character_file("/dev/zero")) GTEST_SKIP() << "no /dev/zero here";
  TempDir dir;
  std::string up;
  for (auto it = dir.path().begin(); it != dir.path().end(); ++it) up += "../";
  const std::string uri = up + "dev/zero";
  const fs::path file =
      cubeFile(dir, BufferStorage::External, [&](Json& j) { j["buffers"][0]["uri"] = uri; });
  ASSERT_TRUE(fs::is_character_file(dir / uri));
  expectLoadError(file, {"dev/zero", "not a regular file"});
}

TEST(GltfLoaderBadFiles, BufferUriPointingAtADirectory) {
  TempDir dir;
  fs::create_directories(dir / "data.bin");
  const fs::path file =
      cubeFile(dir, BufferStorage::External, [](Json& j) { j["buffers"][0]["uri"] = "data.bin"; });
  expectLoadError(file, {"data.bin", "not a regular file"});
}

TEST(GltfLoaderBadFiles, BufferUriPointingAtAFifo) {
  TempDir dir;
  ASSERT_EQ(::mkfifo((dir / "pipe.bin").c_str(), 0600), 0);
  const fs::path file =
      cubeFile(dir, BufferStorage::External, [](Json& j) { j["buffers"][0]["uri"] = "pipe.bin"; });
  expectLoadError(file, {"pipe.bin", "not a regular file"});
}

TEST(GltfLoaderBadFiles, BufferViewBeyondBuffer) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::Glb, [](Json& j) {
    j["bufferViews"][1]["byteOffset"] = j["buffers"][0]["byteLength"].get<std::size_t>() - 8;
  });
  expectLoadError(file, {"indices accessor 1", "bufferView 1", "beyond buffer 0"});
}

// ---- accessors --------------------------------------------------------------

TEST(GltfLoaderBadFiles, AccessorCountOfFourBillion) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::Glb,
                                 [](Json& j) { j["accessors"][0]["count"] = std::uint64_t{4000000000}; });
  expectLoadError(file, {"POSITION accessor 0", "4000000000 elements", "do not fit"});
}

TEST(GltfLoaderBadFiles, AccessorCountOfTwoToTheSixty) {
  TempDir dir;
  const fs::path file =
      cubeFile(dir, BufferStorage::Glb, [](Json& j) { j["accessors"][1]["count"] = std::uint64_t{1} << 60; });
  expectLoadError(file, {"indices accessor 1", std::to_string(std::uint64_t{1} << 60), "do not fit"});
}

TEST(GltfLoaderBadFiles, AccessorCountOfMaxUint64) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::DataUri, [](Json& j) {
    j["accessors"][0]["count"] = std::numeric_limits<std::uint64_t>::max();
  });
  expectLoadError(file, {"POSITION accessor 0", "do not fit"});
}

TEST(GltfLoaderBadFiles, AccessorOneElementBeyondItsBufferView) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::Glb, [](Json& j) { j["accessors"][0]["count"] = 9; });
  expectLoadError(file, {"POSITION accessor 0", "9 elements", "do not fit"});
}

TEST(GltfLoaderBadFiles, AccessorOffsetBeyondItsBufferView) {
  TempDir dir;
  const fs::path file =
      cubeFile(dir, BufferStorage::Glb, [](Json& j) { j["accessors"][1]["byteOffset"] = 400; });
  expectLoadError(file, {"indices accessor 1", "offset 400", "do not fit"});
}

TEST(GltfLoaderBadFiles, AccessorWithoutBufferView) {
  TempDir dir;
  const fs::path file =
      cubeFile(dir, BufferStorage::Glb, [](Json& j) { j["accessors"][0].erase("bufferView"); });
  expectLoadError(file, {"POSITION accessor 0", "bufferView"});
}

TEST(GltfLoaderBadFiles, PrimitiveNamingMissingAccessor) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::Glb, [](Json& j) {
    j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9;
  });
  expectLoadError(file, {"'cube'", "accessor 9", "does not exist"});
}

TEST(GltfLoaderBadFiles, IndexOutOfRange) {
  MeshData cube = test::unitCube();
  cube.indices[17] = 8;  // the cube has vertices 0..7
  TempDir dir;
  const fs::path file =
      test::writeDoc(test::singleMeshDoc(cube, "cube"), dir.path(), "bad", BufferStorage::Glb);
  expectLoadError(file, {"'cube'", "indices accessor 1", "index 8", "position 17", "out of range"});
}

/// A cube file whose vertex 3 has `value` as its y coordinate.
fs::path cubeWithCoordinate(const TempDir& dir, float value) {
  MeshData cube = test::unitCube();
  cube.positions[3].y = value;
  return test::writeDoc(test::singleMeshDoc(cube, "cube"), dir.path(), "bad", BufferStorage::Glb);
}

TEST(GltfLoaderBadFiles, NanPosition) {
  TempDir dir;
  expectLoadError(cubeWithCoordinate(dir, std::numeric_limits<float>::quiet_NaN()),
                  {"POSITION accessor 0", "position 3", "NaN"});
}

TEST(GltfLoaderBadFiles, InfinitePosition) {
  TempDir dir;
  expectLoadError(cubeWithCoordinate(dir, -std::numeric_limits<float>::infinity()),
                  {"POSITION accessor 0", "position 3", "infinite"});
}

TEST(GltfLoaderBadFiles, TransformTakingPositionsToInfinity) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::Glb, [](Json& j) {
    j["nodes"][0]["scale"] = {1e300, 1, 1};
  });
  expectLoadError(file, {"'cube'", "infinity"});
}

TEST(GltfLoaderBadFiles, PositionOfTypeVec2) {
  TempDir dir;
  const fs::path file =
      cubeFile(dir, BufferStorage::Glb, [](Json& j) { j["accessors"][0]["type"] = "VEC2"; });
  expectLoadError(file, {"POSITION accessor 0", "must be float VEC3"});
}

TEST(GltfLoaderBadFiles, PositionOfUnsignedShorts) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::Glb,
                                 [](Json& j) { j["accessors"][0]["componentType"] = test::kUnsignedShort; });
  expectLoadError(file, {"POSITION accessor 0", "must be float VEC3"});
}

TEST(GltfLoaderBadFiles, IndicesOfFloatType) {
  TempDir dir;
  const fs::path file =
      cubeFile(dir, BufferStorage::Glb, [](Json& j) { j["accessors"][1]["componentType"] = test::kFloat; });
  expectLoadError(file, {"indices accessor 1", "must be unsigned"});
}

// ---- nodes, meshes, materials -----------------------------------------------

TEST(GltfLoaderBadFiles, NodeChildIndexOutOfRange) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::Glb, [](Json& j) { j["nodes"][0]["children"] = {7}; });
  expectLoadError(file, {"'cube'", "node 7", "does not exist"});
}

TEST(GltfLoaderBadFiles, SceneRootIndexOutOfRange) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::Glb, [](Json& j) { j["scenes"][0]["nodes"] = {0, 3}; });
  expectLoadError(file, {"node 3", "does not exist"});
}

TEST(GltfLoaderBadFiles, NodeThatIsItsOwnChild) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::Glb, [](Json& j) { j["nodes"][0]["children"] = {0}; });
  expectLoadError(file, {"'cube'", "cycle"});
}

TEST(GltfLoaderBadFiles, TwoNodeCycle) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::Glb, [](Json& j) {
    j["nodes"][0]["children"] = {1};
    j["nodes"].push_back({{"name", "b"}, {"children", {0}}});
  });
  expectLoadError(file, {"'cube'", "cycle"});
}

TEST(GltfLoaderBadFiles, TwoNodeCycleWithoutAScene) {
  // no "scenes": roots are the nodes that are nobody's child, and in a cycle there are none
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::Glb, [](Json& j) {
    j.erase("scene");
    j.erase("scenes");
    j["nodes"][0]["children"] = {1};
    j["nodes"].push_back({{"name", "b"}, {"children", {0}}});
  });
  expectLoadError(file, {"cycle"});
}

/// A cube file whose cube node hangs `levels` - 1 nodes below the scene root.
fs::path cubeAtTheBottomOfAChain(const TempDir& dir, std::size_t levels) {
  GltfDoc doc;
  const int mesh = doc.addMesh(test::unitCube());
  int parent = doc.addNode({{"name", "level 1"}});
  doc.addRoot(parent);
  for (std::size_t level = 2; level <= levels; ++level) {
    Json node = {{"name", test::numbered("level ", level)}};
    if (level == levels) node["mesh"] = mesh;
    const int child = doc.addNode(node);
    doc.addChild(parent, child);
    parent = child;
  }
  return test::writeDoc(doc, dir.path(), "chain", BufferStorage::Glb);
}

TEST(GltfLoaderBadFiles, NodeHierarchyDeeperThanTheLimit) {
  TempDir dir;
  expectLoadError(cubeAtTheBottomOfAChain(dir, 100000), {"'level 256'", "level 257", "at most 256 levels"});
}

TEST(GltfLoaderBadFiles, NodeHierarchyAtTheLimitLoads) {
  TempDir dir;
  const Scene scene = loadGltfScene(cubeAtTheBottomOfAChain(dir, 256));
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects[0].name, "level 256");
}

TEST(GltfLoaderBadFiles, MeshIndexOutOfRange) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::Glb, [](Json& j) { j["nodes"][0]["mesh"] = 5; });
  expectLoadError(file, {"'cube'", "mesh 5", "does not exist"});
}

TEST(GltfLoaderBadFiles, MaterialIndexOutOfRange) {
  TempDir dir;
  const fs::path file =
      cubeFile(dir, BufferStorage::Glb, [](Json& j) { j["meshes"][0]["primitives"][0]["material"] = 3; });
  expectLoadError(file, {"'cube'", "material 3", "does not exist"});
}

TEST(GltfLoaderBadFiles, DefaultSceneOutOfRange) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::Glb, [](Json& j) { j["scene"] = 4; });
  expectLoadError(file, {"scene 4"});
}

// ---- Voxhap extras ----------------------------------------------------------

fs::path cubeWithSettings(const TempDir& dir, const Json& settings) {
  return cubeFile(dir, BufferStorage::Glb,
                  [&](Json& j) { j["nodes"][0]["extras"] = test::voxhapExtras(settings); });
}

TEST(GltfLoaderBadFiles, UnknownRole) {
  TempDir dir;
  expectLoadError(cubeWithSettings(dir, {{"role", "flying"}}),
                  {"'cube'", "extras.voxhap.role", "\"dynamic\""});
}

TEST(GltfLoaderBadFiles, NegativeDensity) {
  TempDir dir;
  expectLoadError(cubeWithSettings(dir, {{"density", -1}}), {"'cube'", "extras.voxhap.density", "positive"});
}

TEST(GltfLoaderBadFiles, DensityAsString) {
  TempDir dir;
  expectLoadError(cubeWithSettings(dir, {{"density", "heavy"}}), {"'cube'", "extras.voxhap.density"});
}

TEST(GltfLoaderBadFiles, PointOffsetBeyondOneMetreOrNotANumber) {
  TempDir dir;
  expectLoadError(cubeWithSettings(dir, {{"point_offset", -2}}),
                  {"'cube'", "extras.voxhap.point_offset", "at most 1 m"});
  expectLoadError(cubeWithSettings(dir, {{"point_offset", "-0.5mm"}}),
                  {"'cube'", "extras.voxhap.point_offset"});
}

TEST(GltfLoaderBadFiles, ForceLayerNotAWholeNumberOfLayersFrom1To255) {
  TempDir dir;
  for (const Json& bad : {Json(0), Json(256), Json(2.5), Json(-3), Json("3")}) {
    expectLoadError(cubeWithSettings(dir, {{"force_layer", bad}}),
                    {"'cube'", "extras.voxhap.force_layer", "1 … 255"});
  }
}

TEST(GltfLoaderBadFiles, ObjectNameNotAString) {
  TempDir dir;
  expectLoadError(cubeWithSettings(dir, {{"object", 5}}), {"'cube'", "extras.voxhap.object", "string"});
}

TEST(GltfLoaderBadFiles, VoxhapExtrasNotAnObject) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::Glb, [](Json& j) {
    j["nodes"][0]["extras"] = {{"voxhap", 3}};
  });
  expectLoadError(file, {"'cube'", "extras.voxhap"});
}

TEST(GltfLoaderBadFiles, BadSettingsOnAGroupNodeNameIt) {
  TempDir dir;
  const fs::path file = cubeFile(dir, BufferStorage::Glb, [](Json& j) {
    j["nodes"].push_back(
        {{"name", "group"}, {"children", {0}}, {"extras", test::voxhapExtras({{"role", 1}})}});
    j["scenes"][0]["nodes"] = {1};
  });
  expectLoadError(file, {"'group'", "extras.voxhap.role"});
}

// ---- no triangles -----------------------------------------------------------

TEST(GltfLoaderBadFiles, OnlyLinesAndPoints) {
  GltfDoc doc;
  const int p = doc.addPositions(test::unitCube().positions);
  doc.addMeshNode(doc.addMesh(p, -1, test::kModeLines), "wire");
  doc.addMeshNode(doc.addMesh(p, -1, test::kModePoints), "dots");
  TempDir dir;
  // the error says why: the skipped primitives would otherwise go unreported
  expectLoadError(test::writeDoc(doc, dir.path(), "lines", BufferStorage::Glb),
                  {"no triangles", "4 warnings", "node 'wire' primitive 0: lines primitive skipped"});
}

TEST(GltfLoaderBadFiles, LinesNextToTrianglesAreSkippedWithAWarning) {
  GltfDoc doc = test::singleMeshDoc(test::unitCube(), "cube");
  const int p = doc.addPositions(test::unitCube().positions);
  doc.json["meshes"][0]["primitives"].push_back(
      {{"attributes", {{"POSITION", p}}}, {"mode", test::kModeLines}});
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "mixed", BufferStorage::Glb));

  EXPECT_EQ(scene.triangleCount(), 12u);
  ASSERT_EQ(scene.warnings.size(), 1u) << joined(scene.warnings);
  EXPECT_TRUE(contains(scene.warnings[0], "'cube' primitive 1")) << scene.warnings[0];
  EXPECT_TRUE(contains(scene.warnings[0], "lines primitive skipped")) << scene.warnings[0];
}

TEST(GltfLoaderBadFiles, PrimitiveWithoutPositionIsSkippedWithAWarning) {
  GltfDoc doc = test::singleMeshDoc(test::unitCube(), "cube");
  doc.json["meshes"][0]["primitives"].push_back({{"attributes", {{"NORMAL", 0}}}, {"indices", 1}});
  TempDir dir;
  const Scene scene = loadGltfScene(test::writeDoc(doc, dir.path(), "nopos", BufferStorage::Glb));

  EXPECT_EQ(scene.triangleCount(), 12u);
  ASSERT_EQ(scene.warnings.size(), 1u) << joined(scene.warnings);
  EXPECT_TRUE(contains(scene.warnings[0], "'cube' primitive 1: no POSITION")) << scene.warnings[0];
}

TEST(GltfLoaderBadFiles, TrailingIndicesAreIgnoredWithAWarning) {
  MeshData cube = test::unitCube();
  cube.indices.insert(cube.indices.end(), {0, 1});  // two indices that make no triangle
  TempDir dir;
  const Scene scene = loadGltfScene(
      test::writeDoc(test::singleMeshDoc(cube, "cube"), dir.path(), "trailing", BufferStorage::Glb));

  EXPECT_EQ(scene.triangleCount(), 12u);
  ASSERT_EQ(scene.warnings.size(), 1u) << joined(scene.warnings);
  EXPECT_TRUE(contains(scene.warnings[0], "2 trailing indices")) << scene.warnings[0];
}

TEST(GltfLoaderBadFiles, SceneWithoutNodes) {
  GltfDoc doc;
  TempDir dir;
  expectLoadError(test::writeDoc(doc, dir.path(), "empty", BufferStorage::DataUri), {"no triangles"});
}

TEST(GltfLoaderBadFiles, DocumentWithoutScenesOrNodes) {
  TempDir dir;
  test::writeText(dir / "bare.gltf", R"({"asset": {"version": "2.0"}})");
  expectLoadError(dir / "bare.gltf", {"no triangles"});
}

TEST(GltfLoaderBadFiles, SceneWhoseMeshesHaveNoPrimitives) {
  TempDir dir;
  const fs::path file =
      cubeFile(dir, BufferStorage::Glb, [](Json& j) { j["meshes"][0]["primitives"] = Json::array(); });
  expectLoadError(file, {"no triangles"});
}

// ---- degenerate triangles ----------------------------------------------------

TEST(GltfLoaderBadFiles, DegenerateTrianglesAreDroppedCountedAndWarned) {
  MeshData cube = test::unitCube();
  cube.positions.push_back({1, 0, 0});  // 8: same place as vertex 1
  cube.positions.push_back({2, 0, 0});  // 9: on the line through vertices 0 and 1
  cube.indices.insert(cube.indices.end(), {
                                              0, 0, 1,  // repeated index
                                              0, 1, 8,  // coincident positions
                                              0, 1, 9,  // collinear, zero area
                                          });
  TempDir dir;
  const Scene scene = loadGltfScene(
      test::writeDoc(test::singleMeshDoc(cube, "cube"), dir.path(), "degenerate", BufferStorage::Glb));

  ASSERT_EQ(scene.objects.size(), 1u);
  const Part& part = scene.objects[0].parts.at(0);
  EXPECT_EQ(part.degenerateTrianglesDropped, 3u);
  EXPECT_EQ(part.mesh.triangles.size(), 12u);
  EXPECT_TRUE(part.topology.closed());
  EXPECT_TRUE(part.topology.consistentlyOriented());
  ASSERT_EQ(scene.warnings.size(), 1u) << joined(scene.warnings);
  EXPECT_TRUE(contains(scene.warnings[0], "'cube'")) << scene.warnings[0];
  EXPECT_TRUE(contains(scene.warnings[0], "3 degenerate triangles dropped")) << scene.warnings[0];
}

TEST(GltfLoaderBadFiles, OnlyDegenerateTriangles) {
  MeshData flat;
  flat.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.indices = {0, 1, 2, 0, 0, 1};
  TempDir dir;
  expectLoadError(test::writeDoc(test::singleMeshDoc(flat, "flat"), dir.path(), "flat", BufferStorage::Glb),
                  {"no triangles", "1 warning: node 'flat': 2 degenerate triangles dropped"});
}

}  // namespace
}  // namespace voxhap

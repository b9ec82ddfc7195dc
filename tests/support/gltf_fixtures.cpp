#include "tests/support/gltf_fixtures.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>

#include <gtest/gtest.h>
#include <unistd.h>

namespace voxhap::test {

namespace fs = std::filesystem;

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  std::string name = "voxhap_test";
  if (const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info()) {
    name += std::string("_") + info->test_suite_name() + "_" + info->name();
  }
  for (char& c : name) {
    if (c == '/' || c == '\\' || c == ' ') c = '_';
  }
  name += numbered("_", static_cast<std::uint64_t>(::getpid()));
  name += numbered("_", static_cast<std::uint64_t>(counter++));
  path_ = fs::temp_directory_path() / name;
  std::error_code ec;
  fs::remove_all(path_, ec);
  fs::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

MeshData unitCube() {
  MeshData m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  m.indices = {
      0, 3, 2, 0, 2, 1,  // z = 0
      4, 5, 6, 4, 6, 7,  // z = 1
      0, 1, 5, 0, 5, 4,  // y = 0
      3, 7, 6, 3, 6, 2,  // y = 1
      0, 4, 7, 0, 7, 3,  // x = 0
      1, 2, 6, 1, 6, 5,  // x = 1
  };
  return m;
}

MeshData tetrahedron() {
  MeshData m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  return m;
}

GltfDoc::GltfDoc() {
  json = {{"asset", {{"version", "2.0"}, {"generator", "voxhap tests"}}},
          {"scene", 0},
          {"scenes", nlohmann::json::array({{{"nodes", nlohmann::json::array()}}})}};
}

int GltfDoc::addBufferView(const void* data, std::size_t bytes, std::size_t byteStride) {
  const std::size_t offset = bin.size();
  const auto* p = static_cast<const unsigned char*>(data);
  bin.insert(bin.end(), p, p + bytes);
  while (bin.size() % 4 != 0) bin.push_back(0);
  nlohmann::json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
  if (byteStride != 0) view["byteStride"] = byteStride;
  json["bufferViews"].push_back(view);
  return static_cast<int>(json["bufferViews"].size() - 1);
}

int GltfDoc::addAccessor(int bufferView, int componentType, std::uint64_t count, const std::string& type,
                         std::size_t byteOffset) {
  nlohmann::json accessor = {
      {"bufferView", bufferView}, {"componentType", componentType}, {"count", count}, {"type", type}};
  if (byteOffset != 0) accessor["byteOffset"] = byteOffset;
  json["accessors"].push_back(accessor);
  return static_cast<int>(json["accessors"].size() - 1);
}

int GltfDoc::addPositions(const std::vector<glm::vec3>& positions) {
  const int view = addBufferView(positions.data(), positions.size() * sizeof(glm::vec3));
  const int accessor = addAccessor(view, kFloat, positions.size(), "VEC3");
  if (!positions.empty()) {
    glm::vec3 lo = positions[0];
    glm::vec3 hi = positions[0];
    for (const glm::vec3& p : positions) {
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    }
    json["accessors"][static_cast<std::size_t>(accessor)]["min"] = {lo.x, lo.y, lo.z};
    json["accessors"][static_cast<std::size_t>(accessor)]["max"] = {hi.x, hi.y, hi.z};
  }
  return accessor;
}

int GltfDoc::addIndices(const std::vector<std::uint32_t>& indices, int componentType) {
  std::vector<unsigned char> bytes;
  for (std::uint32_t index : indices) {
    if (componentType == kUnsignedByte) {
      bytes.push_back(static_cast<unsigned char>(index));
    } else if (componentType == kUnsignedShort) {
      const auto v = static_cast<std::uint16_t>(index);
      bytes.insert(bytes.end(), {static_cast<unsigned char>(v & 0xFF), static_cast<unsigned char>(v >> 8)});
    } else if (componentType == kUnsignedInt) {
      for (int k = 0; k < 4; ++k) bytes.push_back(static_cast<unsigned char>(index >> (8 * k)));
    } else {
      throw std::invalid_argument("addIndices: componentType must be 5121, 5123 or 5125");
    }
  }
  const int view = addBufferView(bytes.data(), bytes.size());
  return addAccessor(view, componentType, indices.size(), "SCALAR");
}

int GltfDoc::addMaterial(const glm::vec4& baseColor, const std::string& name) {
  nlohmann::json material = {
      {"pbrMetallicRoughness", {{"baseColorFactor", {baseColor.r, baseColor.g, baseColor.b, baseColor.a}}}}};
  if (!name.empty()) material["name"] = name;
  json["materials"].push_back(material);
  return static_cast<int>(json["materials"].size() - 1);
}

int GltfDoc::addMesh(int positionsAccessor, int indicesAccessor, int mode, int material) {
  nlohmann::json primitive = {{"attributes", {{"POSITION", positionsAccessor}}}, {"mode", mode}};
  if (indicesAccessor >= 0) primitive["indices"] = indicesAccessor;
  if (material >= 0) primitive["material"] = material;
  json["meshes"].push_back({{"primitives", nlohmann::json::array({primitive})}});
  return static_cast<int>(json["meshes"].size() - 1);
}

int GltfDoc::addMesh(const MeshData& mesh, int material, int indexType) {
  const int positions = addPositions(mesh.positions);
  const int indices = addIndices(mesh.indices, indexType);
  return addMesh(positions, indices, kModeTriangles, material);
}

int GltfDoc::addNode(nlohmann::json nodeJson) {
  json["nodes"].push_back(std::move(nodeJson));
  return static_cast<int>(json["nodes"].size() - 1);
}

int GltfDoc::addMeshNode(int mesh, const std::string& name) {
  nlohmann::json n = {{"mesh", mesh}};
  if (!name.empty()) n["name"] = name;
  const int index = addNode(std::move(n));
  addRoot(index);
  return index;
}

void GltfDoc::addRoot(int nodeIndex) {
  json["scenes"][0]["nodes"].push_back(nodeIndex);
}

void GltfDoc::addChild(int parent, int child) {
  node(parent)["children"].push_back(child);
}

nlohmann::json& GltfDoc::node(int index) {
  return json.at("nodes").at(static_cast<std::size_t>(index));
}

int GltfDoc::nodeNamed(const std::string& name) const {
  const nlohmann::json& nodes = json.at("nodes");
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].value("name", std::string()) == name) return static_cast<int>(i);
  }
  throw std::out_of_range("no node named " + name);
}

GltfDoc pistonAssemblyDoc() {
  GltfDoc doc;
  auto coloured = [&](const glm::vec4& colour, const std::string& name) {
    return doc.addMesh(unitCube(), doc.addMaterial(colour, name));
  };
  const int red = coloured({0.8f, 0.1f, 0.1f, 1.0f}, "red");
  const int blue = coloured({0.1f, 0.2f, 0.9f, 1.0f}, "blue");
  const int grey = coloured({0.5f, 0.5f, 0.5f, 1.0f}, "grey");
  const int piston = doc.addNode({{"name", "piston"}});
  const int crown = doc.addNode(
      {{"name", "crown"}, {"mesh", red}, {"translation", {0.0, 0.0, 0.012}}, {"scale", {0.01, 0.01, 0.01}}});
  const int pin = doc.addNode({{"name", "pin"},
                               {"mesh", blue},
                               {"translation", {0.011, 0.003, 0.015}},
                               {"scale", {0.004, 0.004, 0.004}}});
  doc.addChild(piston, crown);
  doc.addChild(piston, pin);
  doc.addRoot(piston);
  const int block = doc.addNode({{"name", "block"},
                                 {"mesh", grey},
                                 {"translation", {-0.01, -0.01, 0.0}},
                                 {"scale", {0.03, 0.03, 0.01}}});
  doc.addRoot(block);
  return doc;
}

GltfDoc singleMeshDoc(const MeshData& mesh, const std::string& name, int material) {
  GltfDoc doc;
  doc.addMeshNode(doc.addMesh(mesh, material), name);
  return doc;
}

nlohmann::json voxhapExtras(const nlohmann::json& settings) {
  return {{"voxhap", settings}};
}

nlohmann::json finishedJson(const GltfDoc& doc, BufferStorage storage, const std::string& binUri) {
  nlohmann::json json = doc.json;
  if (doc.bin.empty()) return json;
  nlohmann::json buffer = {{"byteLength", doc.bin.size()}};
  switch (storage) {
    case BufferStorage::DataUri:
      buffer["uri"] = "data:application/octet-stream;base64," + base64(doc.bin);
      break;
    case BufferStorage::External:
      buffer["uri"] = binUri;
      break;
    case BufferStorage::Glb:
      break;
  }
  json["buffers"] = nlohmann::json::array({buffer});
  return json;
}

fs::path writeDoc(const GltfDoc& doc, const fs::path& dir, const std::string& stem, BufferStorage storage,
                  const JsonMutator& mutate) {
  const std::string binName = stem + ".bin";
  nlohmann::json json = finishedJson(doc, storage, binName);
  if (mutate) mutate(json);
  if (storage == BufferStorage::Glb) {
    const fs::path file = dir / (stem + ".glb");
    writeBytes(file, packGlb(json.dump(), doc.bin));
    return file;
  }
  if (storage == BufferStorage::External) writeBytes(dir / binName, doc.bin);
  const fs::path file = dir / (stem + ".gltf");
  writeText(file, json.dump(2));
  return file;
}

void putU32(std::vector<unsigned char>& bytes, std::size_t offset, std::uint32_t value) {
  if (offset + 4 > bytes.size()) throw std::out_of_range("putU32 past the end");
  for (int k = 0; k < 4; ++k)
    bytes[offset + static_cast<std::size_t>(k)] = static_cast<unsigned char>(value >> (8 * k));
}

std::uint32_t getU32(const std::vector<unsigned char>& bytes, std::size_t offset) {
  if (offset + 4 > bytes.size()) throw std::out_of_range("getU32 past the end");
  std::uint32_t value = 0;
  for (int k = 0; k < 4; ++k) value |= std::uint32_t{bytes[offset + static_cast<std::size_t>(k)]} << (8 * k);
  return value;
}

namespace {
void appendU32(std::vector<unsigned char>& bytes, std::uint32_t value) {
  bytes.resize(bytes.size() + 4);
  putU32(bytes, bytes.size() - 4, value);
}
}  // namespace

std::vector<unsigned char> packGlb(const std::string& jsonText, const std::vector<unsigned char>& bin) {
  std::vector<unsigned char> jsonChunk(jsonText.begin(), jsonText.end());
  while (jsonChunk.size() % 4 != 0) jsonChunk.push_back(' ');
  std::vector<unsigned char> binChunk = bin;
  while (binChunk.size() % 4 != 0) binChunk.push_back(0);

  std::vector<unsigned char> out;
  const std::size_t total = 12 + 8 + jsonChunk.size() + (binChunk.empty() ? 0 : 8 + binChunk.size());
  out.insert(out.end(), {'g', 'l', 'T', 'F'});
  appendU32(out, 2);
  appendU32(out, static_cast<std::uint32_t>(total));
  appendU32(out, static_cast<std::uint32_t>(jsonChunk.size()));
  out.insert(out.end(), {'J', 'S', 'O', 'N'});
  out.insert(out.end(), jsonChunk.begin(), jsonChunk.end());
  if (!binChunk.empty()) {
    appendU32(out, static_cast<std::uint32_t>(binChunk.size()));
    out.insert(out.end(), {'B', 'I', 'N', '\0'});
    out.insert(out.end(), binChunk.begin(), binChunk.end());
  }
  return out;
}

GlbLayout glbLayout(const std::vector<unsigned char>& glb) {
  GlbLayout layout;
  const std::size_t jsonEnd =
      GlbLayout::kJsonChunkDataOffset + getU32(glb, GlbLayout::kJsonChunkLengthOffset);
  if (jsonEnd + 8 <= glb.size()) {
    layout.binChunkLengthOffset = jsonEnd;
    layout.binChunkDataOffset = jsonEnd + 8;
  }
  return layout;
}

std::string base64(const std::vector<unsigned char>& bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v =
        (std::uint32_t{bytes[i]} << 16) | (std::uint32_t{bytes[i + 1]} << 8) | bytes[i + 2];
    for (int k = 3; k >= 0; --k) out.push_back(kAlphabet[(v >> (6 * k)) & 63]);
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    std::uint32_t v = std::uint32_t{bytes[i]} << 16;
    if (rest == 2) v |= std::uint32_t{bytes[i + 1]} << 8;
    out.push_back(kAlphabet[(v >> 18) & 63]);
    out.push_back(kAlphabet[(v >> 12) & 63]);
    out.push_back(rest == 2 ? kAlphabet[(v >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

std::string numbered(const std::string& prefix, std::uint64_t n) {
  std::string out = prefix;
  out += std::to_string(n);
  return out;
}

void writeBytes(const fs::path& file, const std::vector<unsigned char>& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

void writeText(const fs::path& file, const std::string& text) {
  writeBytes(file, std::vector<unsigned char>(text.begin(), text.end()));
}

std::vector<unsigned char> readBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace voxhap::test

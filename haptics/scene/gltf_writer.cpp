#include "haptics/scene/gltf_writer.h"

#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <system_error>
#include <tuple>

#include <glm/common.hpp>
#include <tiny_gltf.h>

#include "haptics/core/error.h"
#include "haptics/scene/gltf_extras.h"

namespace voxhap {
namespace {

/// Appends raw bytes to buffer 0 and returns the index of a new view on them.
int addView(tinygltf::Model& model, const void* data, std::size_t bytes, int target) {
  std::vector<unsigned char>& buffer = model.buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.size();
  view.byteLength = bytes;
  view.target = target;
  const auto* p = static_cast<const unsigned char*>(data);
  buffer.insert(buffer.end(), p, p + bytes);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size() - 1);
}

int addMesh(tinygltf::Model& model, const Part& part, int material) {
  const TriangleMesh& mesh = part.mesh;
  tinygltf::Accessor positions;
  positions.bufferView =
      addView(model, mesh.positionsWorld.data(), mesh.positionsWorld.size() * sizeof(glm::vec3),
              TINYGLTF_TARGET_ARRAY_BUFFER);
  positions.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  positions.type = TINYGLTF_TYPE_VEC3;
  positions.count = mesh.positionsWorld.size();
  glm::vec3 lo(std::numeric_limits<float>::max());
  glm::vec3 hi(std::numeric_limits<float>::lowest());
  for (const glm::vec3& p : mesh.positionsWorld) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  positions.minValues = {lo.x, lo.y, lo.z};
  positions.maxValues = {hi.x, hi.y, hi.z};
  model.accessors.push_back(positions);

  tinygltf::Accessor indices;
  indices.bufferView = addView(model, mesh.triangles.data(), mesh.triangles.size() * sizeof(glm::uvec3),
                               TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  indices.type = TINYGLTF_TYPE_SCALAR;
  indices.count = mesh.triangles.size() * 3;
  model.accessors.push_back(indices);

  tinygltf::Primitive primitive;
  primitive.attributes["POSITION"] = static_cast<int>(model.accessors.size() - 2);
  primitive.indices = static_cast<int>(model.accessors.size() - 1);
  primitive.material = material;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh out;
  out.name = part.name;
  out.primitives.push_back(primitive);
  model.meshes.push_back(out);
  return static_cast<int>(model.meshes.size() - 1);
}

}  // namespace

std::vector<unsigned char> writeGlb(const Scene& scene) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "voxhap";
  model.buffers.resize(1);
  model.scenes.resize(1);
  model.defaultScene = 0;

  std::map<std::tuple<float, float, float, float>, int> materialOfColor;
  auto materialFor = [&](const glm::vec4& c) {
    const auto key = std::make_tuple(c.r, c.g, c.b, c.a);
    const auto found = materialOfColor.find(key);
    if (found != materialOfColor.end()) return found->second;
    tinygltf::Material material;
    material.name = "color " + std::to_string(model.materials.size());
    material.pbrMetallicRoughness.baseColorFactor = {c.r, c.g, c.b, c.a};
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.6;
    model.materials.push_back(material);
    const int index = static_cast<int>(model.materials.size() - 1);
    materialOfColor.emplace(key, index);
    return index;
  };

  for (const SceneObject& object : scene.objects) {
    tinygltf::Node objectNode;
    objectNode.name = object.name;
    objectNode.extras = objectExtras(object);
    const bool singlePart = object.parts.size() == 1 && object.parts[0].name == object.name;
    std::vector<tinygltf::Node> children;
    for (const Part& part : object.parts) {
      const int mesh = addMesh(model, part, materialFor(part.baseColor));
      if (singlePart) {
        objectNode.mesh = mesh;
      } else {
        tinygltf::Node child;
        child.name = part.name;
        child.mesh = mesh;
        children.push_back(child);
      }
    }
    const int objectIndex = static_cast<int>(model.nodes.size());
    model.nodes.push_back(objectNode);
    for (tinygltf::Node& child : children) {
      model.nodes[static_cast<std::size_t>(objectIndex)].children.push_back(
          static_cast<int>(model.nodes.size()));
      model.nodes.push_back(std::move(child));
    }
    model.scenes[0].nodes.push_back(objectIndex);
  }

  tinygltf::TinyGLTF writer;
  std::ostringstream stream;
  if (!writer.WriteGltfSceneToStream(&model, stream, false, true)) {
    throw Error(scene.sourceName + ": could not encode the scene as GLB");
  }
  const std::string bytes = std::move(stream).str();
  return {bytes.begin(), bytes.end()};
}

void writeGlbFile(const Scene& scene, const std::filesystem::path& file) {
  const std::vector<unsigned char> bytes = writeGlb(scene);
  std::filesystem::path temporary = file;
  temporary += ".partial";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw Error(file.string() + ": cannot write: " + std::strerror(errno));
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, file, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    throw Error(file.string() + ": cannot move the finished file into place: " + ec.message());
  }
}

}  // namespace voxhap

#include "haptics/scene/gltf_loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <system_error>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat4x4.hpp>
#include <tiny_gltf.h>

#include "haptics/core/error.h"
#include "haptics/scene/gltf_accessors.h"
#include "haptics/scene/gltf_extras.h"

namespace voxhap {
namespace {

namespace fs = std::filesystem;

std::string quoted(const std::string& name) {
  return "'" + name + "'";
}

// Both limits keep recursion (tinygltf's JSON conversion, our node walk) far from
// the end of the stack; real glTF files stay within a few dozen levels.
constexpr std::size_t kMaxJsonDepth = 256;
constexpr std::size_t kMaxNodeDepth = 256;

/// Deepest nesting of JSON arrays and objects in `text`, not counting brackets in strings.
std::size_t jsonNestingDepth(const unsigned char* text, std::size_t size) {
  std::size_t depth = 0;
  std::size_t deepest = 0;
  bool inString = false;
  for (std::size_t i = 0; i < size; ++i) {
    const unsigned char c = text[i];
    if (inString) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        inString = false;
      }
    } else if (c == '"') {
      inString = true;
    } else if (c == '{' || c == '[') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == '}' || c == ']') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

/// Reads a whole regular file, refusing devices, pipes and files over the limit.
std::vector<unsigned char> readRegularFile(const fs::path& path, std::string& error) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) {
    error = "no such file";
    return {};
  }
  if (!fs::is_regular_file(status)) {
    error = "not a regular file";
    return {};
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) {
    error = "cannot read its size: " + ec.message();
    return {};
  }
  if (size > kMaxGltfFileBytes) {
    error = "larger than the 4 GiB limit (" + std::to_string(size) + " bytes)";
    return {};
  }
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
  if (!in || !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size))) {
    error = std::string("cannot read: ") + std::strerror(errno);
    return {};
  }
  return bytes;
}

// tinygltf file-system callbacks: external buffers go through readRegularFile so
// that a URI naming a device or a huge file cannot hang or exhaust memory. A path
// that exists but is no regular file is "found" so that the read reports why.
// tinygltf looks for a URI next to the glTF file and then in the working directory;
// `user` is the glTF file's directory, and only paths inside it count, so that a
// missing buffer is reported rather than replaced by a namesake from elsewhere.
bool fileExists(const std::string& path, void* user) {
  const std::string& baseDir = *static_cast<const std::string*>(user);
  if (!baseDir.empty()) {
    const std::string prefix = baseDir.back() == '/' ? baseDir : baseDir + "/";
    if (path.rfind(prefix, 0) != 0) return false;
  }
  std::error_code ec;
  return fs::exists(path, ec);
}
std::string expandFilePath(const std::string& path, void*) {
  return path;
}
bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  std::string error;
  *out = readRegularFile(path, error);
  if (!error.empty() && err) *err += error;  // tinygltf prefixes the path
  return error.empty();
}
bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "writing is not allowed while loading";
  return false;
}
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
               void*) {
  return true;  // only geometry and base colours matter to Voxhap
}

/// Converts a tinygltf message (several lines, with trailing newlines) to one short
/// line: tinygltf quotes whole data: URIs, which can be megabytes of base64.
std::string oneLine(std::string text) {
  constexpr std::size_t kMaxChars = 400;
  for (std::size_t from = 0; (from = text.find(";base64,", from)) != std::string::npos;) {
    const std::size_t begin = from + 8;
    std::size_t end = begin;
    while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end])) && text[end] != '\'' &&
           text[end] != '"') {
      ++end;
    }
    if (end - begin > 16) text.replace(begin, end - begin, "...(" + std::to_string(end - begin) + " chars)");
    from = begin;
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.pop_back();
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ';';
  }
  if (text.size() > kMaxChars) text = text.substr(0, kMaxChars) + "...";
  return text;
}

std::uint32_t readU32(const std::vector<unsigned char>& bytes, std::size_t offset) {
  std::uint32_t value = 0;
  for (std::size_t k = 0; k < 4; ++k) value |= std::uint32_t{bytes[offset + k]} << (8 * k);
  return value;
}

/// Checks the GLB container (header and chunk lengths) so that a truncated or
/// corrupt file gets a message saying what is wrong; returns "" when it is sound.
std::string glbContainerError(const std::vector<unsigned char>& bytes) {
  const std::uint64_t size = bytes.size();
  if (size < 12) return "truncated GLB: " + std::to_string(size) + " bytes, shorter than the 12-byte header";
  const std::uint32_t version = readU32(bytes, 4);
  if (version != 2) return "GLB version " + std::to_string(version) + " is not supported (only 2)";
  const std::uint64_t length = readU32(bytes, 8);
  if (length > size) {
    return "truncated GLB: its header says " + std::to_string(length) + " bytes but the file has " +
           std::to_string(size);
  }
  if (length < 20) return "GLB length " + std::to_string(length) + " leaves no room for the JSON chunk";
  const std::uint64_t jsonLength = readU32(bytes, 12);
  if (readU32(bytes, 16) != 0x4E4F534Au) return "the first GLB chunk is not the JSON chunk";
  const std::uint64_t jsonEnd = 20 + jsonLength;
  if (jsonEnd > length) {
    return "GLB JSON chunk of " + std::to_string(jsonLength) + " bytes runs past the end of the " +
           std::to_string(length) + "-byte file";
  }
  if (jsonEnd == length) return "";
  if (jsonEnd + 8 > length) return "truncated GLB: it ends inside the BIN chunk header";
  const std::uint64_t binLength = readU32(bytes, static_cast<std::size_t>(jsonEnd));
  if (jsonEnd + 8 + binLength > length) {
    return "GLB BIN chunk of " + std::to_string(binLength) + " bytes runs past the end of the " +
           std::to_string(length) + "-byte file";
  }
  return "";
}

glm::dmat4 localTransform(const tinygltf::Node& node, const std::string& where) {
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) throw Error(where + ": matrix must have 16 numbers");
    glm::dmat4 m;
    std::memcpy(glm::value_ptr(m), node.matrix.data(), sizeof(double) * 16);  // column-major
    return m;
  }
  glm::dmat4 m(1.0);
  if (!node.translation.empty()) {
    if (node.translation.size() != 3) throw Error(where + ": translation must have 3 numbers");
    m = glm::translate(m, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
  }
  if (!node.rotation.empty()) {
    if (node.rotation.size() != 4) throw Error(where + ": rotation must have 4 numbers");
    const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    const double norm = glm::length(q);
    if (!(norm > 0.0)) throw Error(where + ": rotation is not a valid quaternion");
    m = m * glm::mat4_cast(q / norm);
  }
  if (!node.scale.empty()) {
    if (node.scale.size() != 3) throw Error(where + ": scale must have 3 numbers");
    m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
  }
  return m;
}

/// Triangles of one primitive as vertex-index triples, by primitive mode.
std::vector<glm::uvec3> assembleTriangles(const std::vector<std::uint32_t>& idx, int mode) {
  std::vector<glm::uvec3> out;
  const std::size_t n = idx.size();
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    out.reserve(n / 3);
    for (std::size_t i = 0; i + 2 < n; i += 3) out.emplace_back(idx[i], idx[i + 1], idx[i + 2]);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (std::size_t i = 0; i + 2 < n; ++i) {
      if (i % 2 == 0) {
        out.emplace_back(idx[i], idx[i + 1], idx[i + 2]);
      } else {
        out.emplace_back(idx[i + 1], idx[i], idx[i + 2]);
      }
    }
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (std::size_t i = 1; i + 1 < n; ++i) out.emplace_back(idx[0], idx[i], idx[i + 1]);
  }
  return out;
}

const char* modeName(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS:
      return "points";
    case TINYGLTF_MODE_LINE:
      return "lines";
    case TINYGLTF_MODE_LINE_LOOP:
      return "line loop";
    case TINYGLTF_MODE_LINE_STRIP:
      return "line strip";
    default:
      return "unknown";
  }
}

class SceneBuilder {
public:
  SceneBuilder(const tinygltf::Model& model, std::string fileName, const ProgressFn& progress)
      : model_(model), file_(std::move(fileName)), reader_(model), progress_(progress) {
    scene_.sourceName = file_;
  }

  Scene build() {
    const std::vector<int> roots = rootNodes();
    visited_.assign(model_.nodes.size(), false);
    for (int root : roots) visit(root, glm::dmat4(1.0), std::nullopt, "scene", 0);
    if (model_.scenes.empty()) {
      // every node is reachable from a parentless one unless it sits in (or under) a cycle
      for (std::size_t i = 0; i < visited_.size(); ++i) {
        if (!visited_[i]) {
          const std::string& name = model_.nodes[i].name;
          throw Error(file_ + ": node " + quoted(name.empty() ? "node " + std::to_string(i) : name) +
                      " is in or under a cycle of the node hierarchy");
        }
      }
    }
    if (scene_.triangleCount() == 0) {
      // what was skipped is usually why; the exception is all the user gets to see
      std::string why;
      if (!scene_.warnings.empty()) {
        std::string first = scene_.warnings.front();
        if (first.rfind(file_ + ": ", 0) == 0) first.erase(0, file_.size() + 2);
        const std::size_t n = scene_.warnings.size();
        why = " (" + std::to_string(n) + (n == 1 ? " warning: " : " warnings, the first: ") + first + ")";
      }
      throw Error(file_ + ": the scene has no triangles" + why);
    }
    reportDuplicateNames();
    for (const SceneObject& object : scene_.objects) reportTopology(object);
    if (progress_) progress_(1.0);  // nodes outside the scene are never visited
    return std::move(scene_);
  }

private:
  std::vector<int> rootNodes() const {
    if (!model_.scenes.empty()) {
      const int chosen = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (static_cast<std::size_t>(chosen) >= model_.scenes.size()) {
        throw Error(file_ + ": default scene " + std::to_string(chosen) + " does not exist");
      }
      return model_.scenes[static_cast<std::size_t>(chosen)].nodes;
    }
    // no scenes: every node that is nobody's child is a root
    std::vector<bool> isChild(model_.nodes.size(), false);
    for (const tinygltf::Node& node : model_.nodes) {
      for (int child : node.children) {
        if (child >= 0 && static_cast<std::size_t>(child) < isChild.size()) {
          isChild[static_cast<std::size_t>(child)] = true;
        }
      }
    }
    std::vector<int> roots;
    for (std::size_t i = 0; i < isChild.size(); ++i) {
      if (!isChild[i]) roots.push_back(static_cast<int>(i));
    }
    return roots;
  }

  void visit(int nodeIndex, const glm::dmat4& parentWorld, std::optional<NodeSettings> inherited,
             const std::string& parentWhere, std::size_t depth) {
    if (nodeIndex < 0 || static_cast<std::size_t>(nodeIndex) >= model_.nodes.size()) {
      throw Error(file_ + ": " + parentWhere + " names node " + std::to_string(nodeIndex) +
                  ", which does not exist (" + std::to_string(model_.nodes.size()) + " nodes)");
    }
    const std::size_t index = static_cast<std::size_t>(nodeIndex);
    const tinygltf::Node& node = model_.nodes[index];
    const std::string name = node.name.empty() ? "node " + std::to_string(nodeIndex) : node.name;
    const std::string where = file_ + ": node " + quoted(name);
    if (visited_[index]) {
      throw Error(where + " appears twice in the node hierarchy (a cycle or a shared child)");
    }
    visited_[index] = true;
    ++nodesDone_;
    if (progress_ && !model_.nodes.empty()) {
      progress_(static_cast<double>(nodesDone_) / static_cast<double>(model_.nodes.size()));
    }

    const glm::dmat4 world = parentWorld * localTransform(node, where);
    std::optional<NodeSettings> own = readNodeSettings(node, name, where, scene_.warnings);
    // a node with neither mesh nor settings, outside any object named by extras, groups
    // what lies under it (a CAD sub-assembly); kept if it holds a part
    const bool isGroup = node.mesh < 0 && !own && !inherited;
    const std::size_t group = scene_.groups.size();
    const std::size_t firstPlaced = objectOfPart_.size();
    if (isGroup) scene_.groups.push_back({name, {}});
    if (own) inherited = std::move(own);
    if (node.mesh >= 0) addMeshNode(node, name, where, world, inherited);
    if (!node.children.empty() && depth + 1 >= kMaxNodeDepth) {
      throw Error(where + ": its children would be level " + std::to_string(depth + 2) +
                  " of the node hierarchy, which may have at most " + std::to_string(kMaxNodeDepth) +
                  " levels");
    }
    for (int child : node.children) visit(child, world, inherited, "node " + quoted(name), depth + 1);
    if (isGroup) {
      std::vector<std::size_t>& objects = scene_.groups[group].objects;
      objects.assign(objectOfPart_.begin() + static_cast<std::ptrdiff_t>(firstPlaced), objectOfPart_.end());
      std::sort(objects.begin(), objects.end());
      objects.erase(std::unique(objects.begin(), objects.end()), objects.end());
    }
  }

  void addMeshNode(const tinygltf::Node& node, const std::string& name, const std::string& where,
                   const glm::dmat4& world, const std::optional<NodeSettings>& settings) {
    if (static_cast<std::size_t>(node.mesh) >= model_.meshes.size()) {
      throw Error(where + ": mesh " + std::to_string(node.mesh) + " does not exist");
    }
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(node.mesh)];
    const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;

    TriangleMesh out;
    std::optional<glm::vec4> color;
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = mesh.primitives[p];
      const std::string primWhere = where + " primitive " + std::to_string(p);
      const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
      if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
          mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        scene_.warnings.push_back(primWhere + ": " + modeName(mode) + " primitive skipped (not triangles)");
        continue;
      }
      const auto position = prim.attributes.find("POSITION");
      if (position == prim.attributes.end()) {
        scene_.warnings.push_back(primWhere + ": no POSITION attribute; skipped");
        continue;
      }
      const std::vector<glm::vec3> local = reader_.positions(position->second, primWhere);
      std::vector<std::uint32_t> idx;
      if (prim.indices >= 0) {
        idx = reader_.indices(prim.indices, local.size(), primWhere);
      } else {
        idx.resize(local.size());
        for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<std::uint32_t>(i);
      }
      if (mode == TINYGLTF_MODE_TRIANGLES && idx.size() % 3 != 0) {
        scene_.warnings.push_back(primWhere + ": " + std::to_string(idx.size() % 3) +
                                  " trailing indices do not make a triangle; ignored");
      }
      if (out.positionsWorld.size() + local.size() > std::numeric_limits<std::uint32_t>::max()) {
        throw Error(primWhere + ": more than 2^32 vertices in one node");
      }
      const auto base = static_cast<std::uint32_t>(out.positionsWorld.size());
      for (const glm::vec3& p0 : local) out.positionsWorld.emplace_back(world * glm::dvec4(p0, 1.0));
      for (glm::uvec3 t : assembleTriangles(idx, mode)) {
        if (mirrored) std::swap(t.y, t.z);
        out.triangles.push_back(t + base);
      }
      const glm::vec4 primColor = materialColor(prim.material, primWhere);
      if (!color) {
        color = primColor;
      } else if (*color != primColor) {
        scene_.warnings.push_back(primWhere +
                                  ": its material colour differs from primitive 0's; "
                                  "the part keeps primitive 0's colour");
      }
    }
    for (const glm::vec3& p : out.positionsWorld) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        throw Error(where + ": its transform takes a position to infinity");
      }
    }
    if (out.triangles.empty()) {
      scene_.warnings.push_back(where + ": no triangles; skipped");
      return;
    }
    Part part = makePart(name, color.value_or(glm::vec4(1.0f)), std::move(out));
    if (part.degenerateTrianglesDropped > 0) {
      scene_.warnings.push_back(where + ": " + std::to_string(part.degenerateTrianglesDropped) +
                                " degenerate triangles dropped");
    }
    if (part.mesh.triangles.empty()) return;
    const std::size_t object = objectFor(name, settings);
    scene_.objects[object].parts.push_back(std::move(part));
    objectOfPart_.push_back(object);
  }

  glm::vec4 materialColor(int materialIndex, const std::string& where) const {
    if (materialIndex < 0) return glm::vec4(1.0f);
    if (static_cast<std::size_t>(materialIndex) >= model_.materials.size()) {
      throw Error(where + ": material " + std::to_string(materialIndex) + " does not exist");
    }
    const std::vector<double>& f =
        model_.materials[static_cast<std::size_t>(materialIndex)].pbrMetallicRoughness.baseColorFactor;
    if (f.size() != 4) throw Error(where + ": baseColorFactor must have 4 numbers");
    return glm::vec4(static_cast<float>(f[0]), static_cast<float>(f[1]), static_cast<float>(f[2]),
                     static_cast<float>(f[3]));
  }

  /// The index in scene_.objects of the object a mesh node's part goes to.
  std::size_t objectFor(const std::string& nodeName, const std::optional<NodeSettings>& settings) {
    if (settings) {
      const auto found = namedObjects_.find(settings->objectName);
      if (found != namedObjects_.end()) return found->second;
      namedObjects_.emplace(settings->objectName, scene_.objects.size());
      scene_.objects.push_back({settings->objectName, settings->settings, {}, true});
      return scene_.objects.size() - 1;
    }
    scene_.objects.push_back({nodeName, ObjectSettings{}, {}, false});
    return scene_.objects.size() - 1;
  }

  /// Objects and groups need unique names for `--move NAME`: later namesakes get " (2)",
  /// " (3)", …; objects keep their names before groups do.
  void reportDuplicateNames() {
    std::erase_if(scene_.groups, [](const SceneGroup& g) { return g.objects.empty(); });
    std::map<std::string, int> seen;
    auto number = [&](std::string& name, std::size_t& renamed, std::string& names) {
      for (int n = ++seen[name]; n > 1; n = ++seen[name]) {
        const std::string numberedName = name + " (" + std::to_string(n) + ")";
        if (seen.count(numberedName) == 0) {
          name = numberedName;
          ++seen[name];
          if (++renamed <= 5) names += (renamed > 1 ? ", '" : "'") + name + "'";
          return;
        }
      }
    };
    auto warn = [&](std::size_t renamed, const std::string& names, const char* what) {
      if (renamed == 0) return;
      scene_.warnings.push_back(file_ + ": " + std::to_string(renamed) + what + names +
                                (renamed > 5 ? ", ..." : ""));
    };
    std::size_t renamed = 0;
    std::string names;
    for (SceneObject& object : scene_.objects) number(object.name, renamed, names);
    warn(renamed, names, " objects share a name with an earlier one and were numbered: ");
    renamed = 0;
    names.clear();
    for (SceneGroup& group : scene_.groups) number(group.name, renamed, names);
    warn(renamed, names, " groups share a name with an object or an earlier group and were numbered: ");
  }

  void reportTopology(const SceneObject& object) {
    for (const Part& part : object.parts) {
      const MeshTopology& t = part.topology;
      const std::string where = file_ + ": object " + quoted(object.name) + " part " + quoted(part.name);
      if (!t.closed()) {
        const glm::vec3 p = t.firstOpenEdgeWorld.value_or(glm::vec3(0.0f));
        std::ostringstream s;
        s << where << " is open: " << t.boundaryEdges << " boundary and " << t.nonManifoldEdges
          << " non-manifold edges, the first near (" << p.x << ", " << p.y << ", " << p.z << ") m";
        scene_.warnings.push_back(s.str());
      }
      if (!t.consistentlyOriented()) {
        scene_.warnings.push_back(where + " is not consistently oriented: " +
                                  std::to_string(t.misorientedEdges) + " edges join flipped triangles");
      }
    }
  }

  const tinygltf::Model& model_;
  std::string file_;
  AccessorReader reader_;
  const ProgressFn& progress_;
  Scene scene_;
  std::vector<bool> visited_;
  std::size_t nodesDone_ = 0;
  std::map<std::string, std::size_t> namedObjects_;
  std::vector<std::size_t> objectOfPart_;  // per part placed, in node order, its object's index
};

}  // namespace

Scene loadGltfScene(const fs::path& file, const ProgressFn& progress) {
  const std::string fileName = file.string();
  std::string readError;
  const std::vector<unsigned char> bytes = readRegularFile(file, readError);
  if (!readError.empty()) throw Error(fileName + ": " + readError);
  if (bytes.empty()) throw Error(fileName + ": the file is empty");

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&skipImage, nullptr);
  std::string baseDir = file.parent_path().string();
  loader.SetFsCallbacks({&fileExists, &expandFilePath, &readWholeFile, &writeWholeFile, &baseDir});
  tinygltf::Model model;
  std::string err;
  std::string warn;
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  bool ok = false;
  auto checkJsonDepth = [&](const unsigned char* json, std::size_t size) {
    if (jsonNestingDepth(json, size) > kMaxJsonDepth) {
      throw Error(fileName + ": JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    }
  };
  if (binary) {
    const std::string containerError = glbContainerError(bytes);
    if (!containerError.empty()) throw Error(fileName + ": " + containerError);
    checkJsonDepth(bytes.data() + 20, readU32(bytes, 12));
    ok = loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(),
                                     static_cast<unsigned int>(bytes.size()), baseDir);
  } else {
    std::size_t first = bytes.size() >= 3 && std::memcmp(bytes.data(), "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;
    while (first < bytes.size() && std::isspace(bytes[first])) ++first;
    const bool looksLikeJson = first < bytes.size() && bytes[first] == '{';
    if (!looksLikeJson) {
      throw Error(fileName + ": not a glTF file (neither a GLB header nor a JSON object)");
    }
    checkJsonDepth(bytes.data(), bytes.size());
    ok = loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                    static_cast<unsigned int>(bytes.size()), baseDir);
  }
  if (!ok) {
    throw Error(fileName + ": not valid glTF" + std::string(binary ? " binary" : "") + ": " +
                oneLine(err.empty() ? std::string("unknown tinygltf error") : err));
  }
  SceneBuilder builder(model, fileName, progress);
  Scene scene = builder.build();
  if (!warn.empty()) scene.warnings.insert(scene.warnings.begin(), fileName + ": " + oneLine(warn));
  return scene;
}

}  // namespace voxhap

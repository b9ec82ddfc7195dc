#pragma once
/// Test support: writes small glTF files, good and bad, into a per-test directory.
///
/// A `GltfDoc` is a glTF document under construction: its JSON plus the bytes of
/// its one binary buffer. Tests add meshes and nodes through the helpers, then
/// write the document as `.gltf` with an embedded data: URI, as `.gltf` with an
/// external `.bin`, or as `.glb`. A mutator runs on the finished JSON just before
/// it is written, and the GLB packer works on raw bytes, so a test can corrupt any
/// field, length or byte it wants.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>

namespace voxhap::test {

/// A fresh, empty directory under the system temp directory, named after the
/// running GoogleTest test; removed with everything in it on destruction.
class TempDir {
public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
  std::filesystem::path path_;
};

/// A small triangle mesh as written into a file: float positions and flat indices.
struct MeshData {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;  ///< three per triangle, CCW seen from outside

  std::size_t triangleCount() const { return indices.size() / 3; }
};

/// The unit cube [0,1]³: 8 vertices, 12 triangles, closed, CCW seen from outside.
MeshData unitCube();
/// The corner tetrahedron (0,0,0),(1,0,0),(0,1,0),(0,0,1): closed, outward, volume 1/6.
MeshData tetrahedron();

// glTF constants, spelt out so tests read like the spec
inline constexpr int kUnsignedByte = 5121;
inline constexpr int kUnsignedShort = 5123;
inline constexpr int kUnsignedInt = 5125;
inline constexpr int kFloat = 5126;
inline constexpr int kModePoints = 0;
inline constexpr int kModeLines = 1;
inline constexpr int kModeTriangles = 4;
inline constexpr int kModeTriangleStrip = 5;
inline constexpr int kModeTriangleFan = 6;

/// A glTF 2.0 document under construction: JSON and the bytes of buffer 0.
struct GltfDoc {
  nlohmann::json json;             ///< everything but "buffers" (added when written)
  std::vector<unsigned char> bin;  ///< buffer 0; every view starts 4-byte aligned

  GltfDoc();

  /// Appends `bytes` to the buffer (zero-padded to 4 bytes) and adds a bufferView
  /// on them; returns the view's index. `byteStride` 0 leaves it out.
  int addBufferView(const void* data, std::size_t bytes, std::size_t byteStride = 0);
  /// Adds an accessor on `bufferView`; returns its index.
  int addAccessor(int bufferView, int componentType, std::uint64_t count, const std::string& type,
                  std::size_t byteOffset = 0);
  /// Float VEC3 positions (view + accessor with min/max); returns the accessor index.
  int addPositions(const std::vector<glm::vec3>& positions);
  /// Scalar indices stored as `componentType` (5121, 5123 or 5125); returns the accessor.
  int addIndices(const std::vector<std::uint32_t>& indices, int componentType = kUnsignedInt);
  /// A material with this baseColorFactor; returns its index.
  int addMaterial(const glm::vec4& baseColor, const std::string& name = "");
  /// A mesh of one primitive; `indices` / `material` < 0 leave them out. Returns the mesh.
  int addMesh(int positionsAccessor, int indicesAccessor, int mode = kModeTriangles, int material = -1);
  /// A mesh of one indexed TRIANGLES primitive made from `mesh`; returns the mesh index.
  int addMesh(const MeshData& mesh, int material = -1, int indexType = kUnsignedInt);
  /// Adds a node (any JSON object) and returns its index; it is not put in the scene.
  int addNode(nlohmann::json node);
  /// Adds a node `{"name": name, "mesh": mesh}` (no name when empty) and puts it in the scene.
  int addMeshNode(int mesh, const std::string& name);
  /// Puts an existing node into scene 0's root list.
  void addRoot(int node);
  /// Makes `child` a child of `parent`.
  void addChild(int parent, int child);
  /// The JSON of node `index`, to edit.
  nlohmann::json& node(int index);
  /// The index of the first node named `name`; throws std::out_of_range when there is none.
  int nodeNamed(const std::string& name) const;
};

/// A document with one root node `name` holding `mesh` (one TRIANGLES primitive).
GltfDoc singleMeshDoc(const MeshData& mesh, const std::string& name = "cube", int material = -1);

/// A CAD assembly untouched by Voxhap (no extras anywhere), in metres: a group node
/// "piston" (no mesh) holding the mesh nodes "crown" (a 10 mm cube, red, from (0, 0, 12) mm)
/// and "pin" (a 4 mm cube, blue, 1 mm beside the crown, from (11, 3, 15) mm), and a root mesh
/// node "block" (30 × 30 × 10 mm, grey, from (−10, −10, 0) mm), 2 mm below them.
GltfDoc pistonAssemblyDoc();

/// `{"voxhap": {...}}` as node extras.
nlohmann::json voxhapExtras(const nlohmann::json& settings);

/// How buffer 0 is stored.
enum class BufferStorage {
  DataUri,   ///< .gltf with a base64 data: URI
  External,  ///< .gltf next to `<stem>.bin`
  Glb,       ///< .glb with a BIN chunk
};

using JsonMutator = std::function<void(nlohmann::json&)>;

/// The finished JSON of `doc` with "buffers" filled in for `storage` (`binUri` names
/// the external file).
nlohmann::json finishedJson(const GltfDoc& doc, BufferStorage storage, const std::string& binUri = "");

/// Writes `doc` into `dir` as `<stem>.gltf` (+ `<stem>.bin`) or `<stem>.glb`, after
/// running `mutate` on the finished JSON; returns the path of the main file.
std::filesystem::path writeDoc(const GltfDoc& doc, const std::filesystem::path& dir, const std::string& stem,
                               BufferStorage storage, const JsonMutator& mutate = {});

/// Packs a GLB: 12-byte header, JSON chunk padded with spaces, BIN chunk (left out
/// when `bin` is empty) padded with zeros. Every length is the honest one.
std::vector<unsigned char> packGlb(const std::string& jsonText, const std::vector<unsigned char>& bin);

/// Byte offsets inside a GLB made by packGlb, for corrupting it.
struct GlbLayout {
  static constexpr std::size_t kTotalLengthOffset = 8;
  static constexpr std::size_t kJsonChunkLengthOffset = 12;
  static constexpr std::size_t kJsonChunkDataOffset = 20;
  std::size_t binChunkLengthOffset = 0;  ///< 0 when there is no BIN chunk
  std::size_t binChunkDataOffset = 0;
};
GlbLayout glbLayout(const std::vector<unsigned char>& glb);

/// Little-endian 32-bit store and load at `offset`.
void putU32(std::vector<unsigned char>& bytes, std::size_t offset, std::uint32_t value);
std::uint32_t getU32(const std::vector<unsigned char>& bytes, std::size_t offset);

/// Standard base64 with padding.
std::string base64(const std::vector<unsigned char>& bytes);

/// `prefix` followed by `n` ("level " and 3 → "level 3"). Built by appending, because
/// GCC 12 at -O3 warns falsely (-Wrestrict) on `"literal" + std::to_string(n)`.
std::string numbered(const std::string& prefix, std::uint64_t n);

/// Writes bytes (or text) to `file`, replacing it.
void writeBytes(const std::filesystem::path& file, const std::vector<unsigned char>& bytes);
void writeText(const std::filesystem::path& file, const std::string& text);
std::vector<unsigned char> readBytes(const std::filesystem::path& file);

}  // namespace voxhap::test

// readable GoogleTest failure messages for glm vectors
namespace glm {
template <length_t N, typename T, qualifier Q>
void PrintTo(const vec<N, T, Q>& v, std::ostream* os) {
  *os << "(";
  for (length_t k = 0; k < N; ++k) *os << (k ? ", " : "") << +v[k];
  *os << ")";
}
}  // namespace glm

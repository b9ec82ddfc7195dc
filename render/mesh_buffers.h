#pragma once
/// GPU buffers of one scene object: every part's vertices and triangles in one vertex
/// array, uploaded once at construction (positions, per-vertex normals, uint32 indices);
/// nothing of the static data is copied again per frame.
///
/// Vertices keep the scene's order: the parts in order, each part's vertices in order,
/// which is the order of `updateColours` (the moving objects' proximity colours, the only
/// stream updated per frame). Positions stay in the scene-placement frame; a pose moves
/// the object through the shader's model matrix. Needs a current GL context throughout.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "haptics/scene/scene.h"
#include "render/proximity_ramp.h"

namespace voxhap::render {

/// Where one part lies in the buffers.
struct PartRange {
  std::uint32_t firstIndex = 0;   ///< into the index buffer
  std::uint32_t indexCount = 0;   ///< 3 per triangle
  std::uint32_t firstVertex = 0;  ///< into the vertex streams
  std::uint32_t vertexCount = 0;
  glm::vec4 baseColor{1.0f};  ///< linear RGBA, the part's
  /// Closed and consistently oriented: back faces can be culled.
  bool closed = false;
};

/// The vertex array of one SceneObject. Move-only; frees its GL objects with it.
class MeshBuffers {
public:
  /// Uploads `object`'s parts; `withColourStream` adds a per-vertex RGBA8 stream (for
  /// proximity colours), initialised to each part's base colour. Throws voxhap::Error when
  /// the object has more than 2^32 - 1 vertices or GL runs out of memory.
  MeshBuffers(const SceneObject& object, bool withColourStream);
  ~MeshBuffers();
  MeshBuffers(MeshBuffers&& other) noexcept;
  MeshBuffers& operator=(MeshBuffers&&) = delete;
  MeshBuffers(const MeshBuffers&) = delete;
  MeshBuffers& operator=(const MeshBuffers&) = delete;

  std::uint32_t vertexCount() const { return vertexCount_; }
  std::uint64_t triangleCount() const { return indexCount_ / 3; }
  const std::vector<PartRange>& parts() const { return parts_; }
  bool hasColourStream() const { return colours_ != 0; }

  /// Replaces the colour stream: one colour per vertex in the scene's order. Throws
  /// voxhap::Error when there is no stream or the count is not vertexCount().
  void updateColours(std::span<const Rgba8> colourPerVertex);

  /// Binds the vertex array (for drawPart).
  void bind() const;
  /// Draws one part's triangles; the vertex array must be bound.
  void drawPart(std::size_t partIndex) const;

private:
  std::uint32_t vao_ = 0;
  std::uint32_t positions_ = 0;
  std::uint32_t normals_ = 0;
  std::uint32_t colours_ = 0;
  std::uint32_t indices_ = 0;
  std::uint32_t vertexCount_ = 0;
  std::uint64_t indexCount_ = 0;
  std::vector<PartRange> parts_;
};

/// Area-weighted vertex normals of a mesh (unit; +z for a vertex no triangle uses).
std::vector<glm::vec3> vertexNormals(const TriangleMesh& mesh);

}  // namespace voxhap::render

#include "render/mesh_buffers.h"

#include <limits>
#include <string>
#include <utility>

#include <epoxy/gl.h>
#include <glm/geometric.hpp>

#include "haptics/core/error.h"
#include "render/gl_check.h"
#include "render/shaders.h"

namespace voxhap::render {
namespace {

template <typename T>
GLsizeiptr bytesOf(std::size_t count) {
  return static_cast<GLsizeiptr>(count * sizeof(T));
}
template <typename T>
GLintptr offsetOf(std::size_t count) {
  return static_cast<GLintptr>(count * sizeof(T));
}

}  // namespace

std::vector<glm::vec3> vertexNormals(const TriangleMesh& mesh) {
  std::vector<glm::dvec3> sum(mesh.positionsWorld.size(), glm::dvec3(0.0));
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 a(mesh.positionsWorld[t.x]);
    // the cross product's length is twice the area: larger faces weigh more
    const glm::dvec3 n =
        glm::cross(glm::dvec3(mesh.positionsWorld[t.y]) - a, glm::dvec3(mesh.positionsWorld[t.z]) - a);
    sum[t.x] += n;
    sum[t.y] += n;
    sum[t.z] += n;
  }
  std::vector<glm::vec3> normals(sum.size());
  for (std::size_t i = 0; i < sum.size(); ++i) {
    const double length = glm::length(sum[i]);
    normals[i] = length > 0.0 ? glm::vec3(sum[i] / length) : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  return normals;
}

MeshBuffers::MeshBuffers(const SceneObject& object, bool withColourStream) {
  std::uint64_t vertices = 0;
  for (const Part& part : object.parts) {
    PartRange range;
    range.firstVertex = static_cast<std::uint32_t>(vertices);
    range.firstIndex = static_cast<std::uint32_t>(indexCount_);
    range.vertexCount = static_cast<std::uint32_t>(part.mesh.positionsWorld.size());
    range.indexCount = static_cast<std::uint32_t>(part.mesh.triangles.size() * 3);
    range.baseColor = part.baseColor;
    range.closed = part.topology.closed() && part.topology.consistentlyOriented();
    vertices += part.mesh.positionsWorld.size();
    indexCount_ += part.mesh.triangles.size() * 3;
    if (vertices >= std::numeric_limits<std::uint32_t>::max() ||
        indexCount_ >= std::numeric_limits<std::uint32_t>::max()) {
      throw Error("object " + object.name + ": too many vertices or triangles for 32-bit indices");
    }
    parts_.push_back(range);
  }
  vertexCount_ = static_cast<std::uint32_t>(vertices);

  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  glGenBuffers(1, &positions_);
  glGenBuffers(1, &normals_);
  glGenBuffers(1, &indices_);

  // allocate once, then fill part by part: only one part's normals live on the CPU at a time
  glBindBuffer(GL_ARRAY_BUFFER, positions_);
  glBufferData(GL_ARRAY_BUFFER, bytesOf<glm::vec3>(vertexCount_), nullptr, GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, normals_);
  glBufferData(GL_ARRAY_BUFFER, bytesOf<glm::vec3>(vertexCount_), nullptr, GL_STATIC_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, bytesOf<std::uint32_t>(indexCount_), nullptr, GL_STATIC_DRAW);
  std::vector<glm::uvec3> shifted;
  for (std::size_t p = 0; p < object.parts.size(); ++p) {
    const TriangleMesh& mesh = object.parts[p].mesh;
    const PartRange& range = parts_[p];
    if (range.vertexCount == 0) continue;
    glBindBuffer(GL_ARRAY_BUFFER, positions_);
    glBufferSubData(GL_ARRAY_BUFFER, offsetOf<glm::vec3>(range.firstVertex),
                    bytesOf<glm::vec3>(range.vertexCount), mesh.positionsWorld.data());
    const std::vector<glm::vec3> normals = vertexNormals(mesh);
    glBindBuffer(GL_ARRAY_BUFFER, normals_);
    glBufferSubData(GL_ARRAY_BUFFER, offsetOf<glm::vec3>(range.firstVertex),
                    bytesOf<glm::vec3>(range.vertexCount), normals.data());
    shifted.resize(mesh.triangles.size());
    for (std::size_t t = 0; t < shifted.size(); ++t) shifted[t] = mesh.triangles[t] + range.firstVertex;
    glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, offsetOf<std::uint32_t>(range.firstIndex),
                    bytesOf<glm::uvec3>(shifted.size()), shifted.data());
  }
  glBindBuffer(GL_ARRAY_BUFFER, positions_);
  glEnableVertexAttribArray(kPositionAttribute);
  glVertexAttribPointer(kPositionAttribute, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, normals_);
  glEnableVertexAttribArray(kNormalAttribute);
  glVertexAttribPointer(kNormalAttribute, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);

  if (withColourStream) {
    std::vector<Rgba8> colours(vertexCount_);
    for (const PartRange& range : parts_) {
      const Rgba8 c = toRgba8(range.baseColor);
      for (std::uint32_t v = 0; v < range.vertexCount; ++v) colours[range.firstVertex + v] = c;
    }
    glGenBuffers(1, &colours_);
    glBindBuffer(GL_ARRAY_BUFFER, colours_);
    glBufferData(GL_ARRAY_BUFFER, bytesOf<Rgba8>(colours.size()), colours.data(), GL_DYNAMIC_DRAW);
    glEnableVertexAttribArray(kColourAttribute);
    glVertexAttribPointer(kColourAttribute, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(Rgba8), nullptr);
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  throwOnGlError(("uploading object " + object.name).c_str());
}

MeshBuffers::~MeshBuffers() {
  if (vao_ == 0) return;
  const GLuint buffers[] = {positions_, normals_, colours_, indices_};
  glDeleteBuffers(4, buffers);  // zero names are ignored
  glDeleteVertexArrays(1, &vao_);
}

MeshBuffers::MeshBuffers(MeshBuffers&& other) noexcept
    : vao_(std::exchange(other.vao_, 0)),
      positions_(std::exchange(other.positions_, 0)),
      normals_(std::exchange(other.normals_, 0)),
      colours_(std::exchange(other.colours_, 0)),
      indices_(std::exchange(other.indices_, 0)),
      vertexCount_(other.vertexCount_),
      indexCount_(other.indexCount_),
      parts_(std::move(other.parts_)) {}

void MeshBuffers::updateColours(std::span<const Rgba8> colourPerVertex) {
  if (colours_ == 0) throw Error("these mesh buffers have no colour stream");
  if (colourPerVertex.size() != vertexCount_) {
    throw Error("colour stream: " + std::to_string(colourPerVertex.size()) + " colours for " +
                std::to_string(vertexCount_) + " vertices");
  }
  glBindBuffer(GL_ARRAY_BUFFER, colours_);
  // orphan the old storage so that the driver need not wait for frames still reading it
  glBufferData(GL_ARRAY_BUFFER, bytesOf<Rgba8>(vertexCount_), nullptr, GL_DYNAMIC_DRAW);
  glBufferSubData(GL_ARRAY_BUFFER, 0, bytesOf<Rgba8>(vertexCount_), colourPerVertex.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void MeshBuffers::bind() const {
  glBindVertexArray(vao_);
}

void MeshBuffers::drawPart(std::size_t partIndex) const {
  const PartRange& range = parts_[partIndex];
  if (range.indexCount == 0) return;
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(range.indexCount), GL_UNSIGNED_INT,
                 reinterpret_cast<const void*>(offsetOf<std::uint32_t>(range.firstIndex)));
}

}  // namespace voxhap::render

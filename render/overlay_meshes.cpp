#include "render/overlay_meshes.h"

#include <array>

#include <epoxy/gl.h>
#include <glm/mat4x4.hpp>

#include "haptics/geometry/mesh_builder.h"
#include "render/gl_check.h"
#include "render/shaders.h"

namespace voxhap::render {

InstancedCubes::InstancedCubes() {
  constexpr std::array<glm::vec3, 8> kCorners = {{{-0.5f, -0.5f, -0.5f},
                                                  {0.5f, -0.5f, -0.5f},
                                                  {0.5f, 0.5f, -0.5f},
                                                  {-0.5f, 0.5f, -0.5f},
                                                  {-0.5f, -0.5f, 0.5f},
                                                  {0.5f, -0.5f, 0.5f},
                                                  {0.5f, 0.5f, 0.5f},
                                                  {-0.5f, 0.5f, 0.5f}}};
  constexpr std::array<std::uint32_t, 36> kTriangles = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                                        1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  glGenBuffers(1, &cubeVertices_);
  glBindBuffer(GL_ARRAY_BUFFER, cubeVertices_);
  glBufferData(GL_ARRAY_BUFFER, sizeof kCorners, kCorners.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(kPositionAttribute);
  glVertexAttribPointer(kPositionAttribute, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
  glGenBuffers(1, &cubeIndices_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, cubeIndices_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof kTriangles, kTriangles.data(), GL_STATIC_DRAW);
  glGenBuffers(1, &centres_);
  glBindBuffer(GL_ARRAY_BUFFER, centres_);
  glEnableVertexAttribArray(kInstanceOffsetAttribute);
  glVertexAttribPointer(kInstanceOffsetAttribute, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
  glVertexAttribDivisor(kInstanceOffsetAttribute, 1);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  throwOnGlError("creating the overlay cubes");
}

InstancedCubes::~InstancedCubes() {
  const GLuint buffers[] = {cubeVertices_, cubeIndices_, centres_};
  glDeleteBuffers(3, buffers);
  glDeleteVertexArrays(1, &vao_);
}

void InstancedCubes::setCentres(std::span<const glm::vec3> centresWorld) {
  count_ = centresWorld.size();
  if (count_ == 0) return;
  glBindBuffer(GL_ARRAY_BUFFER, centres_);
  const auto bytes = static_cast<GLsizeiptr>(count_ * sizeof(glm::vec3));
  if (count_ > capacity_) {
    capacity_ = count_;
    glBufferData(GL_ARRAY_BUFFER, bytes, centresWorld.data(), GL_DYNAMIC_DRAW);
  } else {
    glBufferSubData(GL_ARRAY_BUFFER, 0, bytes, centresWorld.data());
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void InstancedCubes::draw() const {
  if (count_ == 0) return;
  glBindVertexArray(vao_);
  glDrawElementsInstanced(GL_TRIANGLES, 36, GL_UNSIGNED_INT, nullptr, static_cast<GLsizei>(count_));
  glBindVertexArray(0);
}

SceneObject unitArrowObject() {
  // (radius, z) loop, counter-clockwise: shaft to 75 %, then a cone to the tip
  const ProfilePoint profile[] = {{0.0, 0.0}, {0.025, 0.0}, {0.025, 0.75}, {0.07, 0.75}, {0.0, 1.0}};
  TriangleMesh mesh;
  appendLathe(mesh, glm::dmat4(1.0), profile, 24);
  SceneObject arrow;
  arrow.name = "force arrow";
  arrow.parts.push_back(makePart("force arrow", glm::vec4(0.1f, 0.9f, 0.2f, 1.0f), std::move(mesh)));
  return arrow;
}

}  // namespace voxhap::render

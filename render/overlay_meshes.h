#pragma once
/// Geometry of the overlays: instanced cubes (shadow voxels, contact points) and the
/// force arrow's mesh. Needs a current GL context throughout.

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "haptics/scene/scene.h"

namespace voxhap::render {

/// A unit cube (edges 1, centred on the origin) drawn once per centre in one instanced
/// call; centres in the world frame, m. Move-free, not copyable.
class InstancedCubes {
public:
  InstancedCubes();
  ~InstancedCubes();
  InstancedCubes(const InstancedCubes&) = delete;
  InstancedCubes& operator=(const InstancedCubes&) = delete;

  /// Replaces the instances (uploads the centres; the buffer grows as needed).
  void setCentres(std::span<const glm::vec3> centresWorld);
  std::size_t count() const { return count_; }
  /// Draws every instance with the current program (the flat shader).
  void draw() const;

private:
  std::uint32_t vao_ = 0;
  std::uint32_t cubeVertices_ = 0;
  std::uint32_t cubeIndices_ = 0;
  std::uint32_t centres_ = 0;
  std::size_t capacity_ = 0;
  std::size_t count_ = 0;
};

/// An arrow of length 1 along +z from the origin (shaft and cone, closed), as an object
/// of one part for MeshBuffers; the renderer scales and turns it onto the force.
SceneObject unitArrowObject();

}  // namespace voxhap::render

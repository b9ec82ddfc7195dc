#pragma once
/// glTF accessors read with every offset, stride and count checked against the buffers
/// first (a file's numbers are not trusted): positions and indices of a primitive.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <tiny_gltf.h>

namespace voxhap {

/// Reads glTF accessors after checking every offset against the buffers; throws
/// voxhap::Error naming the accessor and what is wrong.
class AccessorReader {
public:
  explicit AccessorReader(const tinygltf::Model& model) : model_(model) {}

  /// Float VEC3 positions, every one finite.
  std::vector<glm::vec3> positions(int accessorIndex, const std::string& where) const;

  /// Unsigned scalar indices, each below `vertexCount`.
  std::vector<std::uint32_t> indices(int accessorIndex, std::size_t vertexCount,
                                     const std::string& where) const;

private:
  struct View {
    const tinygltf::Accessor* accessor;
    const unsigned char* data;  // first element
    std::size_t stride;         // bytes between elements
    std::string where;
  };

  View check(int accessorIndex, const std::string& what) const;

  const tinygltf::Model& model_;
};

}  // namespace voxhap

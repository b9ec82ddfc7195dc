#pragma once
/// Inside or outside, for voxels that no surface passes through (DESIGN §4.2 step 3).
///
/// Rays run along every row of voxel centres parallel to x, to y and to z (Embree,
/// all crossings). Along a row a point is inside a part after an odd number of that
/// part's crossings, and inside the object when inside any part, so overlapping parts
/// are fine. Each voxel gets three votes; two or more say inside. A small hole in a
/// CAD mesh spoils the rows through it along one axis only, and is outvoted; voxels
/// where the votes differ are counted and one is reported.
///
/// Rays are offset inside the voxel from the centre row by a fixed fraction so that
/// they do not graze axis-aligned CAD edges; for a voxel no surface passes through
/// every point has the same inside-ness, so the offset does not change the answer.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec2.hpp>

#include "haptics/scene/scene.h"
#include "haptics/voxel/voxel_grid.h"

namespace voxhap {

class EmbreeScene;

class InteriorClassifier {
public:
  /// Casts all rows that meet the meshes' bounds (`threads` threads, 0: all cores).
  InteriorClassifier(const VoxelGrid& grid, std::span<const TriangleMesh* const> meshes,
                     const EmbreeScene& scene, int threads);

  /// Votes (0 … 3) that each voxel of the box [lo, lo + size) is inside, x fastest.
  void votes(const glm::ivec3& lo, const glm::ivec3& size, std::vector<std::uint8_t>& out) const;

  /// Number of parts the crossings refer to.
  std::size_t partCount() const { return partCount_; }

private:
  struct Crossing {
    float tVoxels;  // along the row, in voxels from the grid's origin
    std::uint32_t part;
  };
  /// Crossings of every row parallel to one axis, sorted along each row.
  struct AxisRows {
    int axis = 0;
    glm::ivec2 lo{0};                  // first row's coordinates along the two other axes
    glm::ivec2 size{0};                // rows cast along the two other axes (the meshes' bounds)
    std::vector<std::uint32_t> begin;  // per row, index of its first crossing; one more at the end
    std::vector<Crossing> crossings;
  };

  AxisRows castRows(int axis, std::span<const TriangleMesh* const> meshes, const EmbreeScene& scene,
                    const glm::ivec3& boundsLo, const glm::ivec3& boundsHi, int threads) const;
  /// Adds 1 to `out[i]` for each voxel i of the box that the row pass along `rows.axis` finds inside.
  void addVotes(const AxisRows& rows, const glm::ivec3& lo, const glm::ivec3& size,
                std::vector<std::uint8_t>& out) const;

  VoxelGrid grid_;
  std::size_t partCount_ = 0;
  AxisRows rows_[3];
};

}  // namespace voxhap

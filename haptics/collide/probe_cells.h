#pragma once
/// The surface probes of one body (surface_probes.h), grouped for culling: space is cut
/// into cubic cells of `cellSizeM` on a lattice anchored at the body's local origin, and
/// cells into blocks of kCellsPerBlockEdge³ cells. A cell holds the probes that fall in
/// it (its vertex and edge probes first), with their bounding sphere; a block holds its
/// non-empty cells, with the sphere around theirs. Exact duplicates (shared edges and
/// vertices) are kept once.
///
/// Whole: every block is built at construction (a small surface: a moving object).
/// On demand: a block is built the first time it is asked for, from the triangles that
/// come within its circumscribed sphere (an Embree query), each clipped to the block's
/// box; it stays cached until clear() (a large surface, such as a static scene of
/// millions of triangles, of which a measurement only needs what lies near the other
/// body). Either way a block's probes are the same, bit for bit: what is cached changes
/// the speed, never the answer.
///
/// Load time and measurement time, one thread at a time; allocates.

#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

#include "haptics/collide/surface_probes.h"
#include "haptics/geometry/embree_scene.h"
#include "haptics/scene/scene.h"

namespace voxhap {

/// Cells along a block's edge.
inline constexpr int kCellsPerBlockEdge = 8;

/// A cell: probes [first, first + count), of which [first, first + edgeCount) lie on
/// edges or at vertices.
struct ProbeCell {
  glm::dvec3 centreLocal{0.0};  ///< centre of the bounding sphere of its probes, local frame, m
  double radiusM = 0.0;         ///< of that sphere
  std::uint32_t first = 0;
  std::uint32_t edgeCount = 0;
  std::uint32_t count = 0;
};

/// A block: cells [firstCell, firstCell + cellCount).
struct ProbeBlock {
  glm::dvec3 centreLocal{0.0};  ///< centre of a sphere holding every probe of the block, local frame, m
  double radiusM = 0.0;         ///< of that sphere
  std::uint32_t firstCell = 0;
  std::uint32_t cellCount = 0;
};

class ProbeCells {
public:
  /// Probes of `meshes` (the body's local frame; kept by reference, with `scene`, built
  /// from the same span: both must outlive this) at `spacingM`, in cells of `cellSizeM`
  /// (> 0); all built now when `whole`, else on demand.
  ProbeCells(std::span<const TriangleMesh* const> meshes, const EmbreeScene& scene, double spacingM,
             double cellSizeM, bool whole);

  bool whole() const { return whole_; }
  double spacingM() const { return spacingM_; }
  double cellSizeM() const { return cellSizeM_; }
  double blockSizeM() const { return cellSizeM_ * kCellsPerBlockEdge; }

  /// Every block (whole), or the blocks built so far (on demand), in key order when whole.
  std::span<const ProbeBlock> blocks() const { return blocks_; }
  const ProbeCell& cell(std::uint32_t index) const { return cells_[index]; }
  const glm::vec3& probeLocal(std::uint32_t index) const { return probes_[index]; }
  /// Probes held now.
  std::size_t probeCount() const { return probes_.size(); }

  /// The key of the block holding `pointLocal`.
  std::uint64_t blockKeyOf(const glm::dvec3& pointLocal) const;
  /// Keys of the blocks that meet the box [minLocal, maxLocal], appended to `out`.
  void blockKeysIn(const glm::dvec3& minLocal, const glm::dvec3& maxLocal,
                   std::vector<std::uint64_t>& out) const;
  /// The block of `key` (on demand: built now if need be); none when no probe lies in it.
  std::optional<ProbeBlock> block(std::uint64_t key);

  /// On demand: forgets every block built (whole: nothing happens).
  void clear();

private:
  /// A probe with the keys it sorts by.
  struct KeyedProbe {
    std::uint64_t block;
    std::uint32_t cellInBlock;
    SurfaceProbe probe;
  };
  KeyedProbe keyed(const SurfaceProbe& probe) const;
  /// Sorts `probes` (all of one block), drops exact duplicates, appends their cells and
  /// block to the arrays; returns the block's index in blocks_, or −1 when it is empty.
  std::int64_t addBlock(std::span<KeyedProbe> probes);

  std::vector<const TriangleMesh*> meshes_;
  const EmbreeScene* scene_;
  double spacingM_;
  double cellSizeM_;
  bool whole_;
  std::vector<glm::vec3> probes_;
  std::vector<ProbeCell> cells_;
  std::vector<ProbeBlock> blocks_;
  std::unordered_map<std::uint64_t, std::int64_t> blockIndex_;  // on demand: key → index in blocks_ or −1
  std::vector<TriangleRef> triangles_;                          // scratch
};

}  // namespace voxhap

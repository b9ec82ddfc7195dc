#pragma once
/// Time-critical sampling of one pair (paper §5, DESIGN §4.5): which of the pointshell's
/// points and chunks to test this frame, and where each goes after its test.
///
/// Points. Every point of a chunk in range sits in one distance-to-contact queue
/// (max_travel.h); queues 0 and 1 are tested every frame, queue i ≥ 2 within d_i = i − 1
/// voxels of relative travel, by sweeps (swept_queues.h). By the paper's quota alone a
/// point waits while others join the queue ahead of the cursor: in a random-motion test
/// one waited 6 frames where its 2 voxels allowed 4 and was found in contact untested.
/// The sweeps cover the pointshell's blocks at the rate the travel asks instead, which
/// bounds every wait; Eq. 2 plans with what they will take (max_travel.h).
///
/// Chunks (paper §5.1). A chunk of the pointshell (its points have contiguous indices)
/// whose centroid lies at chunk distance D from the voxel-bearing chunks of the voxmap
/// (Voxmap::chunkDistance) has every point at least gap = (D − 1)·C − ρ from them (C the
/// voxmap's chunk edge, ρ the chunk's radius about its centroid): all its points read far.
/// A chunk whose gap is at least 3C leaves the point queues (collapsed) and is tracked in
/// chunk queue j = floor(gap / C), retested within (j − 1)·C of travel; one whose gap falls
/// under 2C is disgorged: its points go to the far queue, which is exact for them. Chunk
/// queue 1 (must test now) is mandatory; chunks in range (queue 0) are retested once per
/// C of travel, to see whether they may collapse.
///
/// Point drifting (paper §5.2). A test that reads the voxmap (a lookup) stores where the
/// point was, in voxel coordinates, and the queue it found. A later test of a point in
/// queue ≥ 2 first measures its drift δ (voxels) from there: while the i₀ − 1 − δ voxels
/// still guaranteed from the lookup's queue i₀ are at least two (two queues of margin,
/// as the paper keeps), it skips the lookup and at most lowers the point's queue to
/// floor(i₀ − 1 − δ) + 1; otherwise it looks up again. Points of a disgorged chunk have
/// no lookup and get one at their first test.
///
/// Out of range (the pointshell wholly outside the voxmap's grid) every chunk waits in
/// chunk queue 1 for its test in the first frame back in range; the grid's padding keeps
/// its points far until then.
///
/// Built once per pair (allocates); the frame calls are noexcept and allocation-free.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "haptics/coherence/max_travel.h"
#include "haptics/coherence/swept_queues.h"
#include "haptics/collide/point_sampler.h"
#include "haptics/voxel/voxel_pager.h"

namespace voxhap {

/// What a pair's coherence asks of Eq. 2 this frame.
struct CoherenceLoad {
  std::uint32_t mandatory = 0;  ///< points and chunks tested whatever the travel
  TestsByTravel tests{};        ///< other tests at each travel scale (max_travel.h)
};

class FrameHelper;

class PairCoherence {
public:
  /// testDue hands half its points to a frame helper from this many on (fewer would not
  /// repay the hand-over).
  static constexpr std::uint32_t kHelpedTests = 1024;

  /// For `shell` against voxels of size `voxelSizeM` whose largest value is `maxValue`,
  /// with force layer `forceLayer`; `drifting` turns point drifting on.
  PairCoherence(const Pointshell& shell, double voxelSizeM, std::uint8_t forceLayer, std::uint8_t maxValue,
                bool drifting);

  const PointQueues& queues() const noexcept { return points_.queues(); }
  const PointQueues& chunkQueues() const noexcept { return chunks_.queues(); }
  std::uint8_t forceLayer() const noexcept { return forceLayer_; }

  /// Tests every chunk and every point of the chunks in range and queues them (load
  /// time); with a `pager` (paged voxmap, else null) it first makes their voxels resident.
  void sortAll(const Pointshell& shell, const Voxmap& voxmap, const VoxelTransform& transform,
               const std::array<std::uint8_t, 3>& fieldShifts, VoxelPager* pager);
  /// A frame out of range in which the pair may move `relativeTravelM`.
  void skipFrame(double relativeTravelM) noexcept;
  /// Makes every point in range mandatory, to be re-sorted by its next test.
  void setForceLayer(std::uint8_t forceLayer) noexcept;

  /// What the queues ask of Eq. 2 now: this frame's mandatory tests, and the next frame's
  /// sweeps if this one allows a relative travel of up to `fullTravelM`.
  CoherenceLoad load(double fullTravelM) const noexcept;
  /// Whether every chunk is collapsed: no point can reach contact before its chunk has
  /// been disgorged, so the pair allows half a chunk of travel per frame (a collapsed
  /// chunk is retested while it is still that far from being disgorged).
  bool onlyCollapsed() const noexcept;

  /// Tests the due chunks (due by the travel of the frame before, endFrame()); disgorges
  /// and collapses chunks. `scratch` has room for the chunk count. A disgorged chunk asks
  /// `pager` (null: the voxmap is whole) for the voxmap chunks around it (paper §5.3).
  /// Returns the chunk tests.
  std::uint32_t updateChunks(const Pointshell& shell, const Voxmap& voxmap, const VoxelTransform& transform,
                             std::span<std::uint32_t> scratch, VoxelPager* pager) noexcept;

  /// Collects the due points into `due` (room for the pointshell); returns how many.
  std::uint32_t collectDue(std::span<std::uint32_t> due) noexcept;

  /// What testDue() did.
  struct Tested {
    std::uint32_t contacts = 0;           ///< written to `contacts`
    std::uint32_t drifted = 0;            ///< tests that skipped the lookup
    std::uint32_t missing = 0;            ///< lookups of paged-out chunks (the frame must be suspended)
    glm::ivec3 lastAskedChunk{-1 << 30};  ///< the voxmap chunk last asked for
  };
  /// Tests the points collectDue() returned; writes those whose value lies in
  /// [1, sampledLayer] to `contacts` (room for due.size()), in the order of `due`. A point
  /// whose chunk of the voxmap is paged out becomes mandatory and asks `pager` for it.
  /// With a `helper` (and a whole voxmap: `pager` null) the helper tests the last half of
  /// a frame's points meanwhile; the results are the same bits either way.
  Tested testDue(const Pointshell& shell, const Voxmap& voxmap, const VoxelTransform& transform,
                 const std::array<std::uint8_t, 3>& fieldShifts, std::uint8_t sampledLayer,
                 std::span<const std::uint32_t> due, PointContact* contacts, VoxelPager* pager,
                 FrameHelper* helper = nullptr) noexcept;

  /// Call at the end of a frame in range with the relative travel it allowed: it sets the
  /// next frame's sweeps (swept_queues.h).
  void endFrame(double relativeTravelM) noexcept { lastTravelM_ = relativeTravelM; }

private:
  /// What a test of `chunk` finds with its centroid at `voxelOfCentroid` (voxel coordinates):
  /// 0 (in range) or the whole chunks of its gap, at most the last chunk queue.
  int chunkClass(const Voxmap& voxmap, const glm::vec3& voxelOfCentroid, std::uint32_t chunk) const noexcept;
  /// Moves `chunk` from chunk queue `from` to what its test found, `to`; a disgorged chunk
  /// whose centroid lies at `voxelOfCentroid` asks `pager` for the voxels around it.
  void testChunk(std::uint32_t chunk, int from, int to, const glm::vec3& voxelOfCentroid,
                 VoxelPager* pager) noexcept;
  /// Asks `pager` for the voxmap chunks within `radiusVoxels` of `voxel`.
  static void askAround(VoxelPager* pager, const glm::vec3& voxel, float radiusVoxels) noexcept;
  double chunkDistanceM(int q) const noexcept;
  /// What testShare found in its share of the due points.
  struct Share {
    std::uint32_t contacts = 0;  ///< written from its `contacts`
    std::uint32_t moves = 0;     ///< written to moves_ from its `begin`
    std::uint32_t drifted = 0;   ///< tests that skipped the lookup
  };
  /// testDue's first pass, over `due[begin, end)`: reads and drift, each point's lookup,
  /// its contacts written from `contacts` on and the queue moves it asks for from
  /// moves_[begin] on. It moves no queue and asks no pager, so that two shares may run on
  /// two threads.
  Share testShare(const Pointshell& shell, const Voxmap& voxmap, const VoxelTransform& transform,
                  const std::array<std::uint8_t, 3>& fieldShifts, std::uint8_t sampledLayer,
                  std::span<const std::uint32_t> due, std::uint32_t begin, std::uint32_t end,
                  PointContact* contacts) noexcept;
  /// testDue's second pass over the share that began at `begin`, in order: its queue moves,
  /// and the pager asked for the chunks of the points that missed; adds to `tested`.
  void moveTested(const Pointshell& shell, const VoxelTransform& transform, const Share& share,
                  std::uint32_t begin, VoxelPager* pager, Tested& tested) noexcept;
  double pointDistanceM(int q) const noexcept;

  SweptQueues points_;
  SweptQueues chunks_;
  std::vector<std::uint32_t> chunkBegin_;  // the pointshell's, for disgorging without it
  std::vector<float> chunkRadiusVoxels_;   // per chunk, its points' farthest from the centroid
  double voxelSizeM_;
  std::uint8_t forceLayer_;
  std::uint8_t maxValue_;
  std::vector<std::uint32_t> dueEndByQueue_;  // collectDue's output: queue q's points end here
  bool drifting_;
  std::vector<glm::vec3> lookupVoxel_;     // per point, where its last lookup was (voxel coordinates)
  std::vector<std::uint8_t> lookupQueue_;  // per point, the queue that lookup found; 0: none
  /// A queue move that a test asks for (testShare), made by moveTested.
  struct Move {
    std::uint32_t point;
    std::uint8_t from;
    std::uint8_t to;
    bool missing;  ///< its voxmap chunk was paged out
  };
  std::vector<Move> moves_;   // room for a move per due point
  double lastTravelM_ = 0.0;  // relative travel allowed in the frame before
};

}  // namespace voxhap

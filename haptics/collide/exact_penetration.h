#pragma once
/// Ground-truth penetration between two rigid bodies, for demos, benchmarks and tests
/// (never the 1 kHz frame): how deep either body's surface sits inside the other,
/// measured exactly with Embree on the triangle meshes, faces included.
///
/// Bodies. Each body is a set of closed triangle meshes in its own local frame, placed
/// by a pose at each measurement; a static body is one whose local frame is the world
/// (identity pose). A moving object's meshes as the scene loads them are its local-frame
/// meshes (its local frame is the world frame at load time, DESIGN §3).
///
/// Probes. Each body's surface is sampled by probes (surface_probes.h): every triangle's
/// vertices, edges and interior at `probeSpacingM` (kProbesPerVoxel per voxel of the
/// static scene by default), so that an edge cutting a face between vertices, or the
/// other body's corner poking into a face, is seen. A probe of one body is tested against
/// the other body in that body's frame (both directions): inside when a ray from it
/// crosses some part of the other body an odd number of times (parity per part, so that
/// overlapping parts are fine; three skewed rays vote, two decide); its depth is then its
/// exact distance to the other body's surface (closest point over every part, so that
/// inside overlapping parts a face buried in the other part counts). The measure's depth
/// is the deepest probe's, in either direction.
///
/// A body of at most kMaxPseudoNormalTriangles whose parts are all closed and
/// consistently oriented answers without rays: a probe is inside the part of its nearest
/// surface point exactly when it lies behind that point's angle-weighted pseudo-normal
/// (Bærentzen and Aanæs 2005), and the same query gives its depth. A probe outside that
/// part but within another part's bounding box (overlapping parts) still takes the vote.
/// On mating surfaces, where most probes are near the other surface, this is what keeps
/// a check affordable.
///
/// Which probes. Probing a small body (a moving object) is done once, at construction,
/// in its local frame. A large body (a static scene of millions of triangles) is probed
/// on demand, region by region (blocks of probe cells, probe_cells.h), only where the
/// small body's surface comes near it, and the regions are cached across measurements;
/// the answer does not depend on what is cached. Probes are grouped in cells and blocks
/// with bounding spheres, and whole groups far from the other body are skipped at once.
///
/// Filter. A body may come with a voxmap (its local frame, voxelized from the same meshes,
/// e.g. the static environment's or a moving object's voxmap): a probe of the other body
/// in one of its free-space voxels (value ≥ 3, or far) lies where no surface passes and
/// the voxelizer found outside, so it is outside without rays; one in an interior voxel
/// (value 1) is inside for the same reason and only its depth is measured; only probes in
/// surface voxels (value 2, or a voxel of a paged voxmap that is not resident) take the
/// exact test. The filter is exact as long as the voxelizer's inside/outside votes were (it
/// warns otherwise). Without a voxmap, the body's bounding box filters instead and every
/// probe inside the box takes the exact test: fine for small meshes, slow for large ones.
///
/// Clearance. Probes outside the other body but within a few voxels of it (kClearanceVoxels,
/// or kClearanceVoxels · kProbesPerVoxel · probeSpacingM without a voxmap) give the least
/// exact distance between the surfaces, so that a run without penetration still says how
/// close it came. The least distance between two polyhedral surfaces is reached at a
/// vertex facing a face or between two edges, so only vertex and edge probes (of both
/// bodies) are measured for it: exact for a vertex facing a face, within half the probe
/// spacing between edges. A clearance found below kClearanceResolutionM ends the search.
/// Candidates are measured nearest first, each search no wider than the best so far, and
/// a surface probed whole keeps each probe's last measured distance across measurements:
/// less the most any probe can have moved since (rotation and translation of the pair's
/// relative pose), it is a lower bound that spares the query when it cannot win (as the
/// paper's point drifting, §5.2). That changes the work, never the answer.
///
/// Threads: construction builds Embree scenes and probes (allocates, may throw
/// voxhap::Error); measure() and inside() are for one thread at a time (they reuse
/// buffers and the cache of probes).

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "haptics/dynamics/pose.h"
#include "haptics/scene/scene.h"
#include "haptics/voxel/voxmap.h"

namespace voxhap {

/// One body of an exact measurement. Everything is kept by reference: the meshes and the
/// voxmap must outlive the ExactPenetration built from them.
struct ExactBody {
  /// Closed triangle meshes, the body's local frame (a static body: world), m.
  std::vector<const TriangleMesh*> meshesLocal;
  /// Optional filter: the body's voxmap, its local frame, voxelized from `meshesLocal`;
  /// may be paged. nullptr: the bounding box filters (see the design note).
  const Voxmap* voxmapLocal = nullptr;
};

/// Which surface was found inside which body.
enum class PenetrationDirection : std::uint8_t {
  None,    ///< nothing inside
  AIntoB,  ///< a probe on body A's surface inside body B
  BIntoA,  ///< a probe on body B's surface inside body A
};

/// "none", "a-into-b" or "b-into-a", for reports.
const char* penetrationDirectionName(PenetrationDirection direction);

/// What one measurement found.
struct PenetrationSample {
  /// Deepest probe inside the other body: its exact distance to that body's surface, m
  /// (0: no probe inside).
  double depthM = 0.0;
  /// That probe (on the penetrating surface), world frame, m (meaningful when depthM > 0).
  glm::dvec3 deepestWorld{0.0};
  PenetrationDirection direction = PenetrationDirection::None;  ///< whose probe it is
  std::uint64_t probes = 0;      ///< probes of both surfaces the measurement considered
  std::uint64_t nearProbes = 0;  ///< of which near enough to the other body to be looked at one by one
  std::uint64_t candidates = 0;  ///< of which took the exact inside test (pseudo-normal side or ray vote)
  std::uint64_t inside = 0;  ///< probes found inside the other body (by the exact test or an interior voxel)
  /// Least exact distance from a vertex or edge probe outside the other body to that
  /// body's surface, m, among the probes within the clearance range (infinite when there
  /// are none: the surfaces are further apart than about kClearanceVoxels voxels).
  double clearanceM = std::numeric_limits<double>::infinity();
};

/// Probes within this many voxels (chessboard, in the other body's voxmap) of a surface
/// voxel get their clearance measured exactly.
inline constexpr int kClearanceVoxels = 4;
/// Once the clearance found is this small, m, the rest of the candidates are not measured
/// (they could lower it by no more than that): mating surfaces touch.
inline constexpr double kClearanceResolutionM = 1e-6;
/// The default probe spacing is the static voxel size over this: probes a quarter voxel apart.
inline constexpr int kProbesPerVoxel = 4;
/// A body whose surface takes at most this many probes is probed whole at construction
/// (the smaller body of a pair always is); a larger one on demand.
inline constexpr double kMaxWholeProbes = 4.0e6;
/// A body of at most this many triangles, every part closed and consistently oriented,
/// decides the side of a probe near its surface by pseudo-normals instead of rays.
inline constexpr std::size_t kMaxPseudoNormalTriangles = std::size_t{1} << 19;
/// Probes of an on-demand body kept cached across measurements; beyond, the cache starts over.
inline constexpr std::size_t kMaxCachedProbes = std::size_t{1} << 23;

/// Where ExactPenetration changes method with size (tests lower them to try both ways).
struct ExactPenetrationLimits {
  /// The larger surface of a pair is probed on demand beyond this many probes.
  double maxWholeProbes = kMaxWholeProbes;
  /// A body of more triangles (or with a part not closed or not consistently oriented)
  /// takes the ray vote instead of pseudo-normals.
  std::size_t maxPseudoNormalTriangles = kMaxPseudoNormalTriangles;
};

class ExactPenetration {
public:
  /// Bodies `a` and `b` (see ExactBody), probed at `probeSpacingM` (> 0, m; e.g. the
  /// static voxel size / kProbesPerVoxel). Throws voxhap::Error for a bad spacing or when
  /// Embree fails.
  ExactPenetration(const ExactBody& a, const ExactBody& b, double probeSpacingM,
                   const ExactPenetrationLimits& limits = {});
  ~ExactPenetration();
  ExactPenetration(const ExactPenetration&) = delete;
  ExactPenetration& operator=(const ExactPenetration&) = delete;

  /// The penetration of A placed by `aToWorld` and B placed by `bToWorld` (local → world),
  /// both directions. Without `withClearance` the clearance is not measured (clearanceM
  /// stays infinite): near a wide parallel gap that is most of the cost.
  PenetrationSample measure(const Pose& aToWorld, const Pose& bToWorld, bool withClearance = true);

  /// Whether `pointLocal` (body `body`'s local frame, m; 0: A, 1: B) lies inside that
  /// body, by the three-ray parity vote straight from its meshes.
  bool inside(std::size_t body, const glm::dvec3& pointLocal);

  /// Whether body `body` (0: A, 1: B) was probed whole at construction.
  bool probedWhole(std::size_t body) const;
  /// Probes body `body` holds now: all of its surface's when probed whole, the cached
  /// regions' otherwise.
  std::size_t probeCount(std::size_t body) const;
  double probeSpacingM() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace voxhap

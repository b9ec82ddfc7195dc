#include "haptics/collide/exact_penetration.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

#include <glm/geometric.hpp>

#include "haptics/collide/probe_cells.h"
#include "haptics/collide/surface_probes.h"
#include "haptics/core/error.h"
#include "haptics/geometry/embree_scene.h"
#include "haptics/geometry/mesh_topology.h"
#include "haptics/geometry/pseudo_normals.h"
#include "haptics/voxel/voxel_encoding.h"

namespace voxhap {
namespace {

/// Clearance candidates are taken nearest first, in this many buckets of lower bound.
constexpr std::size_t kClearanceBuckets = 64;

/// A closest point this near a mesh edge or vertex takes that feature's pseudo-normal, m:
/// far above the rounding of a closest point computed on the feature, far below any probe spacing.
constexpr double kFeatureToleranceM = 1e-9;

/// Probe cells span at most this many probe spacings along an edge.
constexpr double kCellSpacings = 8.0;

/// Distance from `p` to the box `b` (0 inside), m.
double distanceToBox(const glm::dvec3& p, const Bounds& b) {
  const glm::dvec3 below = glm::max(b.min - p, glm::dvec3(0.0));
  const glm::dvec3 above = glm::max(p - b.max, glm::dvec3(0.0));
  return glm::length(glm::max(below, above));
}

/// The most any point within `radiusM` of `centreLocal` moves from `before` to `after`, m.
double displacementBound(const Pose& before, const Pose& after, const glm::dvec3& centreLocal,
                         double radiusM) {
  const glm::dquat turn = after.orientation * glm::conjugate(before.orientation);
  const double angleRad = 2.0 * std::atan2(glm::length(glm::dvec3(turn.x, turn.y, turn.z)), std::abs(turn.w));
  // |R1 x − R0 x| ≤ 2 sin(θ/2) |x| ≤ θ |x| about the centre
  return glm::length(apply(after, centreLocal) - apply(before, centreLocal)) + angleRad * radiusM;
}

/// `m` as a float no larger.
float floatBelow(double m) {
  float f = static_cast<float>(m);
  if (static_cast<double>(f) > m) f = std::nextafter(f, 0.0f);
  return f;
}

/// What the filter says of one probe, in the target body's frame.
enum class Verdict : std::uint8_t {
  Outside,  ///< outside and beyond the clearance range
  Near,     ///< outside, within the clearance range
  Inside,   ///< inside (an interior voxel): depth only
  Unknown,  ///< the vote decides
};

struct Classified {
  Verdict verdict;
  double lowerBoundM;  ///< Near: the probe is at least this far from the target's surface
  double depthHintM;   ///< Inside, Unknown: a first search radius for its depth
};

/// A probe outside the other body whose distance may be the clearance.
struct ClearanceCandidate {
  double lowerBoundM;
  glm::dvec3 pointTarget;  ///< in the target body's frame
  std::uint8_t target;     ///< 0: A, 1: B
  std::uint32_t probe;     ///< index of the probe in its side, when that side is probed whole (else kNoProbe)
};
constexpr std::uint32_t kNoProbe = 0xFFFFFFFFu;

/// Which probes of a group need looking at one by one.
struct Reach {
  bool faces;  ///< some may lie inside the other body or in one of its surface voxels
  bool edges;  ///< some may lie within the clearance range (faces implies edges)
};

/// A rigid transform as a matrix, for the loop over probes.
struct Placement {
  glm::dmat3 rotation;
  glm::dvec3 translation;
  explicit Placement(const Pose& pose)
      : rotation(glm::mat3_cast(pose.orientation)), translation(pose.position) {}
  glm::dvec3 operator()(const glm::dvec3& p) const { return rotation * p + translation; }
};

/// A sphere around a block of probes some of whose cells survived culling, in the other body's frame.
struct Sphere {
  glm::dvec3 centre;
  double radiusM;
};

/// One body: its meshes and Embree scene (local frame), its filter, and its probes.
struct ExactSide {
  std::vector<const TriangleMesh*> meshes;
  const Voxmap* voxmap = nullptr;
  std::unique_ptr<EmbreeScene> scene;
  Bounds boundsLocal;
  double rayLengthM = 1.0;  // longer than the bounding box's diagonal
  /// How far out of this body a probe of the other body counts for the clearance, m.
  double clearanceRangeM = 0.0;
  /// Search radius of a clearance query, m.
  double clearanceCapM = 0.0;
  double voxelsPerM = 0.0;  // 1 / the voxmap's voxel size, 1/m
  double estimatedProbes = 0.0;
  /// Outward pseudo-normals, when every part is closed and consistently oriented and the
  /// body is at most kMaxPseudoNormalTriangles: which side of the nearest surface a probe
  /// is on then says whether it is inside that part, without rays.
  std::unique_ptr<PseudoNormals> normals;
  std::vector<Bounds> partBounds;  // per part, local frame
  std::unique_ptr<ProbeCells> probes;
  // Drifting (as the paper's point drifting, §5.2), for a side probed whole: each probe's
  // last measured distance to the other surface (a lower bound: rounded down, or the
  // search radius that found nothing) and the side's drift when it was measured. The
  // drift sums, over measurements, a bound on how far any probe moved relative to the
  // other body; a probe's distance now is at least its last minus the drift since.
  std::vector<float> lastDistanceM;
  std::vector<double> lastDriftM;
  double driftM = 0.0;
  std::optional<Pose> lastToOther;
  glm::dvec3 centreLocal{0.0};  // of a sphere holding every probe
  double radiusM = 0.0;
  InsideVoteScratch vote;
};

}  // namespace

const char* penetrationDirectionName(PenetrationDirection direction) {
  switch (direction) {
    case PenetrationDirection::None:
      return "none";
    case PenetrationDirection::AIntoB:
      return "a-into-b";
    case PenetrationDirection::BIntoA:
      return "b-into-a";
  }
  return "none";
}

struct ExactPenetration::Impl {
  double spacingM;
  ExactSide sides[2];
  std::vector<ClearanceCandidate> clearance;
  std::vector<Sphere> survivors;
  std::vector<std::uint64_t> keys;
  std::vector<ProbeBlock> lazyBlocks;
  bool withClearance = true;
  std::vector<std::size_t> bucketStarts;
  std::vector<std::size_t> bucketFill;
  std::vector<std::uint32_t> ordered;
  /// Least exact distance of an outside edge probe found on the way (by its nearest
  /// surface point), m; the clearance starts from it.
  double knownClearanceM = std::numeric_limits<double>::infinity();

  bool voteInside(ExactSide& target, const glm::dvec3& pointLocal);
  /// The exact inside test of a probe near the target's surface: the side of the nearest
  /// surface point's pseudo-normal when the target has them (a probe outside the nearest
  /// part but within another part's box takes the vote), else the vote. Sets `depthM` to
  /// the probe's distance to the surface when it found it (else leaves it negative).
  bool insideNearSurface(ExactSide& target, const glm::dvec3& pointTarget, double hintM, double& depthM);
  Classified classify(const ExactSide& target, const glm::dvec3& pointTarget) const;
  /// Which probes within `radiusM` of `centreTarget` need looking at one by one.
  Reach reachOf(const ExactSide& target, const glm::dvec3& centreTarget, double radiusM) const;
  /// The target's surface point nearest `pointTarget`, searched within `hintM` first.
  std::optional<ClosestSurfacePoint> nearestSurface(const ExactSide& target, const glm::dvec3& pointTarget,
                                                    double hintM) const;
  double depthOf(const ExactSide& target, const glm::dvec3& pointTarget, double hintM) const;
  /// The least distance of the clearance candidates to their targets' surfaces, m.
  double leastClearance();
  /// Adds probe `probe` of side `from` (at `pointTarget`), at least `lowerBoundM` from the
  /// other side's surface, to the clearance candidates.
  void addClearanceCandidate(std::size_t from, std::uint32_t probe, const glm::dvec3& pointTarget,
                             double lowerBoundM);
  /// Remembers that probe `probe` of side `from` is at least `distanceM` from the other surface.
  void rememberDistance(std::size_t from, std::uint32_t probe, double distanceM);
  /// Probes of `blocks` of side `from` tested against the other side.
  void probeInto(std::size_t from, std::span<const ProbeBlock> blocks, const Pose& fromToTarget,
                 const Pose& fromToWorld, PenetrationSample& sample, bool keepSurvivors);
};

bool ExactPenetration::Impl::voteInside(ExactSide& target, const glm::dvec3& pointLocal) {
  return target.scene->insideAnyPart(pointLocal, target.rayLengthM, target.vote);
}

bool ExactPenetration::Impl::insideNearSurface(ExactSide& target, const glm::dvec3& pointTarget, double hintM,
                                               double& depthM) {
  depthM = -1.0;
  if (!target.normals) return voteInside(target, pointTarget);
  const std::optional<ClosestSurfacePoint> nearest = nearestSurface(target, pointTarget, hintM);
  if (!nearest) return voteInside(target, pointTarget);
  // Bærentzen and Aanæs: inside the nearest part iff behind its angle-weighted pseudo-normal
  const glm::dvec3 normal = target.normals->normalAt(*nearest, kFeatureToleranceM);
  if (glm::dot(pointTarget - nearest->point, normal) < 0.0) {
    depthM = nearest->distanceM;
    return true;
  }
  // outside the nearest part: outside the union unless another part may hold it
  for (std::uint32_t part = 0; part < target.partBounds.size(); ++part) {
    if (part == nearest->part) continue;
    if (distanceToBox(pointTarget, target.partBounds[part]) == 0.0) return voteInside(target, pointTarget);
  }
  depthM = nearest->distanceM;
  return false;
}

Classified ExactPenetration::Impl::classify(const ExactSide& target, const glm::dvec3& pointTarget) const {
  if (!target.voxmap) {
    const double d = distanceToBox(pointTarget, target.boundsLocal);
    if (d > target.clearanceRangeM) return {Verdict::Outside, 0.0, 0.0};
    if (d > 0.0) return {Verdict::Near, d, 0.0};
    return {Verdict::Unknown, 0.0, target.clearanceRangeM};
  }
  const Voxmap& voxmap = *target.voxmap;
  const double s = voxmap.grid().voxelSizeM;
  const glm::dvec3 u = glm::floor((pointTarget - voxmap.grid().originLocal) * target.voxelsPerM);
  const VoxelWord word = voxmap.word(glm::ivec3(u));
  if (word == Voxmap::kMissingWord) return {Verdict::Unknown, 0.0, 4.0 * s};
  const std::uint8_t value = voxmap.encoding().value(word, Field::Surface);
  if (value == kValueFar) return {Verdict::Outside, 0.0, 0.0};
  if (value == kValueInterior) return {Verdict::Inside, 0.0, 4.0 * s};
  // the surface passes through the probe's voxel: it is within the voxel's diagonal
  if (value == kValueFeature) return {Verdict::Unknown, 0.0, std::sqrt(3.0) * s * (1.0 + 1e-6)};
  const int distanceVoxels = value - kValueFeature;
  if (distanceVoxels > kClearanceVoxels) return {Verdict::Outside, 0.0, 0.0};
  // a surface voxel D voxels away (chessboard) is at least D − 1 voxel edges away
  return {Verdict::Near, static_cast<double>(distanceVoxels - 1) * s, 0.0};
}

Reach ExactPenetration::Impl::reachOf(const ExactSide& target, const glm::dvec3& centreTarget,
                                      double radiusM) const {
  if (!target.voxmap) {
    const double gapM = distanceToBox(centreTarget, target.boundsLocal) - radiusM;
    return {gapM <= 0.0, gapM <= target.clearanceRangeM};
  }
  const Voxmap& voxmap = *target.voxmap;
  const double s = voxmap.grid().voxelSizeM;
  // a point within the radius is at most this many voxels (chessboard) from the centre's
  const int reachVoxels = static_cast<int>(std::min(std::floor(radiusM / s), 1e6)) + 1;
  const glm::ivec3 ijk = voxmap.grid().voxelOf(centreTarget);
  // every chunk within reach holds only far voxels
  const int reachChunks = reachVoxels / kChunkEdgeVoxels + 1;
  if (voxmap.chunkDistance(ijk >> kChunkEdgeLog2) > reachChunks) return {false, false};
  const VoxelWord word = voxmap.word(ijk);
  if (word == Voxmap::kMissingWord) return {true, true};
  const std::uint8_t value = voxmap.encoding().value(word, Field::Surface);
  int distanceVoxels = 0;
  if (value == kValueFar) {
    distanceVoxels = voxmap.encoding().rangeVoxels + 1;
  } else if (value > kValueFeature) {
    distanceVoxels = value - kValueFeature;
  } else {
    return {true, true};
  }
  // every voxel within reach is free space at least this far (chessboard) from the surface
  const int freeVoxels = distanceVoxels - reachVoxels;
  return {freeVoxels < 1, freeVoxels <= kClearanceVoxels};
}

std::optional<ClosestSurfacePoint> ExactPenetration::Impl::nearestSurface(const ExactSide& target,
                                                                          const glm::dvec3& pointTarget,
                                                                          double hintM) const {
  // most contacts are shallow: a small search radius first, the whole body if need be
  for (const double radiusM : {hintM, target.rayLengthM}) {
    if (auto nearest = target.scene->closestPoint(pointTarget, radiusM)) return nearest;
  }
  return std::nullopt;
}

double ExactPenetration::Impl::depthOf(const ExactSide& target, const glm::dvec3& pointTarget,
                                       double hintM) const {
  const std::optional<ClosestSurfacePoint> nearest = nearestSurface(target, pointTarget, hintM);
  return nearest ? nearest->distanceM : 0.0;
}

void ExactPenetration::Impl::probeInto(std::size_t from, std::span<const ProbeBlock> blocks,
                                       const Pose& fromToTarget, const Pose& fromToWorld,
                                       PenetrationSample& sample, bool keepSurvivors) {
  ExactSide& source = sides[from];
  ExactSide& target = sides[1 - from];
  const ProbeCells& probes = *source.probes;
  const auto direction = from == 0 ? PenetrationDirection::AIntoB : PenetrationDirection::BIntoA;
  const Placement toTarget(fromToTarget);
  for (const ProbeBlock& block : blocks) {
    std::uint64_t blockProbes = 0;
    for (std::uint32_t c = block.firstCell; c < block.firstCell + block.cellCount; ++c) {
      blockProbes += probes.cell(c).count;
    }
    sample.probes += blockProbes;
    const glm::dvec3 blockCentreTarget = toTarget(block.centreLocal);
    if (!reachOf(target, blockCentreTarget, block.radiusM).edges) continue;
    bool anyCell = false;
    for (std::uint32_t c = block.firstCell; c < block.firstCell + block.cellCount; ++c) {
      const ProbeCell& cell = probes.cell(c);
      const glm::dvec3 centreTarget = toTarget(cell.centreLocal);
      const Reach reach = reachOf(target, centreTarget, cell.radiusM);
      if (!reach.edges) continue;
      anyCell = true;
      // edge probes count for the clearance; without it, or inside, they are like the others
      const bool edges = withClearance ? reach.edges : reach.faces;
      const std::uint32_t end = cell.first + (reach.faces ? cell.count : (edges ? cell.edgeCount : 0));
      sample.nearProbes += end - cell.first;
      for (std::uint32_t i = cell.first; i < end; ++i) {
        const bool onEdge = i < cell.first + cell.edgeCount;
        const glm::dvec3 pointLocal(probes.probeLocal(i));
        const glm::dvec3 pointTarget = toTarget(pointLocal);
        const Classified k = classify(target, pointTarget);
        bool isInside = false;
        double knownDepthM = -1.0;
        switch (k.verdict) {
          case Verdict::Outside:
            continue;
          case Verdict::Near:
            if (onEdge && withClearance) addClearanceCandidate(from, i, pointTarget, k.lowerBoundM);
            continue;
          case Verdict::Inside:
            isInside = true;
            break;
          case Verdict::Unknown:
            ++sample.candidates;
            isInside = insideNearSurface(target, pointTarget, k.depthHintM, knownDepthM);
            if (!isInside && onEdge && withClearance) {
              if (knownDepthM >= 0.0 && knownDepthM <= target.clearanceCapM) {
                knownClearanceM = std::min(knownClearanceM, knownDepthM);
                rememberDistance(from, i, knownDepthM);
              } else {
                addClearanceCandidate(from, i, pointTarget, 0.0);
              }
            }
            break;
        }
        if (!isInside) continue;
        ++sample.inside;
        const double depthM = knownDepthM >= 0.0 ? knownDepthM : depthOf(target, pointTarget, k.depthHintM);
        if (depthM > sample.depthM) {
          sample.depthM = depthM;
          sample.deepestWorld = apply(fromToWorld, pointLocal);
          sample.direction = direction;
        }
      }
    }
    if (keepSurvivors && anyCell) survivors.push_back({blockCentreTarget, block.radiusM});
  }
}

ExactPenetration::ExactPenetration(const ExactBody& a, const ExactBody& b, double probeSpacingM,
                                   const ExactPenetrationLimits& limits)
    : impl_(std::make_unique<Impl>()) {
  if (!(probeSpacingM > 0.0) || !std::isfinite(probeSpacingM)) {
    throw Error("exact penetration: the probe spacing must be a positive length, got " +
                std::to_string(probeSpacingM) + " m");
  }
  impl_->spacingM = probeSpacingM;
  const ExactBody* bodies[2] = {&a, &b};
  for (std::size_t i = 0; i < 2; ++i) {
    ExactSide& side = impl_->sides[i];
    side.meshes = bodies[i]->meshesLocal;
    side.voxmap = bodies[i]->voxmapLocal;
    side.scene = std::make_unique<EmbreeScene>(side.meshes);
    for (const TriangleMesh* mesh : side.meshes) {
      for (const glm::vec3& p : mesh->positionsWorld) side.boundsLocal.add(glm::dvec3(p));
      for (const glm::uvec3& t : mesh->triangles) {
        side.estimatedProbes += estimateTriangleProbes(mesh->positionsWorld[t.x], mesh->positionsWorld[t.y],
                                                       mesh->positionsWorld[t.z], probeSpacingM);
      }
    }
    side.rayLengthM = 2.0 * glm::length(side.boundsLocal.extent()) + 1.0;
    std::size_t triangles = 0;
    bool closed = true;
    for (const TriangleMesh* mesh : side.meshes) {
      triangles += mesh->triangles.size();
      Bounds bounds;
      for (const glm::vec3& p : mesh->positionsWorld) bounds.add(glm::dvec3(p));
      side.partBounds.push_back(bounds);
    }
    if (triangles <= limits.maxPseudoNormalTriangles) {
      for (const TriangleMesh* mesh : side.meshes) {
        const MeshTopology topology = computeTopology(*mesh);
        closed = closed && topology.closed() && topology.consistentlyOriented() && signedVolume(*mesh) > 0.0;
      }
      if (closed) side.normals = std::make_unique<PseudoNormals>(side.meshes);
    }
    if (side.voxmap) {
      const double s = side.voxmap->grid().voxelSizeM;
      // a probe in a voxel at most kClearanceVoxels from a surface voxel is at most this far
      side.clearanceRangeM = std::sqrt(3.0) * (kClearanceVoxels + 1) * s;
      side.clearanceCapM = (kClearanceVoxels + 2) * s;
      side.voxelsPerM = 1.0 / s;
    } else {
      side.clearanceRangeM = kClearanceVoxels * kProbesPerVoxel * probeSpacingM;
      side.clearanceCapM = side.clearanceRangeM;
    }
  }
  for (std::size_t i = 0; i < 2; ++i) {
    ExactSide& side = impl_->sides[i];
    const ExactSide& other = impl_->sides[1 - i];
    // the smaller surface is always probed whole; the larger when it is small enough
    const bool whole = side.estimatedProbes <= limits.maxWholeProbes ||
                       side.estimatedProbes < other.estimatedProbes ||
                       (side.estimatedProbes == other.estimatedProbes && i == 0);
    // cells about two voxels of the other body's voxmap across, so that culling a cell
    // by the voxel under its centre works
    double cellM = kCellSpacings * probeSpacingM;
    if (other.voxmap) cellM = std::clamp(2.0 * other.voxmap->grid().voxelSizeM, 2.0 * probeSpacingM, cellM);
    side.probes = std::make_unique<ProbeCells>(side.meshes, *side.scene, probeSpacingM, cellM, whole);
    if (whole) {
      side.lastDistanceM.assign(side.probes->probeCount(), 0.0f);
      side.lastDriftM.assign(side.probes->probeCount(), 0.0);
    }
    // every probe lies on a triangle, so within the sphere around the vertices
    side.centreLocal = 0.5 * (side.boundsLocal.min + side.boundsLocal.max);
    for (const TriangleMesh* mesh : side.meshes) {
      for (const glm::vec3& p : mesh->positionsWorld) {
        side.radiusM = std::max(side.radiusM, glm::length(glm::dvec3(p) - side.centreLocal));
      }
    }
  }
}

ExactPenetration::~ExactPenetration() = default;

PenetrationSample ExactPenetration::measure(const Pose& aToWorld, const Pose& bToWorld, bool withClearance) {
  Impl& m = *impl_;
  m.withClearance = withClearance;
  PenetrationSample sample;
  m.clearance.clear();
  m.survivors.clear();
  m.knownClearanceM = std::numeric_limits<double>::infinity();
  const Pose toWorld[2] = {aToWorld, bToWorld};
  const Pose aToB = compose(inverse(bToWorld), aToWorld);
  const Pose bToA = compose(inverse(aToWorld), bToWorld);
  const Pose toOther[2] = {aToB, bToA};
  for (std::size_t i = 0; i < 2; ++i) {
    ExactSide& side = m.sides[i];
    if (side.lastToOther)
      side.driftM += displacementBound(*side.lastToOther, toOther[i], side.centreLocal, side.radiusM);
    side.lastToOther = toOther[i];
  }

  // the sides probed whole first; an on-demand side then probes the regions near the
  // cells of the other that were not culled
  const std::size_t first = m.sides[0].probes->whole() ? 0 : 1;
  const std::size_t second = 1 - first;
  m.probeInto(first, m.sides[first].probes->blocks(), toOther[first], toWorld[first], sample,
              !m.sides[second].probes->whole());
  ExactSide& next = m.sides[second];
  if (next.probes->whole()) {
    m.probeInto(second, next.probes->blocks(), toOther[second], toWorld[second], sample, false);
  } else {
    if (next.probes->probeCount() > kMaxCachedProbes) next.probes->clear();
    // probes of `next` within the clearance range of the other side's surface, or inside it
    const double marginM = m.sides[first].clearanceRangeM + m.spacingM;
    m.keys.clear();
    for (const Sphere& s : m.survivors) {
      const glm::dvec3 reach(s.radiusM + marginM);
      next.probes->blockKeysIn(s.centre - reach, s.centre + reach, m.keys);
    }
    std::sort(m.keys.begin(), m.keys.end());
    m.keys.erase(std::unique(m.keys.begin(), m.keys.end()), m.keys.end());
    m.lazyBlocks.clear();
    for (const std::uint64_t key : m.keys) {
      if (const std::optional<ProbeBlock> block = next.probes->block(key)) m.lazyBlocks.push_back(*block);
    }
    m.probeInto(second, m.lazyBlocks, toOther[second], toWorld[second], sample, false);
  }

  sample.clearanceM = m.leastClearance();
  return sample;
}

void ExactPenetration::Impl::addClearanceCandidate(std::size_t from, std::uint32_t probe,
                                                   const glm::dvec3& pointTarget, double lowerBoundM) {
  const ExactSide& side = sides[from];
  const auto target = static_cast<std::uint8_t>(1 - from);
  if (!side.probes->whole()) {
    clearance.push_back({lowerBoundM, pointTarget, target, kNoProbe});
    return;
  }
  const double driftedM =
      static_cast<double>(side.lastDistanceM[probe]) - (side.driftM - side.lastDriftM[probe]);
  clearance.push_back({std::max(lowerBoundM, driftedM), pointTarget, target, probe});
}

void ExactPenetration::Impl::rememberDistance(std::size_t from, std::uint32_t probe, double distanceM) {
  ExactSide& side = sides[from];
  if (!side.probes->whole() || probe == kNoProbe) return;
  side.lastDistanceM[probe] = floatBelow(distanceM);
  side.lastDriftM[probe] = side.driftM;
}

double ExactPenetration::Impl::leastClearance() {
  // nearest candidates first (by buckets of their lower bounds, in the order they came
  // within a bucket), each query no wider than the best so far
  double widthM = std::numeric_limits<double>::infinity();
  for (const ExactSide& side : sides) widthM = std::min(widthM, side.clearanceRangeM / kClearanceBuckets);
  bucketStarts.assign(kClearanceBuckets + 1, 0);
  auto bucketOf = [&](double lowerBoundM) {
    return std::min(static_cast<std::size_t>(lowerBoundM / widthM), kClearanceBuckets - 1);
  };
  for (const ClearanceCandidate& c : clearance) ++bucketStarts[bucketOf(c.lowerBoundM) + 1];
  for (std::size_t b = 1; b <= kClearanceBuckets; ++b) bucketStarts[b] += bucketStarts[b - 1];
  ordered.resize(clearance.size());
  bucketFill.assign(bucketStarts.begin(), bucketStarts.end() - 1);
  for (std::uint32_t i = 0; i < clearance.size(); ++i)
    ordered[bucketFill[bucketOf(clearance[i].lowerBoundM)]++] = i;

  double bestM = knownClearanceM;
  for (std::size_t b = 0; b < kClearanceBuckets; ++b) {
    // below the resolution, nothing more to win
    if (static_cast<double>(b) * widthM >= bestM || bestM <= kClearanceResolutionM) break;
    for (std::size_t k = bucketStarts[b]; k < bucketStarts[b + 1]; ++k) {
      const ClearanceCandidate& c = clearance[ordered[k]];
      if (c.lowerBoundM >= bestM || bestM <= kClearanceResolutionM) continue;
      const ExactSide& target = sides[c.target];
      const double radiusM = std::min(bestM, target.clearanceCapM);
      const auto nearest = target.scene->closestPoint(c.pointTarget, radiusM);
      if (nearest) bestM = std::min(bestM, nearest->distanceM);
      // nothing within the radius: at least that far
      rememberDistance(1u - c.target, c.probe, nearest ? nearest->distanceM : radiusM);
    }
  }
  return bestM;
}

bool ExactPenetration::inside(std::size_t body, const glm::dvec3& pointLocal) {
  return impl_->voteInside(impl_->sides[body], pointLocal);
}

bool ExactPenetration::probedWhole(std::size_t body) const {
  return impl_->sides[body].probes->whole();
}

std::size_t ExactPenetration::probeCount(std::size_t body) const {
  return impl_->sides[body].probes->probeCount();
}

double ExactPenetration::probeSpacingM() const {
  return impl_->spacingM;
}

}  // namespace voxhap

#pragma once
/// Exact geometric queries on triangle meshes through Embree: every crossing of a
/// ray (for inside/outside parity) and the closest surface point (for pointshell
/// normals and for ground-truth distances in tests). Built once, then queried from
/// any number of threads; never used in the 1 kHz frame.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "haptics/scene/scene.h"

namespace voxhap {

/// One crossing of a ray with a triangle.
struct RayCrossing {
  double t;                ///< distance along the (unit) ray from its origin, m
  std::uint32_t part;      ///< index of the mesh in the scene's part list
  std::uint32_t triangle;  ///< index of the triangle in that mesh
};

/// One triangle of the scene.
struct TriangleRef {
  std::uint32_t part;      ///< index of the mesh in the scene's part list
  std::uint32_t triangle;  ///< index of the triangle in that mesh
  friend bool operator==(const TriangleRef&, const TriangleRef&) = default;
  friend auto operator<=>(const TriangleRef&, const TriangleRef&) = default;
};

/// The surface point nearest to a query point.
struct ClosestSurfacePoint {
  glm::dvec3 point;  ///< on the triangle, same frame as the meshes, m
  double distanceM;  ///< from the query point
  std::uint32_t part;
  std::uint32_t triangle;
  glm::dvec3 faceNormal;  ///< unit outward normal of that triangle
};

/// Scratch of EmbreeScene::insideAnyPart(), so that repeated calls do not allocate.
struct InsideVoteScratch {
  std::vector<RayCrossing> hits;
  std::vector<std::uint32_t> parts;
};

class EmbreeScene {
public:
  /// Builds a scene of the given meshes (kept by reference: they must outlive it).
  /// Throws voxhap::Error when Embree fails.
  explicit EmbreeScene(std::span<const TriangleMesh* const> meshes);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  /// Appends to `out` every crossing of the ray from `origin` along unit `direction`
  /// with t in [0, tMaxM], each triangle once, in no particular order.
  void allCrossings(const glm::dvec3& origin, const glm::dvec3& direction, double tMaxM,
                    std::vector<RayCrossing>& out) const;

  /// Whether `point` lies inside the union of the scene's closed meshes: a vote of three
  /// rays skewed off the axes (CAD models are full of axis-aligned faces and edges that one
  /// ray could graze), each saying inside when some part is crossed an odd number of times
  /// within `rayLengthM` (longer than the scene).
  bool insideAnyPart(const glm::dvec3& point, double rayLengthM, InsideVoteScratch& scratch) const;

  /// The closest surface point within `maxDistanceM` of `point`, if any.
  std::optional<ClosestSurfacePoint> closestPoint(const glm::dvec3& point, double maxDistanceM) const;

  /// Appends to `out` every triangle with a point within `radiusM` of `point` (same frame
  /// as the meshes, m), each once, sorted by (part, triangle).
  void trianglesWithin(const glm::dvec3& point, double radiusM, std::vector<TriangleRef>& out) const;

private:
  void release();

  std::vector<const TriangleMesh*> meshes_;
  void* device_ = nullptr;  // RTCDevice; opaque here so that users need no Embree headers
  void* scene_ = nullptr;   // RTCScene
};

/// The point of triangle (a, b, c) closest to `p` (Ericson, Real-Time Collision
/// Detection, §5.1.5).
glm::dvec3 closestPointOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                  const glm::dvec3& c);

}  // namespace voxhap

#include "haptics/geometry/embree_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

#include "haptics/core/error.h"

namespace voxhap {
namespace {

RTCDevice asDevice(void* p) {
  return static_cast<RTCDevice>(p);
}
RTCScene asScene(void* p) {
  return static_cast<RTCScene>(p);
}

/// An intersect context that also carries where to put the crossings.
struct CrossingContext {
  RTCIntersectContext context;  // first, so that Embree's pointer is ours
  std::vector<RayCrossing>* out;
};

void recordCrossing(const RTCFilterFunctionNArguments* args) {
  auto* collector = reinterpret_cast<CrossingContext*>(args->context);
  const float t = RTCRayN_tfar(args->ray, args->N, 0);
  collector->out->push_back(
      {static_cast<double>(t), RTCHitN_geomID(args->hit, args->N, 0), RTCHitN_primID(args->hit, args->N, 0)});
  args->valid[0] = 0;  // reject, so that traversal goes on to the next crossing
}

struct ClosestQuery {
  const std::vector<const TriangleMesh*>* meshes;
  std::optional<ClosestSurfacePoint> best;
  glm::dvec3 point;
};

bool visitTriangle(RTCPointQueryFunctionArguments* args) {
  auto* q = static_cast<ClosestQuery*>(args->userPtr);
  const TriangleMesh& mesh = *(*q->meshes)[args->geomID];
  const glm::uvec3& t = mesh.triangles[args->primID];
  const glm::dvec3 a(mesh.positionsWorld[t.x]);
  const glm::dvec3 b(mesh.positionsWorld[t.y]);
  const glm::dvec3 c(mesh.positionsWorld[t.z]);
  const glm::dvec3 p = closestPointOnTriangle(q->point, a, b, c);
  const double d = glm::length(p - q->point);
  // ties go to the lower (part, triangle), so that the answer does not depend on traversal order
  const bool better = !q->best || d < q->best->distanceM ||
                      (d == q->best->distanceM &&
                       std::pair(args->geomID, args->primID) < std::pair(q->best->part, q->best->triangle));
  if (!better || d > args->query->radius) return false;
  const glm::dvec3 n = glm::cross(b - a, c - a);
  q->best = ClosestSurfacePoint{p, d, args->geomID, args->primID, glm::normalize(n)};
  args->query->radius = static_cast<float>(d) * (1.0f + 1e-6f) + 1e-12f;
  return true;
}

struct NearQuery {
  const std::vector<const TriangleMesh*>* meshes;
  std::vector<TriangleRef>* out;
  glm::dvec3 point;
  double radiusM;
};

bool collectTriangle(RTCPointQueryFunctionArguments* args) {
  auto* q = static_cast<NearQuery*>(args->userPtr);
  const TriangleMesh& mesh = *(*q->meshes)[args->geomID];
  const glm::uvec3& t = mesh.triangles[args->primID];
  const glm::dvec3 p =
      closestPointOnTriangle(q->point, glm::dvec3(mesh.positionsWorld[t.x]),
                             glm::dvec3(mesh.positionsWorld[t.y]), glm::dvec3(mesh.positionsWorld[t.z]));
  if (glm::length(p - q->point) <= q->radiusM) q->out->push_back({args->geomID, args->primID});
  return false;  // the radius stays: every triangle within it is wanted
}

}  // namespace

glm::dvec3 closestPointOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                  const glm::dvec3& c) {
  const glm::dvec3 ab = b - a;
  const glm::dvec3 ac = c - a;
  const glm::dvec3 ap = p - a;
  const double d1 = glm::dot(ab, ap);
  const double d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp);
  const double d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + ab * (d1 / (d1 - d3));
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp);
  const double d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denominator = 1.0 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

EmbreeScene::EmbreeScene(std::span<const TriangleMesh* const> meshes)
    : meshes_(meshes.begin(), meshes.end()) {
  RTCDevice device = rtcNewDevice(nullptr);
  if (!device) throw Error("Embree: cannot create a device");
  device_ = device;
  RTCScene scene = rtcNewScene(device);
  scene_ = scene;
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
  for (std::size_t i = 0; i < meshes_.size(); ++i) {
    const TriangleMesh& mesh = *meshes_[i];
    if (mesh.triangles.empty()) continue;
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices =
        static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                    3 * sizeof(float), mesh.positionsWorld.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangles.size()));
    if (!vertices || !indices) {
      rtcReleaseGeometry(geometry);
      release();
      throw Error("Embree: cannot allocate geometry buffers (out of memory?)");
    }
    std::copy_n(&mesh.positionsWorld[0].x, 3 * mesh.positionsWorld.size(), vertices);
    std::copy_n(&mesh.triangles[0].x, 3 * mesh.triangles.size(), indices);
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(scene, geometry, static_cast<unsigned>(i));
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(scene);
  if (rtcGetDeviceError(device) != RTC_ERROR_NONE) {
    release();
    throw Error("Embree: building the scene failed");
  }
}

EmbreeScene::~EmbreeScene() {
  release();
}

void EmbreeScene::release() {
  if (scene_) rtcReleaseScene(asScene(scene_));
  if (device_) rtcReleaseDevice(asDevice(device_));
  scene_ = nullptr;
  device_ = nullptr;
}

void EmbreeScene::allCrossings(const glm::dvec3& origin, const glm::dvec3& direction, double tMaxM,
                               std::vector<RayCrossing>& out) const {
  CrossingContext collector;
  rtcInitIntersectContext(&collector.context);
  collector.context.filter = &recordCrossing;
  collector.out = &out;
  RTCRayHit rayHit{};
  rayHit.ray.org_x = static_cast<float>(origin.x);
  rayHit.ray.org_y = static_cast<float>(origin.y);
  rayHit.ray.org_z = static_cast<float>(origin.z);
  rayHit.ray.dir_x = static_cast<float>(direction.x);
  rayHit.ray.dir_y = static_cast<float>(direction.y);
  rayHit.ray.dir_z = static_cast<float>(direction.z);
  rayHit.ray.tnear = 0.0f;
  rayHit.ray.tfar = static_cast<float>(tMaxM);
  rayHit.ray.mask = 0xFFFFFFFFu;
  rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  const std::size_t first = out.size();
  rtcIntersect1(asScene(scene_), &collector.context, &rayHit);
  // a triangle may be reported more than once; keep each once
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(),
            [](const RayCrossing& x, const RayCrossing& y) {
              return std::tie(x.part, x.triangle, x.t) < std::tie(y.part, y.triangle, y.t);
            });
  out.erase(std::unique(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(),
                        [](const RayCrossing& x, const RayCrossing& y) {
                          return x.part == y.part && x.triangle == y.triangle;
                        }),
            out.end());
}

bool EmbreeScene::insideAnyPart(const glm::dvec3& point, double rayLengthM,
                                InsideVoteScratch& scratch) const {
  static const glm::dvec3 kDirections[] = {
      glm::normalize(glm::dvec3(1.0, 0.0123, 0.0071)),
      glm::normalize(glm::dvec3(-0.0093, 1.0, 0.0137)),
      glm::normalize(glm::dvec3(0.0117, -0.0081, 1.0)),
  };
  int votes = 0;
  for (const glm::dvec3& direction : kDirections) {
    scratch.hits.clear();
    allCrossings(point, direction, rayLengthM, scratch.hits);
    scratch.parts.clear();
    for (const RayCrossing& hit : scratch.hits) scratch.parts.push_back(hit.part);
    std::sort(scratch.parts.begin(), scratch.parts.end());
    bool odd = false;
    for (std::size_t i = 0; i < scratch.parts.size() && !odd;) {
      std::size_t k = i;
      while (k < scratch.parts.size() && scratch.parts[k] == scratch.parts[i]) ++k;
      odd = ((k - i) & 1u) != 0;
      i = k;
    }
    votes += odd ? 1 : 0;
  }
  return votes >= 2;
}

std::optional<ClosestSurfacePoint> EmbreeScene::closestPoint(const glm::dvec3& point,
                                                             double maxDistanceM) const {
  RTCPointQuery query{};
  query.x = static_cast<float>(point.x);
  query.y = static_cast<float>(point.y);
  query.z = static_cast<float>(point.z);
  query.time = 0.0f;
  query.radius = static_cast<float>(maxDistanceM);
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  ClosestQuery q{&meshes_, std::nullopt, point};
  rtcPointQuery(asScene(scene_), &query, &context, &visitTriangle, &q);
  return q.best;
}

void EmbreeScene::trianglesWithin(const glm::dvec3& point, double radiusM,
                                  std::vector<TriangleRef>& out) const {
  RTCPointQuery query{};
  query.x = static_cast<float>(point.x);
  query.y = static_cast<float>(point.y);
  query.z = static_cast<float>(point.z);
  query.time = 0.0f;
  // a little wider in float, so that rounding the centre loses no triangle; the exact
  // test in collectTriangle decides
  query.radius = static_cast<float>(radiusM) * (1.0f + 1e-5f) + 1e-6f;
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  const std::size_t first = out.size();
  NearQuery q{&meshes_, &out, point, radiusM};
  rtcPointQuery(asScene(scene_), &query, &context, &collectTriangle, &q);
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
  out.erase(std::unique(out.begin() + static_cast<std::ptrdiff_t>(first), out.end()), out.end());
}

}  // namespace voxhap

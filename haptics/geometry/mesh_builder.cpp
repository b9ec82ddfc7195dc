#include "haptics/geometry/mesh_builder.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace voxhap {
namespace {

constexpr double kPi = 3.14159265358979323846264338327950288;
constexpr double kTwoPi = 2.0 * kPi;

/// Appends transformed vertices and (winding-corrected) triangles to one mesh.
class MeshAppender {
public:
  MeshAppender(TriangleMesh& mesh, const glm::dmat4& localToWorld)
      : mesh_(mesh), localToWorld_(localToWorld), flip_(glm::determinant(glm::dmat3(localToWorld)) < 0.0) {}

  void reserve(std::size_t extraVertices, std::size_t extraTriangles) {
    mesh_.positionsWorld.reserve(mesh_.positionsWorld.size() + extraVertices);
    mesh_.triangles.reserve(mesh_.triangles.size() + extraTriangles);
  }

  std::uint32_t addVertex(const glm::dvec3& pointLocal) {
    const std::size_t index = mesh_.positionsWorld.size();
    assert(index < std::numeric_limits<std::uint32_t>::max());
    const glm::dvec4 w = localToWorld_ * glm::dvec4(pointLocal, 1.0);
    mesh_.positionsWorld.emplace_back(static_cast<float>(w.x), static_cast<float>(w.y),
                                      static_cast<float>(w.z));
    return static_cast<std::uint32_t>(index);
  }

  void addTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (flip_) {
      mesh_.triangles.emplace_back(a, c, b);
    } else {
      mesh_.triangles.emplace_back(a, b, c);
    }
  }

private:
  TriangleMesh& mesh_;
  glm::dmat4 localToWorld_;
  bool flip_;
};

/// cos and sin of 2πi/segments, i = 0 … segments-1.
struct AngleTable {
  std::vector<double> cosines;
  std::vector<double> sines;

  explicit AngleTable(std::uint32_t segments) : cosines(segments), sines(segments) {
    for (std::uint32_t i = 0; i < segments; ++i) {
      const double angle = kTwoPi * static_cast<double>(i) / static_cast<double>(segments);
      cosines[i] = std::cos(angle);
      sines[i] = std::sin(angle);
    }
  }
};

/// The core of every swept shape: a closed loop of `ringCount` rings, each either a single
/// apex vertex or `segments` vertices, consecutive rings joined by quads (two triangles)
/// or fans; two consecutive apexes are not joined. Ring j's vertex i comes from
/// `ringPoint(j, i)`. Outward when the loop turns like a counter-clockwise lathe profile
/// (ring vertices counter-clockwise about the direction in which the rings advance at the
/// outside).
template <class IsApex, class RingPoint>
void appendRingLoop(MeshAppender& out, std::size_t ringCount, std::uint32_t segments, IsApex isApex,
                    RingPoint ringPoint) {
  std::size_t vertexCount = 0;
  std::size_t triangleCount = 0;
  for (std::size_t j = 0; j < ringCount; ++j) {
    const std::size_t k = (j + 1) % ringCount;
    vertexCount += isApex(j) ? 1 : segments;
    if (!(isApex(j) && isApex(k))) triangleCount += (isApex(j) || isApex(k)) ? segments : 2 * segments;
  }
  out.reserve(vertexCount, triangleCount);

  std::vector<std::uint32_t> ringStart(ringCount);
  for (std::size_t j = 0; j < ringCount; ++j) {
    ringStart[j] = out.addVertex(ringPoint(j, 0u));
    if (!isApex(j)) {
      for (std::uint32_t i = 1; i < segments; ++i) out.addVertex(ringPoint(j, i));
    }
  }
  auto index = [&](std::size_t j, std::uint32_t i) {
    return isApex(j) ? ringStart[j] : ringStart[j] + (i % segments);
  };
  for (std::size_t j = 0; j < ringCount; ++j) {
    const std::size_t k = (j + 1) % ringCount;
    const bool apexJ = isApex(j);
    const bool apexK = isApex(k);
    if (apexJ && apexK) continue;
    for (std::uint32_t i = 0; i < segments; ++i) {
      const std::uint32_t a = index(j, i);
      const std::uint32_t b = index(j, i + 1);
      const std::uint32_t c = index(k, i + 1);
      const std::uint32_t d = index(k, i);
      if (!apexJ) out.addTriangle(a, b, c);
      if (!apexK) out.addTriangle(a, c, d);
    }
  }
}

std::uint32_t toCount(int value) {
  assert(value > 0);
  return static_cast<std::uint32_t>(value);
}

/// A unit vector perpendicular to the unit vector `axis`, chosen deterministically.
glm::dvec3 perpendicular(const glm::dvec3& axis) {
  const glm::dvec3 reference = std::abs(axis.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
  return glm::normalize(reference - glm::dot(reference, axis) * axis);
}

}  // namespace

void appendBox(TriangleMesh& mesh, const glm::dmat4& localToWorld, const glm::dvec3& halfExtentsM) {
  assert(halfExtentsM.x > 0.0 && halfExtentsM.y > 0.0 && halfExtentsM.z > 0.0);
  MeshAppender out(mesh, localToWorld);
  out.reserve(8, 12);
  std::uint32_t v[8];
  for (std::uint32_t corner = 0; corner < 8; ++corner) {
    v[corner] = out.addVertex({(corner & 1u) ? halfExtentsM.x : -halfExtentsM.x,
                               (corner & 2u) ? halfExtentsM.y : -halfExtentsM.y,
                               (corner & 4u) ? halfExtentsM.z : -halfExtentsM.z});
  }
  // faces as counter-clockwise quads seen from outside: -x, +x, -y, +y, -z, +z
  const std::uint32_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& f : faces) {
    out.addTriangle(v[f[0]], v[f[1]], v[f[2]]);
    out.addTriangle(v[f[0]], v[f[2]], v[f[3]]);
  }
}

void appendGeodesicSphere(TriangleMesh& mesh, const glm::dmat4& localToWorld, double radiusM,
                          int subdivisions) {
  assert(radiusM > 0.0 && subdivisions >= 0 && subdivisions <= 10);
  MeshAppender out(mesh, localToWorld);
  // Lattice points (a, b, c) with |a| + |b| + |c| = n lie on the octahedron; subdividing its
  // faces k times into four gives exactly these points for n = 2^k.
  const std::int64_t n = std::int64_t{1} << subdivisions;
  const std::size_t triangleCount = 8u * (std::size_t{1} << (2 * subdivisions));
  out.reserve(triangleCount / 2 + 2, triangleCount);
  std::unordered_map<std::int64_t, std::uint32_t> vertexOfLattice;
  vertexOfLattice.reserve(triangleCount / 2 + 2);
  auto vertex = [&](std::int64_t a, std::int64_t b, std::int64_t c) {
    const std::int64_t side = 2 * n + 1;
    const std::int64_t key = ((a + n) * side + (b + n)) * side + (c + n);
    const auto found = vertexOfLattice.find(key);
    if (found != vertexOfLattice.end()) return found->second;
    const glm::dvec3 direction =
        glm::normalize(glm::dvec3(static_cast<double>(a), static_cast<double>(b), static_cast<double>(c)));
    const std::uint32_t index = out.addVertex(radiusM * direction);
    vertexOfLattice.emplace(key, index);
    return index;
  };
  for (int octant = 0; octant < 8; ++octant) {
    const std::int64_t sx = (octant & 1) ? -1 : 1;
    const std::int64_t sy = (octant & 2) ? -1 : 1;
    const std::int64_t sz = (octant & 4) ? -1 : 1;
    const bool mirrored = sx * sy * sz < 0;
    auto at = [&](std::int64_t i, std::int64_t j) { return vertex(sx * i, sy * j, sz * (n - i - j)); };
    auto emit = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      if (mirrored) {
        out.addTriangle(a, c, b);
      } else {
        out.addTriangle(a, b, c);
      }
    };
    for (std::int64_t i = 0; i < n; ++i) {
      for (std::int64_t j = 0; j < n - i; ++j) {
        emit(at(i, j), at(i + 1, j), at(i, j + 1));
        if (j + 1 < n - i) emit(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
      }
    }
  }
}

void appendLathe(TriangleMesh& mesh, const glm::dmat4& localToWorld, std::span<const ProfilePoint> profile,
                 int segments) {
  assert(profile.size() >= 3 && segments >= 3);
  const std::uint32_t s = toCount(segments);
  const AngleTable angles(s);
  // radial scale of each ring sample: 1 for circles, apothem / cos(offset from the flat's
  // centre) for polygons (corners land exactly on samples because s is a multiple of 2n)
  std::vector<std::vector<double>> polygonScale(profile.size());
  for (std::size_t j = 0; j < profile.size(); ++j) {
    const int sides = profile[j].polygonSides;
    if (sides == 0 || profile[j].radiusM == 0.0) continue;
    assert(sides >= 3 && s % (2u * static_cast<std::uint32_t>(sides)) == 0);
    const std::uint32_t perFlat = s / static_cast<std::uint32_t>(sides);
    const double apothemScale = std::cos(kPi / static_cast<double>(sides));
    polygonScale[j].resize(s);
    for (std::uint32_t i = 0; i < s; ++i) {
      const std::uint32_t m = (i + perFlat / 2) % perFlat;
      const double offset =
          (static_cast<double>(m) - static_cast<double>(perFlat) / 2.0) * kTwoPi / static_cast<double>(s);
      polygonScale[j][i] = m == 0 ? 1.0 : apothemScale / std::cos(offset);
    }
  }
  MeshAppender out(mesh, localToWorld);
  appendRingLoop(
      out, profile.size(), s, [&](std::size_t j) { return profile[j].radiusM == 0.0; },
      [&](std::size_t j, std::uint32_t i) {
        const ProfilePoint& p = profile[j];
        if (p.radiusM == 0.0) return glm::dvec3(0.0, 0.0, p.zM);
        const double r = polygonScale[j].empty() ? p.radiusM : p.radiusM * polygonScale[j][i];
        return glm::dvec3(r * angles.cosines[i], r * angles.sines[i], p.zM);
      });
}

void appendCylinder(TriangleMesh& mesh, const glm::dmat4& localToWorld, double radiusM, double lengthM,
                    int segments) {
  assert(radiusM > 0.0 && lengthM > 0.0);
  const ProfilePoint profile[] = {{0.0, 0.0}, {radiusM, 0.0}, {radiusM, lengthM}, {0.0, lengthM}};
  appendLathe(mesh, localToWorld, profile, segments);
}

void appendHollowCylinder(TriangleMesh& mesh, const glm::dmat4& localToWorld, double innerRadiusM,
                          double outerRadiusM, double lengthM, int segments) {
  assert(innerRadiusM > 0.0 && innerRadiusM < outerRadiusM && lengthM > 0.0);
  const ProfilePoint profile[] = {
      {innerRadiusM, 0.0}, {outerRadiusM, 0.0}, {outerRadiusM, lengthM}, {innerRadiusM, lengthM}};
  appendLathe(mesh, localToWorld, profile, segments);
}

void appendTorus(TriangleMesh& mesh, const glm::dmat4& localToWorld, double majorRadiusM, double minorRadiusM,
                 int majorSegments, int minorSegments) {
  assert(minorRadiusM > 0.0 && minorRadiusM < majorRadiusM && minorSegments >= 3);
  std::vector<ProfilePoint> profile(static_cast<std::size_t>(minorSegments));
  for (std::size_t m = 0; m < profile.size(); ++m) {
    const double angle = kTwoPi * static_cast<double>(m) / static_cast<double>(profile.size());
    profile[m] = {majorRadiusM + minorRadiusM * std::cos(angle), minorRadiusM * std::sin(angle)};
  }
  appendLathe(mesh, localToWorld, profile, majorSegments);
}

void appendHexPrism(TriangleMesh& mesh, const glm::dmat4& localToWorld, double acrossFlatsM, double lengthM) {
  assert(acrossFlatsM > 0.0 && lengthM > 0.0);
  const double circumradius = acrossFlatsM / std::sqrt(3.0);
  const ProfilePoint profile[] = {
      {0.0, 0.0}, {circumradius, 0.0, 6}, {circumradius, lengthM, 6}, {0.0, lengthM}};
  appendLathe(mesh, localToWorld, profile, 12);
}

void appendPathTube(TriangleMesh& mesh, const glm::dmat4& localToWorld,
                    std::span<const glm::dvec3> centreline, double radiusM, int segments) {
  assert(centreline.size() >= 2 && radiusM > 0.0);
  const std::size_t count = centreline.size();
  // unit tangents: the mean direction of the two legs at interior points
  std::vector<glm::dvec3> tangent(count);
  for (std::size_t j = 0; j < count; ++j) {
    const glm::dvec3 in = j > 0 ? glm::normalize(centreline[j] - centreline[j - 1]) : glm::dvec3(0.0);
    const glm::dvec3 outward =
        j + 1 < count ? glm::normalize(centreline[j + 1] - centreline[j]) : glm::dvec3(0.0);
    tangent[j] = glm::normalize(in + outward);
  }
  // parallel transport of the section's u axis; v = t × u so that u × v = t
  std::vector<glm::dvec3> u(count);
  std::vector<glm::dvec3> v(count);
  u[0] = perpendicular(tangent[0]);
  for (std::size_t j = 0; j < count; ++j) {
    if (j > 0) {
      const glm::dvec3 projected = u[j - 1] - glm::dot(u[j - 1], tangent[j]) * tangent[j];
      u[j] = glm::length(projected) > 1e-9 ? glm::normalize(projected) : perpendicular(tangent[j]);
    }
    v[j] = glm::cross(tangent[j], u[j]);
  }
  const std::uint32_t s = toCount(segments);
  const AngleTable angles(s);
  MeshAppender out(mesh, localToWorld);
  // rings: apex at the start, one ring per centreline point, apex at the end
  appendRingLoop(
      out, count + 2, s, [&](std::size_t j) { return j == 0 || j == count + 1; },
      [&](std::size_t j, std::uint32_t i) {
        if (j == 0) return centreline.front();
        if (j == count + 1) return centreline.back();
        const std::size_t c = j - 1;
        return centreline[c] + radiusM * (angles.cosines[i] * u[c] + angles.sines[i] * v[c]);
      });
}

void appendHelixTube(TriangleMesh& mesh, const glm::dmat4& localToWorld, const HelixSpec& helix,
                     int samplesPerTurn, int segments) {
  assert(helix.turns > 0.0 && helix.helixRadiusM > helix.tubeRadiusM && helix.tubeRadiusM > 0.0);
  const auto spans =
      static_cast<std::size_t>(std::ceil(helix.turns * static_cast<double>(toCount(samplesPerTurn)) - 1e-9));
  std::vector<glm::dvec3> centreline(spans + 1);
  for (std::size_t k = 0; k <= spans; ++k) {
    const double turnsDone = helix.turns * static_cast<double>(k) / static_cast<double>(spans);
    const double angle = kTwoPi * turnsDone;
    centreline[k] = {helix.helixRadiusM * std::cos(angle), helix.helixRadiusM * std::sin(angle),
                     helix.pitchM * turnsDone};
  }
  appendPathTube(mesh, localToWorld, centreline, helix.tubeRadiusM, segments);
}

void appendSphericalSocket(TriangleMesh& mesh, const glm::dmat4& localToWorld, const SocketSpec& socket,
                           int segments, int cavityRings) {
  const double rc = socket.cavityRadiusM;
  assert(rc > 0.0 && socket.bottomDepthM > rc && cavityRings >= 1);
  assert(socket.openingAboveEquatorRad >= 0.0 && socket.openingAboveEquatorRad < kPi / 2.0);
  const double rimPolar = kPi / 2.0 - socket.openingAboveEquatorRad;  // from +z
  const double topZ = rc * std::cos(rimPolar);
  assert(socket.outerRadiusM > rc * std::sin(rimPolar));
  std::vector<ProfilePoint> profile = {
      {0.0, -socket.bottomDepthM}, {socket.outerRadiusM, -socket.bottomDepthM}, {socket.outerRadiusM, topZ}};
  for (int m = 0; m <= cavityRings; ++m) {
    const double polar =
        rimPolar + (kPi - rimPolar) * static_cast<double>(m) / static_cast<double>(cavityRings);
    const bool pole = m == cavityRings;
    profile.push_back({pole ? 0.0 : rc * std::sin(polar), pole ? -rc : rc * std::cos(polar)});
  }
  profile[3].zM = topZ;  // the rim lies exactly in the top face
  appendLathe(mesh, localToWorld, profile, segments);
}

void appendBlockWithHole(TriangleMesh& mesh, const glm::dmat4& localToWorld, const HoledBlockSpec& block,
                         int segments) {
  assert(block.holeRadiusM > 0.0 && block.holeRadiusM < block.halfWidthM);
  assert(block.heightM > 0.0 && block.holeDepthM > 0.0);
  const double corner = block.halfWidthM * std::sqrt(2.0);
  const double h = block.heightM;
  if (block.holeDepthM >= h) {
    const ProfilePoint profile[] = {
        {corner, 0.0, 4}, {corner, h, 4}, {block.holeRadiusM, h}, {block.holeRadiusM, 0.0}};
    appendLathe(mesh, localToWorld, profile, segments);
  } else {
    const double bottom = h - block.holeDepthM;
    const ProfilePoint profile[] = {
        {0.0, 0.0},   {corner, 0.0, 4}, {corner, h, 4}, {block.holeRadiusM, h}, {block.holeRadiusM, bottom},
        {0.0, bottom}};
    appendLathe(mesh, localToWorld, profile, segments);
  }
}

std::vector<glm::dvec3> filletedPolyline(std::span<const glm::dvec3> cornersM, double bendRadiusM,
                                         int samplesPerBend) {
  assert(cornersM.size() >= 2 && bendRadiusM > 0.0 && samplesPerBend >= 1);
  std::vector<glm::dvec3> points;
  points.reserve(cornersM.size() * static_cast<std::size_t>(samplesPerBend + 1));
  points.push_back(cornersM.front());
  for (std::size_t i = 1; i + 1 < cornersM.size(); ++i) {
    const glm::dvec3 legIn = cornersM[i] - cornersM[i - 1];
    const glm::dvec3 legOut = cornersM[i + 1] - cornersM[i];
    const glm::dvec3 d1 = glm::normalize(legIn);
    const glm::dvec3 d2 = glm::normalize(legOut);
    const double turn = std::acos(std::clamp(glm::dot(d1, d2), -1.0, 1.0));
    if (turn < 1e-6) {
      points.push_back(cornersM[i]);
      continue;
    }
    // tangent length, limited so that neighbouring arcs never meet
    const double halfTan = std::tan(turn / 2.0);
    const double available = 0.45 * std::min(glm::length(legIn), glm::length(legOut));
    const double tangentLength = std::min(bendRadiusM * halfTan, available);
    const double radius = tangentLength / halfTan;
    const glm::dvec3 arcStart = cornersM[i] - tangentLength * d1;
    const glm::dvec3 towardCentre = glm::normalize(d2 - glm::dot(d1, d2) * d1);
    const glm::dvec3 centre = arcStart + radius * towardCentre;
    for (int k = 0; k <= samplesPerBend; ++k) {
      const double angle = turn * static_cast<double>(k) / static_cast<double>(samplesPerBend);
      points.push_back(centre - radius * std::cos(angle) * towardCentre + radius * std::sin(angle) * d1);
    }
  }
  points.push_back(cornersM.back());
  return points;
}

glm::dmat4 frameAlongAxis(const glm::dvec3& originWorld, const glm::dvec3& axisWorld) {
  const glm::dvec3 z = glm::normalize(axisWorld);
  const glm::dvec3 x = perpendicular(z);
  const glm::dvec3 y = glm::cross(z, x);
  return glm::dmat4(glm::dvec4(x, 0.0), glm::dvec4(y, 0.0), glm::dvec4(z, 0.0), glm::dvec4(originWorld, 1.0));
}

void appendMesh(TriangleMesh& mesh, const TriangleMesh& source) {
  const auto offset = static_cast<std::uint32_t>(mesh.positionsWorld.size());
  mesh.positionsWorld.insert(mesh.positionsWorld.end(), source.positionsWorld.begin(),
                             source.positionsWorld.end());
  mesh.triangles.reserve(mesh.triangles.size() + source.triangles.size());
  for (const glm::uvec3& t : source.triangles) mesh.triangles.push_back(t + offset);
}

}  // namespace voxhap

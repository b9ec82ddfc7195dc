#pragma once
/// Closed-mesh primitives for procedural scenes (the built-in scenes and tests).
///
/// Every `append*` function adds one or more closed components to a `TriangleMesh`:
/// vertices are shared, every edge is used by exactly two triangles walked in opposite
/// directions, triangles are counter-clockwise seen from outside (outward normals by the
/// right-hand rule) and none is degenerate. A shape is described in its own local frame
/// (metres) and mapped to the world by `localToWorld`, an affine transform; a mirroring
/// transform flips the winding so that normals still point outward. Positions are
/// computed in double precision and stored as float.
///
/// Most shapes are surfaces of revolution built by `appendLathe` from a profile loop in
/// the (radius, z) half-plane; the loop may touch the axis (solid shapes, closed by
/// triangle fans) or not (rings, tubes, tori). Rings may be circles or regular polygons
/// sampled at the same angles, so that a square block with a round hole or a bolt with a
/// hexagonal head is a single closed lathe.

#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "haptics/scene/scene.h"

namespace voxhap {

/// One vertex of a lathe profile, in the local (radius, z) half-plane.
struct ProfilePoint {
  double radiusM = 0.0;  ///< distance from the local z axis, m; 0 puts the point on the axis
  double zM = 0.0;       ///< position along the local z axis, m
  /// 0: the ring is a circle of radius `radiusM`. n >= 3: a regular n-gon with
  /// circumradius `radiusM` whose flats face the angles 2πk/n (a square has flats facing
  /// ±x and ±y); the lathe's segment count must then be a multiple of 2n.
  int polygonSides = 0;
};

/// Appends an axis-aligned box centred on the local origin (12 triangles).
/// `halfExtentsM`: half the size along local x, y, z, m, all > 0.
void appendBox(TriangleMesh& mesh, const glm::dmat4& localToWorld, const glm::dvec3& halfExtentsM);

/// Appends a sphere centred on the local origin: an octahedron whose faces are split
/// `subdivisions` times into four, every vertex projected onto the sphere; 8·4^k
/// triangles (k = 4 gives 2048). The vertices lie on the sphere, the faces inside it.
void appendGeodesicSphere(TriangleMesh& mesh, const glm::dmat4& localToWorld, double radiusM,
                          int subdivisions);

/// Appends the surface swept by revolving `profile` about the local z axis, sampled at
/// `segments` angles 2πi/segments (i = 0 … segments-1). `profile` is a closed loop,
/// counter-clockwise in the (radius, z) plane (radius to the right, z up), simple, with
/// radii >= 0; points with radius 0 become single vertices closed by fans, and loop edges
/// lying on the axis are skipped. Adds 2·segments triangles per edge off the axis and
/// `segments` per edge with one end on the axis.
void appendLathe(TriangleMesh& mesh, const glm::dmat4& localToWorld, std::span<const ProfilePoint> profile,
                 int segments);

/// Appends a solid cylinder along local z from z = 0 to z = `lengthM`, with flat caps
/// (4·segments triangles).
void appendCylinder(TriangleMesh& mesh, const glm::dmat4& localToWorld, double radiusM, double lengthM,
                    int segments);

/// Appends a hollow cylinder (annulus) along local z from z = 0 to z = `lengthM`
/// (8·segments triangles). Requires 0 < innerRadiusM < outerRadiusM.
void appendHollowCylinder(TriangleMesh& mesh, const glm::dmat4& localToWorld, double innerRadiusM,
                          double outerRadiusM, double lengthM, int segments);

/// Appends a torus around the local z axis, centred on the origin
/// (2·majorSegments·minorSegments triangles). Requires 0 < minorRadiusM < majorRadiusM.
void appendTorus(TriangleMesh& mesh, const glm::dmat4& localToWorld, double majorRadiusM, double minorRadiusM,
                 int majorSegments, int minorSegments);

/// Appends a hexagonal prism along local z from z = 0 to z = `lengthM`, flats facing ±x
/// (24 triangles). `acrossFlatsM` is the spanner size, m.
void appendHexPrism(TriangleMesh& mesh, const glm::dmat4& localToWorld, double acrossFlatsM, double lengthM);

/// Appends a round tube of radius `radiusM` swept along `centreline` (local frame, at
/// least 2 distinct consecutive points) with flat end caps; cross-sections are
/// perpendicular to the local direction of the line and carried along by parallel
/// transport (no twist). Adds 2·segments·(points-1) + 2·segments triangles. The caller
/// keeps bends wider than the tube radius so that the surface does not fold.
void appendPathTube(TriangleMesh& mesh, const glm::dmat4& localToWorld,
                    std::span<const glm::dvec3> centreline, double radiusM, int segments);

/// A helix around the local z axis, starting at (helixRadiusM, 0, 0) and rising
/// counter-clockwise seen from +z.
struct HelixSpec {
  double helixRadiusM = 0.0;  ///< distance of the tube's centreline from the axis, m
  double pitchM = 0.0;        ///< rise per turn, m; keep > 2·tubeRadiusM so turns do not touch
  double turns = 1.0;         ///< number of turns (may be fractional), > 0
  double tubeRadiusM = 0.0;   ///< radius of the tube's cross-section, m
};

/// Appends a round tube swept along a helix, with flat end caps, sampled at
/// `samplesPerTurn` cross-sections per turn. Triangles: 2·segments·n + 2·segments with
/// n = ceil(turns·samplesPerTurn) spans.
void appendHelixTube(TriangleMesh& mesh, const glm::dmat4& localToWorld, const HelixSpec& helix,
                     int samplesPerTurn, int segments);

/// A cylindrical block with a spherical cup opening upward (a ball socket), centred on the
/// cavity's centre: the cavity is the part of the sphere below `openingAboveEquatorRad`
/// above its equator, the block's top face is at that height, its bottom at
/// z = -bottomDepthM.
struct SocketSpec {
  double cavityRadiusM = 0.0;           ///< radius of the spherical cavity, m
  double outerRadiusM = 0.0;            ///< radius of the block, m (> the opening's radius)
  double bottomDepthM = 0.0;            ///< depth of the bottom face below the centre, m (> cavity)
  double openingAboveEquatorRad = 0.0;  ///< in [0, π/2): 0 is a hemisphere
};

/// Appends a ball socket (a lathe): `segments` around, `cavityRings` edges along the
/// cavity's meridian from the rim to the bottom pole. Triangles: segments·(4 + 2·cavityRings).
void appendSphericalSocket(TriangleMesh& mesh, const glm::dmat4& localToWorld, const SocketSpec& socket,
                           int segments, int cavityRings);

/// A square block with a round hole along local z: the block spans
/// x, y ∈ [-halfWidthM, halfWidthM], z ∈ [0, heightM]; the hole opens in the top face.
struct HoledBlockSpec {
  double halfWidthM = 0.0;   ///< half the block's width, m
  double heightM = 0.0;      ///< block height along z, m
  double holeRadiusM = 0.0;  ///< radius of the hole's vertices, m (< halfWidthM)
  double holeDepthM = 0.0;   ///< blind hole depth, m; >= heightM makes a through hole
};

/// Appends a square block with a round hole (a lathe with square outer rings).
/// `segments` must be a multiple of 8. Triangles: 8·segments, through or blind (the bottom
/// annulus of a through hole becomes two fans, bottom face and hole bottom, when blind).
void appendBlockWithHole(TriangleMesh& mesh, const glm::dmat4& localToWorld, const HoledBlockSpec& block,
                         int segments);

/// Samples a polyline through `cornersM` with each interior corner replaced by a circular
/// arc of radius up to `bendRadiusM` (smaller where the legs are short), `samplesPerBend`
/// spans per arc. Straight legs keep only their end points. Requires >= 2 corners.
std::vector<glm::dvec3> filletedPolyline(std::span<const glm::dvec3> cornersM, double bendRadiusM,
                                         int samplesPerBend);

/// A rigid frame whose local z axis is `axisWorld` (any length > 0) and whose origin is
/// `originWorld`; the local x axis is a fixed, deterministic perpendicular.
glm::dmat4 frameAlongAxis(const glm::dvec3& originWorld, const glm::dvec3& axisWorld);

/// Appends every vertex and triangle of `source` to `mesh`, offsetting the indices.
void appendMesh(TriangleMesh& mesh, const TriangleMesh& source);

}  // namespace voxhap

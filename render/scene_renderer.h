#pragma once
/// Draws a Scene as the front end shows it (DESIGN §9): the parts in their base colours,
/// the moving objects at their poses and coloured by proximity, shadow voxels, an
/// optional force arrow and contact points; static objects through the static cache.
///
/// Built once per scene: every object's buffers are uploaded at construction. Per frame
/// the caller sets what changed (poses, proximity, overlays) and calls draw(); only the
/// moving objects' colour streams and the overlays' instances are uploaded then. A pose
/// maps an object's scene-placement coordinates to where it is now,
/// p_now = orientation · p + position (the identity pose: where the scene put it).
/// Needs a current GL context from construction to destruction, on one thread.

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "haptics/dynamics/pose.h"
#include "haptics/scene/scene.h"
#include "render/orbit_camera.h"
#include "render/proximity_ramp.h"
#include "render/static_cache.h"

namespace voxhap::render {

/// Colours and sizes of what the renderer adds to the scene.
struct SceneRendererOptions {
  glm::vec3 backgroundDisplay{0.12f, 0.13f, 0.16f};  ///< sRGB display values, 0…1
  /// The proximity ramp's range, m: beyond it a vertex shows its part's own colour
  /// (the app sets e.g. 5 voxels).
  float proximityRangeM = kDefaultProximityRangeM;
  glm::vec4 shadowVoxelColour{0.45f, 0.1f, 0.85f, 0.6f};  ///< linear RGB, alpha blended
  glm::vec4 contactPointColour{1.0f, 1.0f, 1.0f, 1.0f};   ///< linear RGB, opaque
  glm::vec4 forceArrowColour{0.1f, 0.9f, 0.2f, 1.0f};     ///< linear RGB
  /// Another instance of a moving object (a shared part on another peer, while the
  /// instances diverge): linear RGB, alpha blended, so that it reads as not this one.
  glm::vec4 otherInstanceColour{1.0f, 0.25f, 0.0f, 0.6f};
};

/// The force on the moving object, drawn as an arrow from `originWorld`.
struct ForceArrow {
  glm::dvec3 originWorld{0.0};  ///< m
  glm::dvec3 forceN{0.0};       ///< world frame, N
  double metresPerNewton = 0.01;
};

/// Counters of the last frames, for tests and the HUD.
struct SceneRendererStats {
  StaticCacheStats cache;               ///< redraws vs. reuses of the static cache
  std::uint64_t framesDrawn = 0;        ///< draw() calls
  std::uint64_t staticFramesDrawn = 0;  ///< frames that drew the static objects (cache redraws or no cache)
};

/// Draws one Scene. Not copyable.
class SceneRenderer {
public:
  /// Uploads `scene`; `movingNames` name the objects that move (their order is the
  /// movingIndex of the setters); every other object is static. Throws voxhap::Error
  /// naming an unknown or repeated object, or when GL cannot hold the scene.
  SceneRenderer(const Scene& scene, std::span<const std::string> movingNames,
                const SceneRendererOptions& options = {});
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  std::size_t movingCount() const;
  /// Vertices of a moving object's parts, which setProximity takes one distance each for.
  std::uint32_t movingVertexCount(std::size_t movingIndex) const;
  /// The whole scene's bounds at the scene placement (for OrbitCamera::frame).
  const Bounds& sceneBounds() const { return boundsWorld_; }
  const SceneRendererOptions& options() const { return options_; }

  /// Where a moving object is now. Throws voxhap::Error on a bad index.
  void setPose(std::size_t movingIndex, const Pose& pose);
  /// One distance per vertex of the moving object's parts (scene order; m, +inf far)
  /// coloured through proximityColour over the options' range. Throws voxhap::Error when
  /// the count is not movingVertexCount.
  void setProximity(std::size_t movingIndex, std::span<const float> vertexDistanceM);
  /// Back to the parts' own colours.
  void clearProximity(std::size_t movingIndex);
  void setProximityRange(float rangeM);
  /// Static surface voxels near the moving objects, drawn as cubes of `voxelSizeM`
  /// centred on `centresWorld` (m), blended over the scene. Empty: none.
  void setShadowVoxels(std::span<const glm::vec3> centresWorld, float voxelSizeM);
  /// Contact points as small opaque cubes of `sizeM`. Empty: none.
  void setContactPoints(std::span<const glm::vec3> pointsWorld, float sizeM);
  void setForceArrow(const std::optional<ForceArrow>& arrow);
  /// Another instance of a moving object at `pose` (a shared part as another peer has it),
  /// drawn in the options' otherInstanceColour over the scene; nullopt: none. Throws
  /// voxhap::Error on a bad index.
  void setOtherInstance(std::size_t movingIndex, const std::optional<Pose>& pose);

  /// Draws a frame into the default framebuffer over `viewportPx` (its full size).
  /// `useStaticCache`: static objects from the cache (redrawn only when the view or the
  /// size changed); false draws every object (for comparison and tests).
  void draw(const OrbitCamera& camera, const glm::ivec2& viewportPx, bool useStaticCache);

  SceneRendererStats stats() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  SceneRendererOptions options_;
  Bounds boundsWorld_;
};

}  // namespace voxhap::render

#pragma once
/// The static-scene cache (the paper's FlyThru, §7; DESIGN §9): the static objects are
/// drawn once into an offscreen colour texture and depth texture; while the eye and the
/// viewport size stay the same, each frame only copies both into the default framebuffer
/// (a full-screen pass that writes the cached colour and gl_FragDepth), and the moving
/// objects are then drawn over it, depth-tested against the cached depth. So the frame
/// rate does not depend on how much static geometry there is while the eye is still.
///
/// The cache is keyed on the view-projection matrix and the size, not on a camera's
/// revision, so any camera (or two cameras with the same view) gives the right answer.
/// Needs a current GL context throughout; one cache per context.

#include <cstdint>
#include <functional>
#include <memory>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace voxhap::render {

/// What the cached image depends on.
struct StaticCacheKey {
  glm::dmat4 viewProjection{1.0};
  glm::ivec2 sizePx{0};
  bool operator==(const StaticCacheKey&) const = default;
};

/// Counters of the cache's use: how often it was drawn vs. copied as it was.
struct StaticCacheStats {
  std::uint64_t redraws = 0;  ///< frames that drew the static objects into the cache
  std::uint64_t reuses = 0;   ///< frames that only copied the cached image
};

/// An offscreen colour + depth image of the static objects. Not copyable.
class StaticCache {
public:
  StaticCache();
  ~StaticCache();
  StaticCache(const StaticCache&) = delete;
  StaticCache& operator=(const StaticCache&) = delete;

  /// Makes the cache hold the static scene for `key`: when the key differs from the last
  /// one (or after invalidate), binds the offscreen framebuffer, sets the viewport, clears
  /// to `clearDisplay` (display RGB) and calls `drawStatic`, then binds the default
  /// framebuffer again; otherwise counts a reuse. Returns whether it redrew.
  bool update(const StaticCacheKey& key, const glm::vec3& clearDisplay,
              const std::function<void()>& drawStatic);
  /// Writes the cached colour and depth over the whole viewport of the bound draw
  /// framebuffer (whose size must be the key's). Leaves depth test on with GL_LESS.
  void copyToFramebuffer() const;
  /// Forgets the image (e.g. the static scene changed): the next update redraws.
  void invalidate() { valid_ = false; }

  const StaticCacheStats& stats() const { return stats_; }

private:
  void resize(const glm::ivec2& sizePx);

  struct Programs;
  std::uint32_t framebuffer_ = 0;
  std::uint32_t colourTexture_ = 0;
  std::uint32_t depthTexture_ = 0;
  std::uint32_t emptyVao_ = 0;
  glm::ivec2 sizePx_{0};
  StaticCacheKey key_;
  bool valid_ = false;
  StaticCacheStats stats_;
  std::unique_ptr<Programs> programs_;
};

}  // namespace voxhap::render

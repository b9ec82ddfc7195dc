#include "render/scene_renderer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <epoxy/gl.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "haptics/core/error.h"
#include "haptics/geometry/mesh_builder.h"
#include "render/mesh_buffers.h"
#include "render/overlay_meshes.h"
#include "render/shaders.h"

namespace voxhap::render {
namespace {

/// A moving object: its buffers (with a colour stream), pose and proximity colours.
struct MovingObject {
  std::string name;
  MeshBuffers buffers;
  Pose pose;
  std::optional<Pose> otherInstance;
  bool proximityShown = false;
  std::vector<Rgba8> coloursScratch;  ///< sized once: no allocation per frame
};

glm::mat4 modelMatrixOf(const Pose& pose) {
  glm::dmat4 m = glm::mat4_cast(pose.orientation);
  m[3] = glm::dvec4(pose.position, 1.0);
  return glm::mat4(m);
}

}  // namespace

struct SceneRenderer::Impl {
  LitShader lit;
  FlatShader flat;
  StaticCache cache;
  std::vector<MeshBuffers> statics;
  std::vector<MovingObject> moving;
  InstancedCubes shadowCubes;
  float shadowVoxelSizeM = 0.0f;
  InstancedCubes contactCubes;
  float contactSizeM = 0.0f;
  MeshBuffers arrowBuffers{unitArrowObject(), false};
  std::optional<ForceArrow> arrow;
  std::uint64_t framesDrawn = 0;
  std::uint64_t staticFramesDrawn = 0;

  MovingObject& movingAt(std::size_t index) {
    if (index >= moving.size()) {
      throw Error("moving object " + std::to_string(index) + ": the renderer has " +
                  std::to_string(moving.size()));
    }
    return moving[index];
  }

  /// Draws every part of `buffers` with the lit program in use.
  void drawObject(const MeshBuffers& buffers, const glm::mat4& modelToWorld, bool vertexColours,
                  const glm::vec4* colourOverride = nullptr) const {
    glUniformMatrix4fv(lit.modelToWorld, 1, GL_FALSE, glm::value_ptr(modelToWorld));
    const glm::mat3 normalToWorld(modelToWorld);
    glUniformMatrix3fv(lit.normalToWorld, 1, GL_FALSE, glm::value_ptr(normalToWorld));
    glUniform1i(lit.useVertexColour, vertexColours ? 1 : 0);
    buffers.bind();
    for (std::size_t p = 0; p < buffers.parts().size(); ++p) {
      const PartRange& part = buffers.parts()[p];
      if (part.closed) {
        glEnable(GL_CULL_FACE);
      } else {
        glDisable(GL_CULL_FACE);
      }
      glUniform4fv(lit.baseColour, 1, glm::value_ptr(colourOverride ? *colourOverride : part.baseColor));
      buffers.drawPart(p);
    }
    glBindVertexArray(0);
    glDisable(GL_CULL_FACE);
  }

  /// Uses the lit program with the frame's camera and lights.
  void useLit(const glm::mat4& worldToClip, const OrbitCamera& camera) const {
    lit.program.use();
    glUniformMatrix4fv(lit.worldToClip, 1, GL_FALSE, glm::value_ptr(worldToClip));
    // a key light above and left of the eye and a weaker fill from the right, both
    // moving with the eye so that what faces the viewer is lit
    const glm::dvec3 back = -camera.forwardWorld();
    const glm::vec3 key(glm::normalize(back + 0.8 * camera.upWorld() - 0.5 * camera.rightWorld()));
    const glm::vec3 fill(glm::normalize(0.6 * back - 0.3 * camera.upWorld() + 0.8 * camera.rightWorld()));
    glUniform3fv(lit.keyLightWorld, 1, glm::value_ptr(key));
    glUniform3fv(lit.fillLightWorld, 1, glm::value_ptr(fill));
  }

  void drawStatics(const glm::mat4& worldToClip, const OrbitCamera& camera) const {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    useLit(worldToClip, camera);
    for (const MeshBuffers& buffers : statics) drawObject(buffers, glm::mat4(1.0f), false);
  }
};

SceneRenderer::SceneRenderer(const Scene& scene, std::span<const std::string> movingNames,
                             const SceneRendererOptions& options)
    : options_(options), boundsWorld_(scene.bounds()) {
  std::vector<int> movingIndexOf(scene.objects.size(), -1);
  for (std::size_t m = 0; m < movingNames.size(); ++m) {
    const auto it = std::find_if(scene.objects.begin(), scene.objects.end(),
                                 [&](const SceneObject& o) { return o.name == movingNames[m]; });
    if (it == scene.objects.end()) {
      throw Error(scene.sourceName + ": no object named " + movingNames[m] + " to move");
    }
    const auto index = static_cast<std::size_t>(it - scene.objects.begin());
    if (movingIndexOf[index] >= 0)
      throw Error(scene.sourceName + ": object " + movingNames[m] + " named twice");
    movingIndexOf[index] = static_cast<int>(m);
  }
  impl_ = std::make_unique<Impl>();
  impl_->moving.reserve(movingNames.size());
  for (const std::string& name : movingNames) {
    MovingObject object{name, MeshBuffers(*scene.find(name), true), Pose{}, std::nullopt, false, {}};
    object.coloursScratch.resize(object.buffers.vertexCount());
    impl_->moving.push_back(std::move(object));
  }
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    if (movingIndexOf[i] < 0) impl_->statics.emplace_back(scene.objects[i], false);
  }
  glFrontFace(GL_CCW);
  glCullFace(GL_BACK);
}

SceneRenderer::~SceneRenderer() = default;

std::size_t SceneRenderer::movingCount() const {
  return impl_->moving.size();
}

std::uint32_t SceneRenderer::movingVertexCount(std::size_t movingIndex) const {
  return impl_->movingAt(movingIndex).buffers.vertexCount();
}

void SceneRenderer::setPose(std::size_t movingIndex, const Pose& pose) {
  impl_->movingAt(movingIndex).pose = pose;
}

void SceneRenderer::setProximity(std::size_t movingIndex, std::span<const float> vertexDistanceM) {
  MovingObject& object = impl_->movingAt(movingIndex);
  if (vertexDistanceM.size() != object.buffers.vertexCount()) {
    throw Error("proximity of " + object.name + ": " + std::to_string(vertexDistanceM.size()) +
                " distances for " + std::to_string(object.buffers.vertexCount()) + " vertices");
  }
  for (const PartRange& part : object.buffers.parts()) {
    for (std::uint32_t v = part.firstVertex; v < part.firstVertex + part.vertexCount; ++v) {
      object.coloursScratch[v] =
          toRgba8(proximityColour(vertexDistanceM[v], options_.proximityRangeM, part.baseColor));
    }
  }
  object.buffers.updateColours(object.coloursScratch);
  object.proximityShown = true;
}

void SceneRenderer::clearProximity(std::size_t movingIndex) {
  impl_->movingAt(movingIndex).proximityShown = false;
}

void SceneRenderer::setProximityRange(float rangeM) {
  if (!(rangeM > 0.0f)) throw Error("proximity range must be > 0 m, not " + std::to_string(rangeM));
  options_.proximityRangeM = rangeM;
}

void SceneRenderer::setShadowVoxels(std::span<const glm::vec3> centresWorld, float voxelSizeM) {
  impl_->shadowCubes.setCentres(centresWorld);
  impl_->shadowVoxelSizeM = voxelSizeM;
}

void SceneRenderer::setContactPoints(std::span<const glm::vec3> pointsWorld, float sizeM) {
  impl_->contactCubes.setCentres(pointsWorld);
  impl_->contactSizeM = sizeM;
}

void SceneRenderer::setForceArrow(const std::optional<ForceArrow>& arrow) {
  impl_->arrow = arrow;
}

void SceneRenderer::setOtherInstance(std::size_t movingIndex, const std::optional<Pose>& pose) {
  impl_->movingAt(movingIndex).otherInstance = pose;
}

void SceneRenderer::draw(const OrbitCamera& camera, const glm::ivec2& viewportPx, bool useStaticCache) {
  Impl& d = *impl_;
  const glm::dmat4 viewProjection = camera.viewProjection(viewportPx);
  const glm::mat4 worldToClip(viewProjection);
  const glm::vec3& bg = options_.backgroundDisplay;

  if (useStaticCache) {
    const bool redrawn = d.cache.update(StaticCacheKey{viewProjection, viewportPx}, bg,
                                        [&] { d.drawStatics(worldToClip, camera); });
    if (redrawn) ++d.staticFramesDrawn;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, viewportPx.x, viewportPx.y);
    d.cache.copyToFramebuffer();
  } else {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, viewportPx.x, viewportPx.y);
    glClearColor(bg.r, bg.g, bg.b, 1.0f);
    glClearDepth(1.0);
    glDepthMask(GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    d.drawStatics(worldToClip, camera);
    ++d.staticFramesDrawn;
  }

  // moving geometry over the static image, depth-tested against its depth
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  d.useLit(worldToClip, camera);
  for (const MovingObject& object : d.moving) {
    d.drawObject(object.buffers, modelMatrixOf(object.pose), object.proximityShown);
  }
  if (d.arrow) {
    const double lengthM = glm::length(d.arrow->forceN) * d.arrow->metresPerNewton;
    if (lengthM > 0.0 && std::isfinite(lengthM)) {
      const glm::dmat4 model =
          glm::scale(frameAlongAxis(d.arrow->originWorld, d.arrow->forceN), glm::dvec3(lengthM));
      d.drawObject(d.arrowBuffers, glm::mat4(model), false, &options_.forceArrowColour);
    }
  }
  // other instances blended over what is drawn, without hiding what lies behind them
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE);
  for (const MovingObject& object : d.moving) {
    if (object.otherInstance)
      d.drawObject(object.buffers, modelMatrixOf(*object.otherInstance), false,
                   &options_.otherInstanceColour);
  }
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);

  // overlays in flat colours: contact points opaque, shadow voxels blended without
  // writing depth so that they tint whatever lies behind them
  d.flat.program.use();
  glUniformMatrix4fv(d.flat.worldToClip, 1, GL_FALSE, glm::value_ptr(worldToClip));
  const glm::mat4 identity(1.0f);
  glUniformMatrix4fv(d.flat.modelToWorld, 1, GL_FALSE, glm::value_ptr(identity));
  if (d.contactCubes.count() > 0) {
    glUniform1f(d.flat.instanceScale, d.contactSizeM);
    glUniform4fv(d.flat.colour, 1, glm::value_ptr(options_.contactPointColour));
    d.contactCubes.draw();
  }
  if (d.shadowCubes.count() > 0) {
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_LEQUAL);
    glUniform1f(d.flat.instanceScale, d.shadowVoxelSizeM);
    glUniform4fv(d.flat.colour, 1, glm::value_ptr(options_.shadowVoxelColour));
    d.shadowCubes.draw();
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glDisable(GL_BLEND);
  }
  ++d.framesDrawn;
}

SceneRendererStats SceneRenderer::stats() const {
  return SceneRendererStats{impl_->cache.stats(), impl_->framesDrawn, impl_->staticFramesDrawn};
}

}  // namespace voxhap::render

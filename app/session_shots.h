#pragma once
/// Pictures of a recorded session (`voxhap demo` without a window): the scene drawn by
/// render::SceneRenderer at poses a peer showed, written as PNG files, in a hidden window
/// (an X display is needed: a virtual one from `xvfb-run -a` will do).

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "haptics/dynamics/pose.h"
#include "haptics/scene/scene.h"

namespace voxhap::cli {

/// One picture: every moving object where a peer showed it.
struct SessionShot {
  std::filesystem::path file;
  std::vector<Pose> poses;  ///< per moving object, relative to its place in the scene
  /// Per moving object (or empty): another instance of it, drawn marked (a shared part as
  /// another sharer had it while the instances diverged).
  std::vector<std::optional<Pose>> otherInstances;
};

/// Draws each shot of `scene`, whose objects `moving` move, from an eye that frames
/// `focusWorld`, at `sizePx`, and writes it. Throws voxhap::Error when there is no
/// display or a file cannot be written.
void writeSessionShots(const Scene& scene, std::span<const std::string> moving, const Bounds& focusWorld,
                       std::span<const SessionShot> shots, const glm::ivec2& sizePx);

/// The box around `object` at `pose` (its scene placement moved by it).
Bounds boundsAt(const SceneObject& object, const Pose& pose);

}  // namespace voxhap::cli

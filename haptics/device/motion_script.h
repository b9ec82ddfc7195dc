#pragma once
/// Motion scripts for the scripted device (DESIGN §5): time-stamped 6-DOF handle poses,
/// played back by interpolation.
///
/// Text format, one pose per line: `t qw qx qy qz tx ty tz` — time (s), the rotation as
/// a quaternion (normalized on load; need not be unit, must not be zero) and the
/// translation (m). A pose is the handle's rigid motion relative to where the scene file
/// puts the object; since the object's local frame is the scene-file placement, it is
/// directly the target local→world pose of the object. `#` starts a comment (whole line
/// or trailing); blank lines are skipped; fields are separated by spaces or tabs. Times
/// are finite, strictly increasing, the first ≥ 0; playback starts at t = 0.
///
/// Parsing throws voxhap::Error "FILE:LINE: what is wrong"; `sample` is noexcept and
/// allocation-free, for the 1 kHz frame.

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "haptics/dynamics/pose.h"

namespace voxhap {

/// One pose of a motion script.
struct MotionKeyframe {
  double timeS = 0.0;  ///< s from the start of playback
  Pose handleWorld;    ///< target local→world pose of the object (unit quaternion)
};

/// A validated, read-only motion script.
class MotionScript {
public:
  /// Validates `keyframes` (at least one; finite; times strictly increasing, the first
  /// ≥ 0; quaternions non-zero, then normalized). Throws voxhap::Error
  /// "SOURCE: keyframe N: what is wrong" (N from 1).
  MotionScript(std::vector<MotionKeyframe> keyframes, std::string sourceName);

  /// Handle pose at `tS` (s): slerp of the rotation (shortest arc) and lerp of the
  /// translation between the two surrounding keyframes, exact at keyframes; the first
  /// pose before the first keyframe (and for NaN), the last after the last.
  Pose sample(double tS) const noexcept;

  /// Time of the last keyframe, s: how long playback from t = 0 takes to reach the end.
  double durationS() const noexcept { return keyframes_.back().timeS; }

  /// The keyframes, in time order (quaternions normalized).
  std::span<const MotionKeyframe> keyframes() const noexcept { return keyframes_; }

  /// File name or other source, for messages.
  const std::string& sourceName() const noexcept { return sourceName_; }

private:
  std::vector<MotionKeyframe> keyframes_;
  std::string sourceName_;
};

/// Parses a text motion script; `fileName` names it in error messages.
MotionScript parseMotionScript(std::string_view text, const std::string& fileName);

/// Reads and parses a text motion script. Throws voxhap::Error naming the file when it
/// cannot be read or does not parse.
MotionScript loadMotionScript(const std::filesystem::path& file);

}  // namespace voxhap

#pragma once
/// A scripted collaborative session of peers inside this process, on loopback (DESIGN §8):
/// the main job of `voxhap demo`. Each user's peer is a whole haptic controller
/// (InProcessController with a PeerRunOptions) that owns (type-1) or shares (type-2) one
/// part; once every part is where its users need it, every user grabs it with a motion
/// script at the same moment, and the session records what each peer shows through its
/// front-end protocol, as any front end would, until every script has played.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli/console.h"
#include "haptics/dynamics/pose.h"
#include "haptics/sim/scene_model.h"

namespace voxhap::cli {

/// One user of the session: the part it moves, and how.
struct CrewUser {
  std::string name;
  std::string object;            ///< a moving object of the scene
  bool share = false;            ///< shares it with the other users that do (type-2), else owns it
  std::filesystem::path script;  ///< its handle's motion, played from the common start
};

struct CrewSessionOptions {
  std::string scene;
  std::vector<CrewUser> users;  ///< the first user's peer makes the session
  SceneModelOptions model;
  double playS = 30.0;  ///< how long every peer plays the scripts, simulated s
  bool passivity = true;
  bool realtime = true;
  double sampleHz = 20.0;    ///< how often each peer's poses are recorded
  double patienceS = 120.0;  ///< for the peers to start, join and settle who has what
  /// Called once every peer has started, with each user's controller's front-end port on
  /// 127.0.0.1 (in the users' order), e.g. to watch one through a window.
  std::function<void(const std::vector<std::uint16_t>&)> onStarted;
};

/// What one peer showed at one moment.
struct CrewSample {
  std::size_t peer = 0;
  double playedS = 0.0;         ///< its simulated time since the common grab
  std::vector<Pose> poses;      ///< every moving object, relative to its place in the scene
  std::vector<bool> divergent;  ///< every moving object: a shared one's instances are apart
  /// every moving object: while divergent, the instance furthest from the one this peer shows
  std::vector<std::optional<Pose>> otherInstance;
  std::vector<std::uint32_t> contacts;
};

struct CrewSessionResult {
  std::vector<std::string> objects;       ///< the moving objects, in the samples' order
  std::vector<CrewSample> samples;        ///< in the order they were taken
  std::vector<nlohmann::json> summaries;  ///< each peer's controller summary (JSON)
  std::vector<std::string> logs;          ///< each peer's diagnostics
  double wallS = 0.0;                     ///< from the grab to the last sample
};

/// Runs the session; `progress` (may be empty) gets the share of the scripts played.
/// Throws voxhap::Error naming the peer and what went wrong (it did not start, join, or
/// get its part in time, or simulated too slowly).
CrewSessionResult runCrewSession(const CrewSessionOptions& options, Console& console,
                                 const std::function<void(double)>& progress = {});

}  // namespace voxhap::cli

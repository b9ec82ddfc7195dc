#pragma once
/// `voxhap controller`: the haptic controller as a process (DESIGN §7, paper §6). It
/// builds the scene, starts the 1 kHz haptic thread, serves front ends over TCP on the
/// calling thread (the comms thread) until SIGINT, SIGTERM, a Shutdown request or the
/// asked duration, then stops the haptic thread and reports its period statistics.

#include <atomic>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "app/cli/console.h"
#include "haptics/sim/scene_model.h"

namespace voxhap::cli {

/// A controller that is one peer of a collaborative session (`voxhap peer`, DESIGN §8).
struct PeerRunOptions {
  std::string listenHost = "127.0.0.1";  ///< UDP, for the other peers
  std::uint16_t listenPort = 0;          ///< 0: any free port (printed)
  std::string advertise;                 ///< "HOST:PORT" the others send to; empty: the listening one
  std::string joinHost;                  ///< a member to join through; empty: the first member
  std::uint16_t joinPort = 0;
  std::string keyFile;    ///< the session key; empty: the first member makes one and prints it
  std::string take;       ///< an object to ask for at once; --device holds it once it is ours
  std::string share;      ///< an object to share (type-2); --device holds it once shared
  bool passivity = true;  ///< the shared object's coupling through the passivity controller
  std::string name;       ///< the user, for the others
  double streamHz = 200.0;
  double timeoutS = 2.0;
  double joinPatienceS = 10.0;
};

struct ControllerOptions {
  std::string scene;
  std::vector<std::string> moving;  ///< objects or groups the controller moves
  SceneModelOptions model;
  std::string listenHost = "127.0.0.1";
  std::uint16_t listenPort = 7400;  ///< 0: any free port (printed)
  std::string token;                ///< required of clients when not empty
  std::string device;               ///< "script:FILE" grabs moving[0] at start; empty: none
  std::optional<double> durationS;  ///< stop after this much wall time
  bool realtime = true;             ///< try mlockall and SCHED_FIFO
  bool frameHelper = false;         ///< HapticLoopOptions::frameHelper
  bool json = false;
  /// Called on the controller's thread once it listens, with the port (in-process use).
  std::function<void(std::uint16_t port)> onListening;
  /// Set: this controller is a peer of a session (its --device then holds peer->take).
  std::optional<PeerRunOptions> peer;
  /// When set, the controller stops within its housekeeping period once this holds true.
  const std::atomic<bool>* stopRequested = nullptr;
};

/// Runs the controller; returns when it has stopped, after printing its summary on `out`
/// (text, or one JSON document). Notes, the listening address and the reasons connections
/// were closed go to `console`. Throws voxhap::Error for a scene, device or address it
/// cannot use.
void runController(const ControllerOptions& options, Console& console, std::ostream& out);

}  // namespace voxhap::cli

#pragma once
/// A haptic controller run inside this process on a thread of its own, listening on a free
/// loopback port: what `voxhap view SCENE` talks to over the protocol, as it would to a
/// controller elsewhere, and what `voxhap bench latency` measures.

#include <atomic>
#include <cstdint>
#include <exception>
#include <future>
#include <sstream>
#include <string>
#include <thread>

#include "app/controller/controller_run.h"

namespace voxhap::cli {

class InProcessController {
public:
  /// Starts runController with `options` on 127.0.0.1, port chosen by the system, and a
  /// JSON summary; returns once it listens (after loading options.scene, if any). Throws
  /// what the controller threw when it stopped before listening.
  InProcessController(ControllerOptions options, Console& console);
  /// Asks it to stop (if it still runs) and waits for it.
  ~InProcessController();
  InProcessController(const InProcessController&) = delete;
  InProcessController& operator=(const InProcessController&) = delete;

  std::uint16_t port() const { return port_; }
  /// Whether it has stopped (a client's shutdown, its duration, an error).
  bool stopped() const { return stopped_.load(); }
  /// Asks it to stop, waits, and returns its JSON summary; throws voxhap::Error with the
  /// controller's message when it failed.
  std::string stopAndWait();

private:
  std::atomic<bool> stopRequested_{false};
  std::atomic<bool> stopped_{false};
  std::promise<std::uint16_t> listening_;
  bool listened_ = false;  ///< listening_ has a value (the controller's thread only)
  std::ostringstream summary_;
  std::string error_;
  std::uint16_t port_ = 0;
  std::thread thread_;
};

}  // namespace voxhap::cli

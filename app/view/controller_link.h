#pragma once
/// The front end's link to a haptic controller (docs/protocol.md): one thread of its own
/// owns the connection, sends what the window asks for and keeps a LinkState current, so
/// that the window never waits on the network (DESIGN §9). The window reads a copy of the
/// state each frame and queues commands; both calls take a mutex for microseconds.

#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "haptics/dynamics/pose.h"
#include "net/frontend/frontend_client.h"

namespace voxhap::view {

namespace pb = net::pb;

/// What the front end knows of the controller, as of the messages received so far.
struct LinkState {
  bool connected = false;
  bool closedByController = false;  ///< the link is down because the controller closed it
  std::string error;  ///< why the link is down, or the last refused request's message (one line)
  pb::HelloReply hello;
  std::vector<pb::ObjectInfo> objects;                  ///< moving first, in index order
  std::optional<pb::FrameUpdate> frame;                 ///< the newest
  std::optional<pb::Statistics> statistics;             ///< the newest
  std::optional<pb::Parameters> parameters;             ///< in force
  std::optional<pb::LoadProgress> loading;              ///< while a load (or a rebuild) runs
  std::vector<std::optional<pb::Proximity>> proximity;  ///< per moving object, the newest
  bool proximityUnavailable = false;  ///< the session has none (no static scene, paged voxels)
  std::uint64_t revision = 0;         ///< bumps with every change
};

struct LinkOptions {
  std::string host = "127.0.0.1";
  std::uint16_t port = 7400;
  std::string token;
  std::string clientName = "voxhap view";
  double updateRateHz = 60.0;          ///< frame updates (the window's rate is enough)
  double statisticsPeriodS = 0.25;     ///< how often to ask for statistics
  double proximityPeriodS = 0.1;       ///< how often to ask for each moving object's proximity
  double proximityWithinVoxels = 4.0;  ///< near static voxels listed, in static voxels
  std::chrono::milliseconds connectTimeout{5000};
};

class ControllerLink {
public:
  /// Starts the thread, which connects, says hello, lists the objects, subscribes and
  /// asks for the parameters; a failure shows in the state (connected false, error).
  explicit ControllerLink(LinkOptions options);
  /// Closes the connection and joins the thread.
  ~ControllerLink();
  ControllerLink(const ControllerLink&) = delete;
  ControllerLink& operator=(const ControllerLink&) = delete;

  /// A copy of the state.
  LinkState state() const;

  // Requests, queued for the link's thread (in order; a handle's moves: only the newest).
  void loadScene(const std::string& scene, const std::vector<std::string>& move);
  void grab(const std::string& object, const std::string& device = "client");
  void release(const std::string& object);
  void moveHandle(const std::string& object, const Pose& handleWorld);
  void setParameters(const pb::SetParameters& parameters);
  /// Asks the controller itself to shut down.
  void shutdown();

private:
  void run();
  /// Takes one message from the controller into the state (the link thread).
  void handle(const pb::ServerMessage& message);
  void queue(pb::ClientMessage request);
  void fail(const std::string& error, bool closedByController = false);

  LinkOptions options_;
  mutable std::mutex mutex_;
  LinkState state_;
  std::deque<pb::ClientMessage> queued_;
  std::map<std::string, Pose> handleMoves_;  ///< per object, the newest handle pose to send
  bool stopping_ = false;
  // the link thread's own
  std::map<std::uint64_t, pb::ClientMessage::RequestCase> pending_;  ///< sent, reply awaited
  int proximityPending_ = 0;  ///< get_proximity requests awaiting replies
  std::thread thread_;
};

}  // namespace voxhap::view

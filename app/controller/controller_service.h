#pragma once
/// What the haptic controller answers to front ends (docs/protocol.md): scene loads, the
/// objects, grabs and releases, parameters, frame updates and statistics, on top of a
/// running HapticLoop. Runs on the comms thread only (net::FrontendHandler), except the
/// loader, which runs on a worker thread of its own; it talks to the haptic thread only
/// through the loop's hand-overs, and owns every device it creates until the haptic
/// thread hands it back.

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <asio/io_context.hpp>

#include "app/controller/haptic_loop.h"
#include "app/controller/session_proximity.h"
#include "haptics/core/content_hash.h"
#include "haptics/core/progress.h"
#include "haptics/device/spacemouse_device.h"
#include "haptics/runtime/latest_value.h"
#include "haptics/sim/scene_model.h"
#include "net/frontend/frontend_server.h"

namespace voxhap::controller {

/// A handle moved by a front end (MoveHandle, e.g. the mouse as a 2-DOF device): the
/// newest pose the comms thread received, read by the haptic thread through a mailbox.
/// Its velocity is zero, so the coupling damps the object's motion as a viscosity.
class ClientHandleDevice final : public HapticDevice {
public:
  /// Starts at `initialWorld`, rendering within `limits`.
  ClientHandleDevice(const Pose& initialWorld, const DeviceLimits& limits);
  /// Comms thread: the new handle pose.
  void move(const Pose& handleWorld) noexcept { mailbox_.publish(handleWorld); }
  Pose handlePose(double tS) noexcept override;
  HandleVelocity handleVelocity(double) noexcept override { return {}; }
  void setFeedback(const CouplingWrench&) noexcept override {}
  const DeviceLimits& limits() const noexcept override { return limits_; }

private:
  LatestValue<Pose> mailbox_;
  std::uint64_t version_ = 0;
  Pose pose_;
  DeviceLimits limits_;
};

/// A scene the controller simulates: the built model and the haptic loop running it.
struct ControllerSession {
  net::pb::LoadScene source;               ///< what it was built from (a rebuild changes the sizes)
  std::string sceneName;                   ///< as the scene source names it
  std::vector<std::string> staticObjects;  ///< names of the static parts
  double voxelSizeM = 0.0;                 ///< of the static scene, as built
  double pointSpacingM = 0.0;              ///< of the moving objects, as built
  double pointOffsetM = 0.0;               ///< of the first moving object's points, as built
  std::unique_ptr<BuiltScene> built;       ///< the model the loop reads (a stable address)
  std::unique_ptr<HapticLoop> loop;        ///< started by the ControllerService
  std::unique_ptr<SessionProximity> proximity;
  Digest128 sceneHash;            ///< the scene's content and moving names (peers compare it)
  std::optional<SimState> start;  ///< where the loop starts (a peer's snapshot); none: as loaded
};

/// What a collaborative session (DESIGN §8) allows of a controller's clients (a grab only
/// of what this peer owns or shares, and no other scene or sizes than every peer's), and
/// what it adds to what they see.
struct PeerHooks {
  /// Why `object` may not be grabbed here (empty: it may).
  std::function<std::string(std::size_t object)> whyNotGrab;
  std::string whyNotReload;  ///< why load_scene and size changes are refused
  /// Adds what the session knows to a frame update (the shared objects' sharers, and the
  /// divergence the others see); may be empty.
  std::function<void(net::pb::FrameUpdate& update)> annotate;
};

/// Builds a session (all but its loop) for a LoadScene request, calling `progress` as it
/// goes (it throws to cancel). Runs on a worker thread; throws voxhap::Error for a scene it
/// cannot load.
using SessionLoader = std::function<std::unique_ptr<ControllerSession>(const net::pb::LoadScene& request,
                                                                       const ProgressFn& progress)>;

class ControllerService final : public net::FrontendHandler {
public:
  using LogFn = std::function<void(const std::string&)>;
  using SendFn = std::function<bool(std::uint64_t client, const net::pb::ServerMessage& message)>;

  /// Starts the haptic loop of `session` (null: none until a client loads one) with
  /// `loopOptions` (its period from the model), its first moving object held from the first
  /// frame by `startDevice` when that is not empty (a Grab's device), and serves it; loads
  /// others with `loader` on a worker thread, whose results come back through `io`.
  /// `shutdown` is called on a Shutdown request after its reply is queued. Throws
  /// voxhap::Error when `startDevice` cannot grab.
  ControllerService(asio::io_context& io, std::unique_ptr<ControllerSession> session, SessionLoader loader,
                    HapticLoopOptions loopOptions, const std::string& startDevice,
                    std::function<void()> shutdown, LogFn log);
  /// Cancels a load in progress and waits for its thread; stops the loop.
  ~ControllerService() override;

  /// How deferred replies and progress events reach a client (FrontendServer::send).
  void setSender(SendFn send) { send_ = std::move(send); }
  /// Makes this controller a peer's: grabs and reloads are checked by `guard`.
  void setPeerHooks(PeerHooks guard) { peerHooks_ = std::move(guard); }

  void hello(net::pb::HelloReply& reply) override;
  void handle(std::uint64_t client, const net::pb::ClientMessage& request,
              net::pb::ServerMessage& reply) override;
  void frameUpdate(net::pb::FrameUpdate& update) override;
  void disconnected(std::uint64_t client) override;

  /// Deletes the devices the haptic thread has let go. Called by every request; call it
  /// after the loop has stopped too.
  void collectRetired();
  /// Takes the SpaceMice's button events: button 1 pressed grabs the object the device
  /// last held, or releases it. Call it every few tens of milliseconds.
  void pollDevices();
  /// Stops the haptic loop (for the summary; requests after it find no scene).
  void stopLoop();
  /// The session being simulated, or null.
  const ControllerSession* session() const { return session_.get(); }
  /// Commands the haptic thread's queue refused (it was full).
  std::uint64_t droppedCommands() const { return droppedCommands_; }
  /// Statistics as the protocol sends them (also for the controller's summary).
  void statistics(net::pb::Statistics& out) const;

private:
  /// The index of moving object `name`, or -1 after filling `reply` with an Error.
  int movingObject(const std::string& name, net::pb::ServerMessage& reply) const;
  void listObjects(net::pb::ObjectList& list) const;
  void grab(std::uint64_t client, const net::pb::Grab& request, net::pb::ServerMessage& reply);
  void release(const std::string& name, net::pb::ServerMessage& reply);
  void setParameters(std::uint64_t client, std::uint64_t id, const net::pb::SetParameters& request,
                     net::pb::ServerMessage& reply);
  /// The coupling gains of every moving object at the current share and damping ratio.
  std::vector<CouplingGains> couplingGains() const;
  /// Queues those gains for the haptic thread; false when its queue refused one.
  bool postCouplingGains();
  void parameters(net::pb::Parameters& out) const;
  void moveHandle(std::uint64_t client, const net::pb::MoveHandle& request, net::pb::ServerMessage& reply);
  void proximity(const net::pb::GetProximity& request, net::pb::ServerMessage& reply);
  /// A load_scene (a new scene, its reply the object list), or a rebuild of the scene in
  /// force for set_parameters (its objects kept where they are, the reply its parameters;
  /// an error names `errorField`).
  struct LoadKind {
    bool rebuild = false;
    std::string errorField = "scene";
  };
  void load(std::uint64_t client, std::uint64_t id, const net::pb::LoadScene& request, const LoadKind& kind,
            net::pb::ServerMessage& reply);
  void finishLoad(std::uint64_t client, std::uint64_t id, const LoadKind& kind,
                  std::unique_ptr<ControllerSession> loaded, const std::string& error);
  /// Makes `session` (may be null) the one served and starts its loop from `start` (none:
  /// every object where the scene puts it, at the model's force layer), with no object held
  /// but by `startDevice` (empty: none), which holds the first moving object from the first
  /// frame. Throws voxhap::Error when that device cannot grab.
  void replaceSession(std::unique_ptr<ControllerSession> session, std::optional<SimState> start = {},
                      const std::string& startDevice = {});
  bool post(const LoopCommand& command, net::pb::ServerMessage& reply);
  asio::io_context& io_;
  std::unique_ptr<ControllerSession> session_;
  SessionLoader loader_;
  std::function<void()> shutdown_;
  LogFn log_;
  SendFn send_;
  std::map<const HapticDevice*, std::unique_ptr<HapticDevice>> devices_;  ///< every device not yet retired
  std::vector<std::string> heldBy_;          ///< per moving object, as Grab named it; empty: free
  std::vector<std::uint64_t> heldByClient_;  ///< per moving object, the client whose handle it is, 0: none
  std::vector<ClientHandleDevice*> clientHandles_;  ///< per moving object, while heldByClient_
  /// A SpaceMouse stays open between grabs (its button grabs again): not in devices_, kept
  /// until the session ends; `object` is the moving object it last grabbed.
  struct StandingSpaceMouse {
    std::string device;
    std::unique_ptr<SpaceMouseDevice> mouse;
    std::size_t object = 0;
  };
  std::vector<StandingSpaceMouse> spaceMice_;
  /// The SpaceMouse that `device` ("spacemouse" or "spacemouse:PATH") names, opened on first
  /// use with its handle at `startWorld`; null after filling `reply` with an Error.
  StandingSpaceMouse* spaceMouse(const std::string& device, const Pose& startWorld,
                                 net::pb::ServerMessage& reply);
  HapticLoopOptions loopOptions_;
  std::optional<PeerHooks> peerHooks_;
  double couplingStiffnessShare_ = 1.0;  ///< of every coupling's stiffest (scaledCouplingGains)
  double couplingDampingRatio_ = kCouplingDampingRatio;
  std::uint32_t forceLayer_ = 0;  ///< as last set (the haptic thread takes it at its next frame)
  std::uint64_t droppedCommands_ = 0;
  std::thread loadThread_;
  bool loading_ = false;
  std::atomic<bool> cancelLoad_{false};
};

}  // namespace voxhap::controller

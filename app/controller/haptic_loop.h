#pragma once
/// The haptic controller's 1 kHz thread (DESIGN §7, paper §6): on absolute deadlines it
/// takes the commands queued for it, steps the simulation with the devices that hold
/// objects, and publishes the frame's snapshot.
///
/// Threads. The haptic thread owns the simulation's state and workspace and never locks,
/// allocates, logs or blocks in a frame. One other thread (the comms thread) talks to it,
/// through the non-blocking side of each hand-over: post() into a bounded queue, latest()
/// from a triple buffer, takeRetired() from a second queue that hands back the devices it
/// let go (the comms thread owns every device and deletes it once retired).

#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

#include "haptics/runtime/fifo_hold.h"
#include "haptics/runtime/jitter_buffer.h"
#include "haptics/runtime/period_stats.h"
#include "haptics/runtime/realtime.h"
#include "haptics/runtime/shared_object_port.h"
#include "haptics/runtime/spsc_queue.h"
#include "haptics/runtime/triple_buffer.h"
#include "haptics/sim/simulation.h"

namespace voxhap::controller {

/// A command for the haptic thread, taken at the start of the next frame.
struct LoopCommand {
  enum class Kind : std::uint8_t {
    Grab,              ///< `device` holds `object` from now on (its time starts at 0 now)
    Release,           ///< `object` goes free; its device is retired
    SetForceLayer,     ///< the force layer becomes `value`
    SetCouplingGains,  ///< `object`'s coupling takes `gains`
    SetOwner,          ///< peer `value` owns `object` from now on (kNoPeer: nobody)
    Share              ///< this peer integrates its own instance of `object` from now on, coupled to the
                       ///< other sharers' (type-2); `value` 1: through the passivity controller
  };
  Kind kind = Kind::Release;
  std::uint32_t object = 0;
  HapticDevice* device = nullptr;
  std::uint32_t value = 0;
  CouplingGains gains;
};

/// What a remote peer has of one object (DESIGN §8), from the comms thread.
struct RemoteUpdate {
  enum class Kind : std::uint8_t {
    OwnerState,   ///< its owner's state (type-1): taken only while `peer` owns the object
    SharedState,  ///< a sharer's instance (type-2) with the energy in at its port, `inJ`
    SharedDelay,  ///< a sharer's one-way delay became `oneWayS`
    SharedLeft    ///< a sharer stopped sharing or left: its instance fades out
  };
  Kind kind = Kind::OwnerState;
  std::uint32_t object = 0;
  PeerId peer = kNoPeer;
  RemoteSample sample;         ///< sent on the peer's clock
  std::int64_t arrivalUs = 0;  ///< monotonicTime() on this peer, µs
  double inJ = 0.0;
  double oneWayS = 0.0;
};

/// One moving object in a snapshot.
struct ObjectSnapshot {
  Pose pose;            ///< local → world
  RigidBodyState body;  ///< centre of mass, orientation and velocities, world
  PeerId owner = kNoPeer;
  Pose handle;  ///< its handle's pose, when held
  bool held = false;
  glm::dvec3 forceWorld{0.0};  ///< contact force, N
  std::uint32_t contacts = 0;
  std::uint32_t tested = 0;      ///< point tests of its pointshell this frame
  ContactSample contactSample;   ///< some of its contact points, world
  double travelShare = 1.0;      ///< MaxTravel over its upper bound
  bool shared = false;           ///< this peer integrates its own instance of it (type-2)
  SharedObjectPort::Frame port;  ///< its coupling to the other instances, when shared
};

/// What the haptic thread publishes after each frame.
struct FrameSnapshot {
  std::uint64_t frame = 0;
  double timeS = 0.0;                   ///< simulated
  std::int64_t endedUs = 0;             ///< monotonicTime() when the frame ended, µs
  std::vector<ObjectSnapshot> objects;  ///< one per moving object
  std::uint32_t forceLayer = 0;
  FrameStatus status = kFrameOk;
  bool stopped = false;               ///< the haptic thread has ended (a paging failure, or stop())
  PeriodSummary period;               ///< frame start to frame start, updated every kSummaryFrames
  PeriodSummary compute;              ///< step and hand-overs, same
  std::uint64_t resyncs = 0;          ///< stalls after which the clock re-synced
  std::uint64_t skippedPeriods = 0;   ///< periods those stalls skipped
  std::uint64_t missedDeadlines = 0;  ///< the engine's (more contacts than its capacity)
  bool fifoHeld = false;              ///< the haptic thread is under SCHED_FIFO now
  std::uint64_t fifoGivenUp = 0;      ///< times it gave SCHED_FIFO up, its frames overrunning (FifoHold)
};

struct HapticLoopOptions {
  std::int64_t periodNs = 1'000'000;
  bool realtime = true;  ///< try mlockall and SCHED_FIFO
  int fifoPriority = 80;
  std::size_t commandCapacity = 256;  ///< a power of two
  /// This peer in a collaborative session (DESIGN §8); kNoPeer: alone, every object
  /// integrated here. In a session only the objects this peer owns are integrated; those
  /// a remote peer owns follow its stream (RemoteUpdate) through a jitter buffer, and
  /// those nobody owns stay where they are, so that every peer sees the same. An object
  /// shared here (LoopCommand::Share) is integrated here whoever owns it.
  PeerId localPeer = kNoPeer;
  std::size_t remoteCapacity = 1024;  ///< RemoteUpdates queued, a power of two
  std::int64_t playoutDelayUs = 30'000;
  /// A second thread, pinned to a spare core, that shares the point tests and contact
  /// sums of large frames (haptics/runtime/frame_helper.h): the same results, a core kept
  /// busy while frames run. Made on the haptic thread before it asks for SCHED_FIFO, so that
  /// the helper, which spins between frames, runs under the normal policy and does not
  /// starve whatever else runs on its core.
  bool frameHelper = false;
};

class HapticLoop {
public:
  /// How an object is shared here (type-2).
  enum class Sharing : std::uint8_t { No, Plain, Passive };

  /// A snapshot's period and compute summaries are brought up to date every so many frames.
  static constexpr std::uint64_t kSummaryFrames = 100;

  /// `model` must outlive the loop. Allocates everything the thread will use.
  HapticLoop(const SimModel& model, SimState initial, std::shared_ptr<VoxelPager> staticPager,
             HapticLoopOptions options = {});
  ~HapticLoop();
  HapticLoop(const HapticLoop&) = delete;
  HapticLoop& operator=(const HapticLoop&) = delete;

  /// Starts the haptic thread and waits until it has tried the real-time set-up. Throws
  /// Error when a frame helper was asked for and cannot be had (no spare core).
  void start();
  /// Ends the haptic thread after its current frame and joins it. Devices still held are
  /// retired (takeRetired). Idempotent.
  void stop();

  /// Comms thread: queues `command`; false when the queue is full (nothing is queued).
  bool post(const LoopCommand& command) noexcept;
  /// Comms thread: queues what a remote peer has of an object; false when the queue is full.
  bool postRemote(const RemoteUpdate& update) noexcept;
  /// Comms thread: a device the haptic thread let go, now the caller's to delete; nullptr
  /// when there is none.
  HapticDevice* takeRetired() noexcept;
  /// Comms thread: the newest snapshot (the same object until a newer one is taken).
  const FrameSnapshot& latest() noexcept;
  /// What the real-time set-up achieved (valid after start()).
  const RealtimeStatus& realtime() const noexcept { return realtime_; }
  /// The frame helper's CPU, or −1 without one (valid after start()).
  int frameHelperCpu() const noexcept { return helperCpu_; }
  const SimModel& model() const noexcept { return model_; }
  /// The whole-run statistics (valid after stop()).
  const PeriodStats& periodStats() const noexcept { return period_; }
  const PeriodStats& computeStats() const noexcept { return compute_; }

private:
  /// A held device with its time counted from the grab.
  class GrabbedDevice final : public HapticDevice {
  public:
    Pose handlePose(double tS) noexcept override { return device->handlePose(tS - startS); }
    HandleVelocity handleVelocity(double tS) noexcept override { return device->handleVelocity(tS - startS); }
    void setFeedback(const CouplingWrench& feedbackWorld) noexcept override {
      device->setFeedback(feedbackWorld);
    }
    const DeviceLimits& limits() const noexcept override { return device->limits(); }
    HapticDevice* device = nullptr;
    double startS = 0.0;
  };

  void run() noexcept;
  void apply(const LoopCommand& command) noexcept;
  void take(const RemoteUpdate& update) noexcept;
  /// Fills kinematic_ for the frame ending at local time `endUs`.
  void moveRemoteObjects(std::int64_t endUs) noexcept;
  /// Fills external_ with the shared objects' couplings at local time `nowUs`.
  void coupleSharedObjects(std::int64_t nowUs) noexcept;
  void retire(std::size_t object) noexcept;
  void publish(FrameStatus status, std::uint64_t frame) noexcept;
  /// Gives SCHED_FIFO up or takes it again as fifoHold_ decides, after a frame that began
  /// `lateNs` past its deadline and computed for `computeNs`.
  void holdFifo(std::int64_t lateNs, std::int64_t computeNs) noexcept;

  const SimModel& model_;
  HapticLoopOptions options_;
  SimState state_;
  SimWorkspace workspace_;
  FrameOutputs outputs_;
  std::vector<GrabbedDevice> grabbed_;
  std::vector<HapticDevice*> devices_;  ///< &grabbed_[i] while held, else nullptr
  std::vector<HandleInput> handles_;
  std::vector<CouplingGains> gains_;     ///< per object, its coupling's (the model's until set)
  std::vector<JitterBuffer> jitter_;     ///< per object, its remote owner's stream
  std::vector<Sharing> sharing_;         ///< per object
  std::vector<SharedObjectPort> ports_;  ///< per object, its coupling when shared here
  std::vector<ExternalWrench> external_;
  std::vector<KinematicInput> kinematic_;
  SpscQueue<LoopCommand> commands_;
  SpscQueue<RemoteUpdate> remote_;
  SpscQueue<HapticDevice*> retired_;
  TripleBuffer<FrameSnapshot> snapshots_;
  PeriodStats period_;
  PeriodStats compute_;
  PeriodSummary periodSummary_;
  PeriodSummary computeSummary_;
  std::uint64_t resyncs_ = 0;
  std::uint64_t skippedPeriods_ = 0;
  RealtimeStatus realtime_;
  int helperCpu_ = -1;
  FifoHold fifoHold_;
  std::atomic<bool> stopRequested_{false};
  std::thread thread_;
};

}  // namespace voxhap::controller

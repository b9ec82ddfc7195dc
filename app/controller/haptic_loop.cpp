#include "app/controller/haptic_loop.h"

#include <bit>
#include <chrono>
#include <future>

#include "haptics/runtime/frame_clock.h"
#include "haptics/runtime/frame_helper.h"

namespace voxhap::controller {
namespace {

/// What a reader sees before the first frame: the objects where they start.
FrameSnapshot initialSnapshot(const SimModel& model, const SimState& state) {
  FrameSnapshot s;
  s.objects.resize(model.objects.size());
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    s.objects[i].pose = s.objects[i].handle = objectPose(model, state, i);
    s.objects[i].body = state.bodies[i];
    s.objects[i].owner = state.owners[i];
  }
  s.forceLayer = state.forceLayer;
  s.endedUs = monotonicTime().nowNs() / 1000;  // a peer's first heartbeat carries a real clock
  return s;
}

}  // namespace

HapticLoop::HapticLoop(const SimModel& model, SimState initial, std::shared_ptr<VoxelPager> staticPager,
                       HapticLoopOptions options)
    : model_(model),
      options_(options),
      state_(std::move(initial)),
      workspace_(makeSimWorkspace(model, state_, std::move(staticPager))),
      outputs_(makeFrameOutputs(model)),
      grabbed_(model.objects.size()),
      devices_(model.objects.size(), nullptr),
      handles_(model.objects.size()),
      gains_(model.objects.size()),
      jitter_(model.objects.size(), JitterBuffer(options.playoutDelayUs)),
      sharing_(model.objects.size(), Sharing::No),
      ports_(model.objects.size()),
      external_(model.objects.size()),
      kinematic_(model.objects.size()),
      commands_(options.commandCapacity),
      remote_(options.remoteCapacity),
      retired_(std::bit_ceil(options.commandCapacity + model.objects.size())),
      snapshots_(initialSnapshot(model, state_)),
      period_(options.periodNs * 3 / 2),
      compute_(options.periodNs) {
  for (std::size_t i = 0; i < model.objects.size(); ++i) gains_[i] = model.objects[i].gains;
}

HapticLoop::~HapticLoop() {
  stop();
}

void HapticLoop::start() {
  std::promise<void> ready;
  std::future<void> started = ready.get_future();
  thread_ = std::thread([this, &ready] {
    if (options_.frameHelper) {
      try {
        workspace_.helper = std::make_shared<FrameHelper>();
        helperCpu_ = workspace_.helper->cpu();
      } catch (...) {  // no spare core (Error), or no thread to be had
        ready.set_exception(std::current_exception());
        return;
      }
    }
    if (options_.realtime) realtime_ = requestRealtime(options_.fifoPriority);
    ready.set_value();
    run();
    workspace_.helper.reset();  // the helper ends with the frames, not with the loop object
  });
  try {
    started.get();
  } catch (...) {
    thread_.join();
    throw;
  }
}

void HapticLoop::stop() {
  if (!thread_.joinable()) return;
  stopRequested_.store(true, std::memory_order_relaxed);
  thread_.join();
  for (std::size_t i = 0; i < devices_.size(); ++i) retire(i);
}

bool HapticLoop::post(const LoopCommand& command) noexcept {
  return commands_.tryPush(command);
}

bool HapticLoop::postRemote(const RemoteUpdate& update) noexcept {
  return remote_.tryPush(update);
}

HapticDevice* HapticLoop::takeRetired() noexcept {
  HapticDevice* device = nullptr;
  return retired_.tryPop(device) ? device : nullptr;
}

const FrameSnapshot& HapticLoop::latest() noexcept {
  snapshots_.update();
  return snapshots_.readBuffer();
}

void HapticLoop::retire(std::size_t object) noexcept {
  if (devices_[object] == nullptr) return;
  // the queue has room for every command that can retire one and every object
  [[maybe_unused]] const bool queued = retired_.tryPush(grabbed_[object].device);
  grabbed_[object].device = nullptr;
  devices_[object] = nullptr;
}

void HapticLoop::apply(const LoopCommand& command) noexcept {
  if (command.kind == LoopCommand::Kind::SetForceLayer) {
    setForceLayer(model_, state_, workspace_, command.value);
    return;
  }
  if (command.object >= devices_.size()) return;
  if (command.kind == LoopCommand::Kind::SetCouplingGains) {
    gains_[command.object] = command.gains;
    return;
  }
  if (command.kind == LoopCommand::Kind::Share) {
    // from where the owner's stream has put it, at its velocity: no step
    sharing_[command.object] = command.value == 1 ? Sharing::Passive : Sharing::Plain;
    return;
  }
  if (command.kind == LoopCommand::Kind::SetOwner) {
    state_.owners[command.object] = command.value;
    jitter_[command.object].clear();
    if (sharing_[command.object] != Sharing::No) return;  // its instance goes on here whoever owns it
    // a part taken over starts at rest where it was shown, not with the remote velocity
    RigidBodyState& body = state_.bodies[command.object];
    body.linearVelocityWorld = body.angularVelocityWorld = glm::dvec3(0.0);
    return;
  }
  retire(command.object);
  if (command.kind == LoopCommand::Kind::Grab && command.device != nullptr) {
    grabbed_[command.object].device = command.device;
    grabbed_[command.object].startS = state_.timeS;
    command.device->grabbed(objectPose(model_, state_, command.object));
    devices_[command.object] = &grabbed_[command.object];
  }
}

void HapticLoop::take(const RemoteUpdate& update) noexcept {
  if (update.object >= jitter_.size()) return;
  SharedObjectPort& port = ports_[update.object];
  switch (update.kind) {
    case RemoteUpdate::Kind::OwnerState:
      if (state_.owners[update.object] != update.peer || update.peer == options_.localPeer ||
          sharing_[update.object] != Sharing::No) {
        return;  // a stream of an owner it no longer has, or of an instance it has its own of
      }
      jitter_[update.object].push(update.sample, update.arrivalUs);
      return;
    case RemoteUpdate::Kind::SharedState:
      port.take(update.peer, update.sample, update.inJ, update.arrivalUs);
      return;
    case RemoteUpdate::Kind::SharedDelay:
      port.setDelay(update.peer, update.oneWayS);
      return;
    case RemoteUpdate::Kind::SharedLeft:
      port.drop(update.peer);
      return;
  }
}

void HapticLoop::moveRemoteObjects(std::int64_t endUs) noexcept {
  if (options_.localPeer == kNoPeer) return;
  for (std::size_t i = 0; i < kinematic_.size(); ++i) {
    const PeerId owner = state_.owners[i];
    KinematicInput& k = kinematic_[i];
    k.active = owner != options_.localPeer && sharing_[i] == Sharing::No;
    if (!k.active) continue;
    if (owner == kNoPeer || !jitter_[i].playOut(endUs, k.targetWorld)) {
      // nobody moves it, or its owner's stream has not begun: it stays where it is
      k.targetWorld = state_.bodies[i];
      k.targetWorld.linearVelocityWorld = k.targetWorld.angularVelocityWorld = glm::dvec3(0.0);
    }
  }
}

void HapticLoop::coupleSharedObjects(std::int64_t nowUs) noexcept {
  for (std::size_t i = 0; i < external_.size(); ++i) {
    if (sharing_[i] == Sharing::No) continue;
    external_[i] = ports_[i]
                       .step(nowUs, model_.objects[i].body, state_.bodies[i], gains_[i],
                             sharing_[i] == Sharing::Passive, model_.dtS)
                       .wrench;
  }
}

void HapticLoop::publish(FrameStatus status, std::uint64_t frame) noexcept {
  FrameSnapshot& s = snapshots_.writeBuffer();
  s.frame = frame;
  s.timeS = state_.timeS;
  s.endedUs = monotonicTime().nowNs() / 1000;
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    ObjectSnapshot& o = s.objects[i];
    const ObjectFrame& f = outputs_.objects[i];
    o.pose = objectPose(model_, state_, i);
    o.body = state_.bodies[i];
    o.owner = state_.owners[i];
    o.held = devices_[i] != nullptr;
    o.handle = o.held ? handles_[i].poseWorld : o.pose;
    o.forceWorld = f.contactForceWorld;
    o.contacts = f.contacts;
    o.tested = f.tested;
    o.contactSample = f.contactSample;
    o.travelShare = outputs_.coherence.travelScale;
    o.shared = sharing_[i] != Sharing::No;
    if (o.shared) o.port = ports_[i].last();
  }
  s.forceLayer = state_.forceLayer;
  s.status = status;
  s.stopped = (status & kFrameStopped) != 0;
  if (frame % kSummaryFrames == 0 || frame < kSummaryFrames ||
      s.stopped) {  // and the first ones, so early readers see figures
    periodSummary_ = period_.summary();
    computeSummary_ = compute_.summary();
  }
  s.period = periodSummary_;
  s.compute = computeSummary_;
  s.resyncs = resyncs_;
  s.skippedPeriods = skippedPeriods_;
  s.fifoHeld = realtime_.fifo.ok && fifoHold_.held();
  s.fifoGivenUp = fifoHold_.givenUp();
  s.missedDeadlines = workspace_.counters.missedDeadlines;
  snapshots_.publish();
}

void HapticLoop::run() noexcept {
  FrameClock clock(options_.periodNs);
  LoopCommand command;
  double lastStepS = 0.0;
  for (std::uint64_t frame = 1; !stopRequested_.load(std::memory_order_relaxed); ++frame) {
    const FrameTick tick = clock.waitForFrame();
    if (tick.sincePreviousNs > 0) period_.record(tick.sincePreviousNs);
    if (tick.skippedPeriods > 0) {
      ++resyncs_;
      skippedPeriods_ += tick.skippedPeriods;
    }
    while (commands_.tryPop(command)) apply(command);
    RemoteUpdate update;
    while (remote_.tryPop(update)) take(update);
    moveRemoteObjects(tick.beganNs / 1000 + options_.periodNs / 1000);
    coupleSharedObjects(tick.beganNs / 1000);
    FrameInputs inputs;
    inputs.now = std::chrono::steady_clock::now();
    inputs.previousStepS = lastStepS;
    inputs.couplingGains = gains_;
    inputs.kinematic = kinematic_;
    inputs.externalWrenches = external_;
    const FrameStatus status =
        stepWithDevices(model_, state_, workspace_, devices_, handles_, inputs, outputs_);
    lastStepS = std::chrono::duration<double>(std::chrono::steady_clock::now() - inputs.now).count();
    const std::int64_t computeNs = monotonicTime().nowNs() - tick.beganNs;
    compute_.record(computeNs);
    if (realtime_.fifo.ok) holdFifo(tick.beganNs - tick.deadlineNs, computeNs);
    publish(status, frame);
    if (status & kFrameStopped) break;
    if (fifoHold_.held() && realtime_.fifo.ok) yieldToEqualPriority();
  }
}

void HapticLoop::holdFifo(std::int64_t lateNs, std::int64_t computeNs) noexcept {
  // a frame that waited for its deadline begins within microseconds of it (the clock spins)
  const bool beganLate = lateNs > options_.periodNs / 10;
  const bool quick = computeNs < options_.periodNs / 2;
  switch (fifoHold_.afterFrame(beganLate, quick)) {
    case FifoHold::Change::GiveUp:
      leaveFifo();
      break;
    case FifoHold::Change::TakeAgain:
      if (!enterFifo(options_.fifoPriority)) fifoHold_.refused();
      break;
    case FifoHold::Change::None:
      break;
  }
}

}  // namespace voxhap::controller

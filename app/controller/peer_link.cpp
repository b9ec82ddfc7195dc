#include "app/controller/peer_link.h"

#include <cmath>

#include "haptics/core/error.h"
#include "haptics/sim/sim_state.h"

namespace voxhap::controller {
namespace {

namespace pb = net::pb;

HapticLoop& loopOf(ControllerService& service) {
  return *service.session()->loop;
}

}  // namespace

PeerLink::PeerLink(asio::io_context& io, net::PeerSession& session, ControllerService& service,
                   PeerLinkOptions options, LogFn log)
    : timer_(io),
      session_(session),
      service_(service),
      options_(std::move(options)),
      log_(std::move(log)),
      period_(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(1.0 / options_.streamHz))) {
  const SimModel& model = service_.session()->built->model;
  if (!options_.take.empty()) {
    for (std::size_t i = 0; i < model.objects.size(); ++i) {
      if (model.objects[i].name == options_.take) takeObject_ = static_cast<int>(i);
    }
    if (takeObject_ < 0) throw Error("--take: no moving object '" + options_.take + "'");
  }
  const FrameSnapshot& first = loopOf(service_).latest();
  std::vector<PeerId> owners;
  for (const ObjectSnapshot& o : first.objects) owners.push_back(o.owner);
  session_.start(
      owners,
      [this](std::uint32_t object, PeerId owner, std::int64_t sentUs, const RigidBodyState& body,
             std::int64_t arrivalUs) {
        RemoteUpdate update;
        update.object = object;
        update.owner = owner;
        update.sample = RemoteSample{sentUs, body};
        update.arrivalUs = arrivalUs;
        if (loopOf(service_).postRemote(update)) {
          ++counts_.remoteStates;
        } else {
          ++counts_.remoteStatesDropped;
        }
      },
      [this](std::uint32_t object, PeerId owner) { ownerChanged(object, owner); },
      [this] {
        const FrameSnapshot& s = loopOf(service_).latest();
        SimState state;
        state.frame = s.frame;
        state.timeS = s.timeS;
        state.forceLayer = static_cast<std::uint8_t>(s.forceLayer);
        for (const ObjectSnapshot& o : s.objects) {
          state.bodies.push_back(o.body);
          state.owners.push_back(o.owner);
        }
        return saveState(state);
      });
  if (takeObject_ >= 0) session_.want(static_cast<std::uint32_t>(takeObject_));
  next_ = std::chrono::steady_clock::now();
  tick();
}

net::LocalFrame PeerLink::localFrame() {
  const FrameSnapshot& s = loopOf(service_).latest();
  net::LocalFrame frame;
  frame.endedUs = s.endedUs;
  frame.frame = s.frame;
  for (const ObjectSnapshot& o : s.objects) {
    frame.bodies.push_back(o.body);
    frame.held.push_back(o.held);
  }
  return frame;
}

void PeerLink::ownerChanged(std::uint32_t object, PeerId owner) {
  ++counts_.ownerChanges;
  LoopCommand command;
  command.kind = LoopCommand::Kind::SetOwner;
  command.object = object;
  command.value = owner;
  if (!loopOf(service_).post(command)) log_("the haptic thread's queue is full: an ownership change is late");
  const std::string& name = service_.session()->built->model.objects[object].name;
  const bool mine = owner == session_.self();
  log_("'" + name + "' is " +
       (mine               ? std::string("this peer's")
        : owner == kNoPeer ? "nobody's"
                           : "peer " + std::to_string(owner) + "'s"));
  if (!mine && loopOf(service_).latest().objects[object].held) {
    // another peer won it: this peer's users let go
    pb::ClientMessage release;
    release.mutable_release()->set_object(name);
    pb::ServerMessage reply;
    service_.handle(0, release, reply);
  }
}

void PeerLink::tick() {
  if (stopped_) return;
  ++counts_.ticks;
  session_.tick(localFrame());
  if (takeObject_ >= 0 && !takeGrabbed_ && !options_.takeDevice.empty() &&
      session_.owners()[static_cast<std::size_t>(takeObject_)] == session_.self()) {
    pb::ClientMessage grab;
    grab.mutable_grab()->set_object(options_.take);
    grab.mutable_grab()->set_device(options_.takeDevice);
    pb::ServerMessage reply;
    service_.handle(0, grab, reply);
    if (reply.has_error()) log_("cannot grab '" + options_.take + "': " + reply.error().message());
    takeGrabbed_ = true;
  }
  // on the clock, not after the work: the stream keeps its rate
  next_ += period_;
  const auto now = std::chrono::steady_clock::now();
  if (next_ < now) next_ = now;
  timer_.expires_at(next_);
  timer_.async_wait([this](const asio::error_code& e) {
    if (!e) tick();
  });
}

void PeerLink::stop() {
  if (stopped_) return;
  stopped_ = true;
  timer_.cancel();
  session_.leave(localFrame());
}

}  // namespace voxhap::controller

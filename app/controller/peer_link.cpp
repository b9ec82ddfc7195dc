#include "app/controller/peer_link.h"

#include <algorithm>
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
  const auto objectNamed = [&model](const std::string& name, const char* option) {
    for (std::size_t i = 0; i < model.objects.size(); ++i) {
      if (model.objects[i].name == name) return static_cast<int>(i);
    }
    throw Error(std::string(option) + ": no moving object '" + name + "'");
  };
  if (!options_.take.empty()) takeObject_ = objectNamed(options_.take, "--take");
  if (!options_.share.empty()) shareObject_ = objectNamed(options_.share, "--share");
  const FrameSnapshot& first = loopOf(service_).latest();
  std::vector<PeerId> owners;
  for (const ObjectSnapshot& o : first.objects) owners.push_back(o.owner);
  session_.start(
      owners,
      [this](std::uint32_t object, PeerId owner, std::int64_t sentUs, const RigidBodyState& body,
             std::int64_t arrivalUs) {
        if (static_cast<int>(object) == shareObject_ && !followedSince_)
          followedSince_ = std::chrono::steady_clock::now();
        RemoteUpdate update;
        update.object = object;
        update.peer = owner;
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
    frame.sharedInJ.push_back(o.port.inJ);
    frame.divergent.push_back(o.port.coupling.divergent);
  }
  return frame;
}

void PeerLink::grab(const std::string& object) {
  pb::ClientMessage grab;
  grab.mutable_grab()->set_object(object);
  grab.mutable_grab()->set_device(options_.takeDevice);
  pb::ServerMessage reply;
  service_.handle(0, grab, reply);
  if (reply.has_error()) log_("cannot grab '" + object + "': " + reply.error().message());
}

void PeerLink::tickShared(const FrameSnapshot& s) {
  const auto object = static_cast<std::uint32_t>(shareObject_);
  const std::vector<net::SharerView> sharers = session_.sharers(object);
  if (!sharing_) {
    const std::vector<net::MemberView> members = session_.members();
    const bool allHeard =
        std::all_of(members.begin(), members.end(), [](const net::MemberView& m) { return m.heard; });
    const bool followed =
        followedSince_ && std::chrono::steady_clock::now() - *followedSince_ >= kFollowBeforeSharing;
    if (!(followed || (sharers.empty() && allHeard))) return;
    session_.share(object, [this](std::uint32_t o, PeerId sharer, std::int64_t sentUs,
                                  const RigidBodyState& body, double inJ, std::int64_t arrivalUs) {
      RemoteUpdate update;
      update.kind = RemoteUpdate::Kind::SharedState;
      update.object = o;
      update.peer = sharer;
      update.sample = RemoteSample{sentUs, body};
      update.arrivalUs = arrivalUs;
      update.inJ = inJ;
      if (loopOf(service_).postRemote(update)) {
        ++shared_.sharedStates;
      } else {
        ++counts_.remoteStatesDropped;
      }
    });
    LoopCommand command;
    command.kind = LoopCommand::Kind::Share;
    command.object = object;
    command.value = options_.passivity ? 1 : 0;
    if (!loopOf(service_).post(command)) log_("the haptic thread's queue is full: sharing begins late");
    sharing_ = true;
    log_("sharing '" + options_.share + "' with " + std::to_string(sharers.size()) + " other peer(s)" +
         (options_.passivity ? "" : ", without the passivity controller"));
    if (!options_.takeDevice.empty()) grab(options_.share);
    return;
  }
  // the sharers' delays (at every tick: a sharer's slot may be newer than its delay), and
  // who has stopped sharing
  std::set<PeerId> now;
  auto post = [&](RemoteUpdate::Kind kind, PeerId peer, double oneWayS) {
    RemoteUpdate u;
    u.kind = kind;
    u.object = object;
    u.peer = peer;
    u.oneWayS = oneWayS;
    return loopOf(service_).postRemote(u);
  };
  for (const net::SharerView& v : sharers) {
    now.insert(v.peer);
    post(RemoteUpdate::Kind::SharedDelay, v.peer, v.oneWayMs < 0.0 ? -1.0 : 1e-3 * v.oneWayMs);
  }
  for (const PeerId peer : sharers_) {
    if (!now.count(peer) && !post(RemoteUpdate::Kind::SharedLeft, peer, 0.0))
      now.insert(peer);  // again next tick
  }
  sharers_ = std::move(now);
  const SharedObjectPort::Frame& o = s.objects[object].port;
  ++shared_.ticks;
  if (o.counted > 0) {
    ++shared_.coupledTicks;
    shared_.sumApartM += o.coupling.apartM;
    shared_.maxApartM = std::max(shared_.maxApartM, o.coupling.apartM);
    shared_.maxStiffnessShare = std::max(shared_.maxStiffnessShare, o.coupling.stiffnessShare);
    if (o.coupling.divergent) ++shared_.divergentTicks;
  }
  shared_.minObservedJ = std::min(shared_.minObservedJ, o.observedJ);
  shared_.inJ = o.inJ;
  shared_.dissipatedJ = o.dissipatedJ;
  shared_.largestForceStepN = o.largestForceStepN;
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
  if (!mine && !session_.sharing(object) && loopOf(service_).latest().objects[object].held) {
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
  if (shareObject_ >= 0) tickShared(loopOf(service_).latest());
  if (takeObject_ >= 0 && !takeGrabbed_ && !options_.takeDevice.empty() &&
      session_.owners()[static_cast<std::size_t>(takeObject_)] == session_.self()) {
    grab(options_.take);
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

#include "app/view/controller_link.h"

#include <algorithm>

#include "haptics/core/error.h"
#include "net/frontend/pose_proto.h"

namespace voxhap::view {
namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

/// How long the link waits for a message before it looks at its queue again.
constexpr auto kPollPeriod = 5ms;

pb::ClientMessage makeRequest(void (*fill)(pb::ClientMessage&)) {
  pb::ClientMessage m;
  fill(m);
  return m;
}

}  // namespace

ControllerLink::ControllerLink(LinkOptions options) : options_(std::move(options)) {
  thread_ = std::thread([this] { run(); });
}

ControllerLink::~ControllerLink() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  thread_.join();
}

LinkState ControllerLink::state() const {
  std::lock_guard lock(mutex_);
  return state_;
}

void ControllerLink::queue(pb::ClientMessage request) {
  std::lock_guard lock(mutex_);
  queued_.push_back(std::move(request));
}

void ControllerLink::loadScene(const std::string& scene, const std::vector<std::string>& move) {
  pb::ClientMessage m;
  m.mutable_load_scene()->set_scene(scene);
  for (const std::string& name : move) m.mutable_load_scene()->add_move(name);
  queue(std::move(m));
}

void ControllerLink::grab(const std::string& object, const std::string& device) {
  pb::ClientMessage m;
  m.mutable_grab()->set_object(object);
  m.mutable_grab()->set_device(device);
  queue(std::move(m));
}

void ControllerLink::release(const std::string& object) {
  pb::ClientMessage m;
  m.mutable_release()->set_object(object);
  queue(std::move(m));
}

void ControllerLink::moveHandle(const std::string& object, const Pose& handleWorld) {
  std::lock_guard lock(mutex_);
  handleMoves_[object] = handleWorld;
}

void ControllerLink::setParameters(const pb::SetParameters& parameters) {
  pb::ClientMessage m;
  *m.mutable_set_parameters() = parameters;
  queue(std::move(m));
}

void ControllerLink::shutdown() {
  queue(makeRequest([](pb::ClientMessage& m) { m.mutable_shutdown(); }));
}

void ControllerLink::fail(const std::string& error, bool closedByController) {
  std::lock_guard lock(mutex_);
  state_.connected = false;
  state_.closedByController = closedByController;
  state_.error = error;
  ++state_.revision;
}

void ControllerLink::run() {
  std::optional<net::FrontendClient> client;
  try {
    client.emplace(options_.host, options_.port, options_.connectTimeout);
    client->setTimeout(options_.connectTimeout);
    const pb::HelloReply hello = client->hello(options_.clientName, options_.token);
    std::lock_guard lock(mutex_);
    state_.connected = true;
    state_.hello = hello;
    ++state_.revision;
  } catch (const Error& e) {
    fail(e.what());
    return;
  }
  try {
    const auto sendTracked = [&](pb::ClientMessage m) {
      const pb::ClientMessage::RequestCase kind = m.request_case();
      pending_[client->send(std::move(m))] = kind;
    };
    sendTracked(makeRequest([](pb::ClientMessage& m) { m.mutable_list_objects(); }));
    pb::ClientMessage subscribe;
    subscribe.mutable_subscribe()->set_rate_hz(options_.updateRateHz);
    sendTracked(subscribe);
    // a controller without a scene has no parameters yet: they come with the load
    if (!state().hello.scene().empty())
      sendTracked(makeRequest([](pb::ClientMessage& m) { m.mutable_set_parameters(); }));
    Clock::time_point nextStatistics = Clock::now();
    Clock::time_point nextProximity = Clock::now();
    for (;;) {
      std::deque<pb::ClientMessage> requests;
      std::map<std::string, Pose> moves;
      std::vector<std::string> moving;
      double withinM = 0.0;
      bool proximityAsked = false;
      {
        std::lock_guard lock(mutex_);
        if (stopping_) return;
        requests.swap(queued_);
        moves.swap(handleMoves_);
        for (const pb::ObjectInfo& o : state_.objects) {
          if (o.moving()) moving.push_back(o.name());
        }
        if (state_.parameters) withinM = options_.proximityWithinVoxels * state_.parameters->voxel_size_m();
        proximityAsked = !state_.proximityUnavailable && !state_.loading;
      }
      for (pb::ClientMessage& request : requests) sendTracked(std::move(request));
      for (const auto& [object, pose] : moves) {
        pb::ClientMessage m;
        m.mutable_move_handle()->set_object(object);
        net::toProto(pose, *m.mutable_move_handle()->mutable_handle());
        sendTracked(std::move(m));
      }
      const Clock::time_point now = Clock::now();
      if (now >= nextStatistics) {
        sendTracked(makeRequest([](pb::ClientMessage& m) { m.mutable_get_statistics(); }));
        nextStatistics = now + std::chrono::duration_cast<Clock::duration>(
                                   std::chrono::duration<double>(options_.statisticsPeriodS));
      }
      // one round of proximity at a time: a slow answer (a large object) does not pile up
      if (proximityAsked && now >= nextProximity && proximityPending_ == 0) {
        for (const std::string& name : moving) {
          pb::ClientMessage m;
          m.mutable_get_proximity()->set_object(name);
          m.mutable_get_proximity()->set_within_m(withinM);
          sendTracked(std::move(m));
          ++proximityPending_;
        }
        nextProximity = now + std::chrono::duration_cast<Clock::duration>(
                                  std::chrono::duration<double>(options_.proximityPeriodS));
      }
      for (auto m = client->nextMessage(kPollPeriod); m; m = client->nextMessage(0ms)) handle(*m);
      if (!client->isOpen()) {
        fail("the controller closed the connection", true);
        return;
      }
    }
  } catch (const Error& e) {
    fail(e.what());
  }
}

void ControllerLink::handle(const pb::ServerMessage& message) {
  std::lock_guard lock(mutex_);
  ++state_.revision;
  if (message.id() == 0) {
    if (message.has_frame_update()) state_.frame = message.frame_update();
    if (message.has_load_progress()) state_.loading = message.load_progress();
    return;
  }
  const auto sent = pending_.find(message.id());
  const pb::ClientMessage::RequestCase kind =
      sent == pending_.end() ? pb::ClientMessage::REQUEST_NOT_SET : sent->second;
  if (sent != pending_.end()) pending_.erase(sent);
  if (kind == pb::ClientMessage::kGetProximity) --proximityPending_;
  if (message.has_error()) {
    // a session without proximity (no static scene, or paged voxels) says so once
    if (kind == pb::ClientMessage::kGetProximity) {
      state_.proximityUnavailable = true;
    } else {
      state_.error = message.error().message();
    }
    if (kind == pb::ClientMessage::kLoadScene || kind == pb::ClientMessage::kSetParameters)
      state_.loading.reset();
    return;
  }
  if (message.has_object_list()) {
    state_.objects.assign(message.object_list().objects().begin(), message.object_list().objects().end());
    const auto moving = static_cast<std::size_t>(std::count_if(
        state_.objects.begin(), state_.objects.end(), [](const pb::ObjectInfo& o) { return o.moving(); }));
    if (kind == pb::ClientMessage::kLoadScene) {
      // a new scene: its parameters, its proximity, and the errors before it are past
      state_.loading.reset();
      state_.error.clear();
      state_.proximity.assign(moving, std::nullopt);
      state_.proximityUnavailable = false;
      state_.frame.reset();
      queued_.push_front(makeRequest([](pb::ClientMessage& m) { m.mutable_set_parameters(); }));
    }
    state_.proximity.resize(moving);
  } else if (message.has_parameters()) {
    if (kind == pb::ClientMessage::kSetParameters && state_.loading) {
      state_.loading.reset();  // a rebuild ended: the grabs did too
      queued_.push_front(makeRequest([](pb::ClientMessage& m) { m.mutable_list_objects(); }));
    }
    state_.parameters = message.parameters();
  } else if (message.has_statistics()) {
    state_.statistics = message.statistics();
  } else if (message.has_proximity()) {
    for (std::size_t i = 0; i < state_.objects.size() && i < state_.proximity.size(); ++i) {
      if (state_.objects[i].name() == message.proximity().object()) state_.proximity[i] = message.proximity();
    }
  } else if (message.has_done() &&
             (kind == pb::ClientMessage::kGrab || kind == pb::ClientMessage::kRelease)) {
    queued_.push_front(makeRequest([](pb::ClientMessage& m) { m.mutable_list_objects(); }));
  }
}

}  // namespace voxhap::view

#include "app/controller/controller_service.h"

#include <cmath>
#include <cstring>

#include "haptics/core/error.h"
#include "haptics/device/motion_script.h"
#include "haptics/device/simulated_hand_device.h"
#include "haptics/scene/scene.h"
#include "net/frontend/pose_proto.h"

namespace voxhap::controller {
namespace {

namespace pb = net::pb;
using net::toProto;
/// Farthest GetProximity lists static surface voxels, in static voxels (bounds the reply).
constexpr int kMaxProximityVoxels = 16;
/// Grab's device for the first SpaceMouse found, and the prefix that names one by path.
constexpr const char* kSpaceMouse = "spacemouse";
constexpr const char* kSpaceMousePrefix = "spacemouse:";
/// Grab's devices that play a motion script: rigidly, or as the target of a simulated hand
/// holding a force-feedback handle (simulated_hand_device.h).
constexpr const char* kScriptPrefix = "script:";
constexpr const char* kHandPrefix = "hand:";

void fail(pb::ServerMessage& reply, const std::string& message, const std::string& field = {}) {
  reply.mutable_error()->set_message(message);
  reply.mutable_error()->set_field(field);
}

/// False after filling `reply` with an Error naming the size or offset out of range.
bool sizesInRange(const pb::LoadScene& request, pb::ServerMessage& reply) {
  for (const auto& [field, value] : {std::pair{"voxel_size_m", request.voxel_size_m()},
                                     std::pair{"point_spacing_m", request.point_spacing_m()}}) {
    if (!(value >= 0.0 && value <= 1.0)) {
      fail(reply, std::string(field) + " wants 0 (the default) or a length up to 1 m", field);
      return false;
    }
  }
  if (!(std::abs(request.point_offset_m()) <= kMaxPointOffsetM)) {
    fail(reply, "point_offset_m wants a length of at most 1 m either way", "point_offset_m");
    return false;
  }
  return true;
}

double seconds(std::int64_t ns) {
  return static_cast<double>(ns) * 1e-9;
}

}  // namespace

ClientHandleDevice::ClientHandleDevice(const Pose& initialWorld, const DeviceLimits& limits)
    : pose_(initialWorld), limits_(limits) {}

Pose ClientHandleDevice::handlePose(double) noexcept {
  mailbox_.readNewer(version_, pose_);
  return pose_;
}

ControllerService::ControllerService(asio::io_context& io, std::unique_ptr<ControllerSession> session,
                                     SessionLoader loader, HapticLoopOptions loopOptions,
                                     const std::string& startDevice, std::function<void()> shutdown,
                                     LogFn log)
    : io_(io),
      loader_(std::move(loader)),
      shutdown_(std::move(shutdown)),
      log_(std::move(log)),
      loopOptions_(loopOptions) {
  std::optional<SimState> start = session ? std::move(session->start) : std::nullopt;
  replaceSession(std::move(session), std::move(start), startDevice);
}

ControllerService::~ControllerService() {
  cancelLoad_ = true;
  if (loadThread_.joinable()) loadThread_.join();
  stopLoop();
}

void ControllerService::hello(pb::HelloReply& reply) {
  reply.set_controller_version(std::string("voxhap ") + VOXHAP_VERSION);
  reply.set_scene(session_ ? session_->sceneName : std::string());
  reply.set_frame_period_s(session_ ? session_->built->model.dtS : 1e-3);
}

void ControllerService::stopLoop() {
  if (!session_) return;
  session_->loop->stop();
  collectRetired();
}

void ControllerService::replaceSession(std::unique_ptr<ControllerSession> session,
                                       std::optional<SimState> start, const std::string& startDevice) {
  stopLoop();
  devices_.clear();  // every device is retired once the old loop has stopped
  spaceMice_.clear();
  session_ = std::move(session);
  const std::size_t n = session_ ? session_->built->model.objects.size() : 0;
  heldBy_.assign(n, std::string());
  heldByClient_.assign(n, 0);
  clientHandles_.assign(n, nullptr);
  if (!session_) return;
  const SimModel& model = session_->built->model;
  SimState state = start ? std::move(*start) : makeSimState(model);
  forceLayer_ = state.forceLayer;
  HapticLoopOptions options = loopOptions_;
  options.periodNs = std::llround(model.dtS * 1e9);
  session_->loop =
      std::make_unique<HapticLoop>(model, std::move(state), session_->built->staticPager, options);
  postCouplingGains();  // a fresh queue, with room for one command per object
  if (!startDevice.empty()) {
    // queued before the first frame, which takes it (the loop's first snapshot already
    // shows where the object starts)
    pb::Grab grabIt;
    grabIt.set_object(model.objects.front().name);
    grabIt.set_device(startDevice);
    pb::ServerMessage reply;
    grab(0, grabIt, reply);
    if (reply.has_error()) throw Error("device " + startDevice + ": " + reply.error().message());
  }
  session_->loop->start();
}

bool ControllerService::postCouplingGains() {
  const std::vector<CouplingGains> gains = couplingGains();
  for (std::size_t i = 0; i < gains.size(); ++i) {
    if (!session_->built->model.objects[i].coupled) continue;
    LoopCommand command;
    command.kind = LoopCommand::Kind::SetCouplingGains;
    command.object = static_cast<std::uint32_t>(i);
    command.gains = gains[i];
    if (!session_->loop->post(command)) {
      ++droppedCommands_;
      return false;
    }
  }
  return true;
}

std::vector<CouplingGains> ControllerService::couplingGains() const {
  std::vector<CouplingGains> gains;
  for (const MovingObjectModel& o : session_->built->model.objects)
    gains.push_back(o.coupled
                        ? scaledCouplingGains(o.gains, o.body, couplingStiffnessShare_, couplingDampingRatio_)
                        : CouplingGains{});
  return gains;
}

void ControllerService::collectRetired() {
  if (!session_) return;
  while (HapticDevice* device = session_->loop->takeRetired()) devices_.erase(device);
}

void ControllerService::handle(std::uint64_t client, const pb::ClientMessage& request,
                               pb::ServerMessage& reply) {
  collectRetired();
  switch (request.request_case()) {
    case pb::ClientMessage::kListObjects:
      listObjects(*reply.mutable_object_list());
      return;
    case pb::ClientMessage::kLoadScene:
      load(client, request.id(), request.load_scene(), LoadKind{}, reply);
      return;
    case pb::ClientMessage::kGrab:
      grab(client, request.grab(), reply);
      return;
    case pb::ClientMessage::kRelease:
      release(request.release().object(), reply);
      return;
    case pb::ClientMessage::kSetParameters:
      setParameters(client, request.id(), request.set_parameters(), reply);
      return;
    case pb::ClientMessage::kMoveHandle:
      moveHandle(client, request.move_handle(), reply);
      return;
    case pb::ClientMessage::kGetProximity:
      proximity(request.get_proximity(), reply);
      return;
    case pb::ClientMessage::kGetStatistics:
      statistics(*reply.mutable_statistics());
      return;
    case pb::ClientMessage::kShutdown:
      reply.mutable_done();
      log_("shutdown asked by client " + std::to_string(client));
      shutdown_();
      return;
    default:
      fail(reply, "this controller does not serve that request yet");
      return;
  }
}

void ControllerService::listObjects(pb::ObjectList& list) const {
  if (!session_) return;
  const SimModel& model = session_->built->model;
  for (std::size_t i = 0; i < model.objects.size(); ++i) {
    pb::ObjectInfo& o = *list.add_objects();
    o.set_index(static_cast<std::uint32_t>(i));
    o.set_name(model.objects[i].name);
    o.set_moving(true);
    o.set_mass_kg(model.objects[i].body.massKg);
    o.set_held_by(heldBy_[i]);
    o.set_points(static_cast<std::uint32_t>(model.objects[i].shell.size()));
  }
  for (std::size_t i = 0; i < session_->staticObjects.size(); ++i) {
    pb::ObjectInfo& o = *list.add_objects();
    o.set_index(static_cast<std::uint32_t>(model.objects.size() + i));
    o.set_name(session_->staticObjects[i]);
  }
}

int ControllerService::movingObject(const std::string& name, pb::ServerMessage& reply) const {
  if (!session_) {
    fail(reply, "no scene is loaded (load_scene first)", "object");
    return -1;
  }
  const SimModel& model = session_->built->model;
  for (std::size_t i = 0; i < model.objects.size(); ++i) {
    if (model.objects[i].name == name) return static_cast<int>(i);
  }
  std::string names;
  for (const MovingObjectModel& o : model.objects) names += (names.empty() ? "" : ", ") + o.name;
  fail(reply, "no moving object '" + name + "' (moving: " + names + ")", "object");
  return -1;
}

bool ControllerService::post(const LoopCommand& command, pb::ServerMessage& reply) {
  if (session_->loop->post(command)) return true;
  ++droppedCommands_;
  fail(reply, "the haptic thread's command queue is full; try again");
  return false;
}

void ControllerService::grab(std::uint64_t client, const pb::Grab& request, pb::ServerMessage& reply) {
  const int object = movingObject(request.object(), reply);
  if (object < 0) return;
  const auto i = static_cast<std::size_t>(object);
  if (peerHooks_) {
    if (const std::string why = peerHooks_->whyNotGrab(i); !why.empty()) {
      fail(reply, why, "object");
      return;
    }
  }
  const std::string& device = request.device();
  std::unique_ptr<HapticDevice> created;  // null for a SpaceMouse, which stays open between grabs
  HapticDevice* holder = nullptr;
  ClientHandleDevice* clientHandle = nullptr;
  StandingSpaceMouse* mouse = nullptr;
  if (device.rfind(kScriptPrefix, 0) == 0 || device.rfind(kHandPrefix, 0) == 0) {
    const MovingObjectModel& o = session_->built->model.objects[i];
    try {
      if (device.rfind(kScriptPrefix, 0) == 0) {
        created = std::make_unique<ScriptedDevice>(
            loadMotionScript(device.substr(std::strlen(kScriptPrefix))), session_->built->model.deviceLimits);
      } else {
        SimulatedHandParams hand;
        hand.graspLocal = o.body.comLocal;
        created =
            std::make_unique<SimulatedHandDevice>(loadMotionScript(device.substr(std::strlen(kHandPrefix))),
                                                  hand, session_->built->model.deviceLimits);
      }
    } catch (const Error& e) {
      fail(reply, e.what(), "device");
      return;
    }
  } else if (device == kSpaceMouse || device.rfind(kSpaceMousePrefix, 0) == 0) {
    for (std::size_t j = 0; j < heldBy_.size(); ++j) {
      if (j != i && heldBy_[j] == device) {
        fail(reply, device + " holds '" + session_->built->model.objects[j].name + "'; release it first",
             "device");
        return;
      }
    }
    mouse = spaceMouse(device, session_->loop->latest().objects[i].pose, reply);
    if (mouse == nullptr) return;
    holder = mouse->mouse.get();
  } else if (device == "client") {
    auto handle = std::make_unique<ClientHandleDevice>(session_->loop->latest().objects[i].pose,
                                                       session_->built->model.deviceLimits);
    clientHandle = handle.get();
    created = std::move(handle);
  } else {
    fail(reply, "unknown device '" + device + "' (script:PATH, hand:PATH, spacemouse[:PATH] or client)",
         "device");
    return;
  }
  if (created) holder = created.get();
  LoopCommand command;
  command.kind = LoopCommand::Kind::Grab;
  command.object = static_cast<std::uint32_t>(i);
  command.device = holder;
  if (!post(command, reply)) return;
  if (created) devices_.emplace(holder, std::move(created));
  if (mouse) mouse->object = i;
  heldBy_[i] = device;
  heldByClient_[i] = clientHandle ? client : 0;
  clientHandles_[i] = clientHandle;
  reply.mutable_done();
}

void ControllerService::release(const std::string& name, pb::ServerMessage& reply) {
  const int object = movingObject(name, reply);
  if (object < 0) return;
  LoopCommand command;
  command.kind = LoopCommand::Kind::Release;
  command.object = static_cast<std::uint32_t>(object);
  if (!post(command, reply)) return;
  heldBy_[static_cast<std::size_t>(object)].clear();
  heldByClient_[static_cast<std::size_t>(object)] = 0;
  clientHandles_[static_cast<std::size_t>(object)] = nullptr;
  reply.mutable_done();
}

void ControllerService::setParameters(std::uint64_t client, std::uint64_t id,
                                      const pb::SetParameters& request, pb::ServerMessage& reply) {
  if (!session_) {
    fail(reply, "no scene is loaded (load_scene first)");
    return;
  }
  const SimModel& model = session_->built->model;
  // check every field before anything changes
  if (request.has_force_layer()) {
    const std::uint32_t value = request.force_layer();
    if (value > 255 || !model.forceLayerInRange(static_cast<std::uint8_t>(value))) {
      fail(reply,
           "force_layer " + std::to_string(value) + " is outside " + std::to_string(model.minForceLayer()) +
               " to " + std::to_string(model.maxForceLayer()) +
               (model.usesSurfaceContact() ? " (the values every pair's voxmap renders that reach the points "
                                             "of contact by surface planes)"
                                           : " (the values every pair's voxmap renders)"),
           "force_layer");
      return;
    }
  }
  const double share =
      request.has_coupling_stiffness_share() ? request.coupling_stiffness_share() : couplingStiffnessShare_;
  if (!(share > 0.0 && share <= 1.0)) {
    fail(reply, "coupling_stiffness_share wants a share above 0 and at most 1", "coupling_stiffness_share");
    return;
  }
  const double ratio =
      request.has_coupling_damping_ratio() ? request.coupling_damping_ratio() : couplingDampingRatio_;
  if (!(ratio >= kMinCouplingDampingRatio && ratio <= kMaxCouplingDampingRatio)) {
    fail(reply, "coupling_damping_ratio wants 0.1 to 2 (1: critical)", "coupling_damping_ratio");
    return;
  }
  pb::LoadScene rebuild = session_->source;
  LoadKind kind{true, {}};
  if (request.has_voxel_size_m()) {
    rebuild.set_voxel_size_m(request.voxel_size_m());
    kind.errorField = "voxel_size_m";
  }
  if (request.has_point_spacing_m()) {
    rebuild.set_point_spacing_m(request.point_spacing_m());
    if (kind.errorField.empty()) kind.errorField = "point_spacing_m";
  }
  if (request.has_point_offset_m()) {
    rebuild.set_point_offset_m(request.point_offset_m());
    if (kind.errorField.empty()) kind.errorField = "point_offset_m";
  }
  const bool rebuilds = !kind.errorField.empty();
  if (rebuilds && !sizesInRange(rebuild, reply)) return;
  if (rebuilds && loading_) {
    fail(reply, "a scene is loading already; wait for its reply");
    return;
  }
  if (peerHooks_ && (rebuilds || request.has_force_layer())) {
    fail(reply, peerHooks_->whyNotReload, rebuilds ? kind.errorField : "force_layer");
    return;
  }

  if (request.has_force_layer()) {
    LoopCommand command;
    command.kind = LoopCommand::Kind::SetForceLayer;
    command.value = request.force_layer();
    if (!post(command, reply)) return;
    forceLayer_ = command.value;
  }
  if (share != couplingStiffnessShare_ || ratio != couplingDampingRatio_) {
    couplingStiffnessShare_ = share;
    couplingDampingRatio_ = ratio;
    if (!postCouplingGains()) {
      fail(reply, "the haptic thread's command queue is full; try again");
      return;
    }
  }
  if (rebuilds) {
    load(client, id, rebuild, kind, reply);  // the reply follows the rebuild
    return;
  }
  parameters(*reply.mutable_parameters());
}

void ControllerService::parameters(pb::Parameters& out) const {
  const SimModel& model = session_->built->model;
  out.set_force_layer(forceLayer_);
  out.set_min_force_layer(model.pairs.empty() ? 0 : model.minForceLayer());
  out.set_max_force_layer(model.pairs.empty() ? 0 : model.maxForceLayer());
  out.set_voxel_size_m(session_->voxelSizeM);
  out.set_point_spacing_m(session_->pointSpacingM);
  out.set_point_offset_m(session_->pointOffsetM);
  out.set_coupling_stiffness_share(couplingStiffnessShare_);
  out.set_coupling_damping_ratio(couplingDampingRatio_);
  for (const CouplingGains& g : couplingGains()) {
    pb::CouplingGains& c = *out.add_coupling();
    c.set_linear_stiffness_n_per_m(g.linearStiffnessNPerM);
    c.set_linear_damping_ns_per_m(g.linearDampingNsPerM);
    c.set_angular_stiffness_nm_per_rad(g.angularStiffnessNmPerRad);
    c.set_angular_damping_nms_per_rad(g.angularDampingNmsPerRad);
  }
}

void ControllerService::moveHandle(std::uint64_t client, const pb::MoveHandle& request,
                                   pb::ServerMessage& reply) {
  const int object = movingObject(request.object(), reply);
  if (object < 0) return;
  const auto i = static_cast<std::size_t>(object);
  if (heldByClient_[i] != client || clientHandles_[i] == nullptr) {
    fail(reply,
         "'" + request.object() + "' is not held by this client's handle (grab it with device 'client')",
         "object");
    return;
  }
  const Pose pose = net::fromProto(request.handle());
  const double norm = glm::length(pose.orientation);
  if (!isFinite(pose) || std::abs(norm - 1.0) > 1e-6) {
    fail(reply, "the handle pose must be finite with a unit quaternion", "handle");
    return;
  }
  clientHandles_[i]->move(pose);
  reply.mutable_done();
}

ControllerService::StandingSpaceMouse* ControllerService::spaceMouse(const std::string& device,
                                                                     const Pose& startWorld,
                                                                     pb::ServerMessage& reply) {
  for (StandingSpaceMouse& s : spaceMice_) {
    if (s.device == device) return &s;
  }
  SpaceMouseConfig config;
  if (device != kSpaceMouse) config.path = device.substr(std::strlen(kSpaceMousePrefix));
  try {
    auto mouse = std::make_unique<SpaceMouseDevice>(startWorld, session_->built->model.deviceLimits, config);
    log_(device + ": " + mouse->openedAtStart().name + " at " + mouse->openedAtStart().path);
    log_(device + ": " + mouse->hotplugStatus());
    spaceMice_.push_back({device, std::move(mouse), 0});
  } catch (const Error& e) {
    fail(reply, e.what(), "device");
    return nullptr;
  }
  return &spaceMice_.back();
}

void ControllerService::pollDevices() {
  for (StandingSpaceMouse& s : spaceMice_) {
    ButtonEvent event;
    while (s.mouse->tryPopButtonEvent(event)) {
      if (event.button != 1 || !event.pressed || !session_) continue;
      const std::string& name = session_->built->model.objects[s.object].name;
      const bool held = heldBy_[s.object] == s.device;
      pb::ServerMessage reply;
      if (held) {
        release(name, reply);
      } else {
        pb::Grab grabIt;
        grabIt.set_object(name);
        grabIt.set_device(s.device);
        grab(0, grabIt, reply);
      }
      log_(s.device + " button 1: " +
           (reply.has_error() ? reply.error().message() : (held ? "released " : "grabbed ") + name));
    }
  }
}

void ControllerService::proximity(const pb::GetProximity& request, pb::ServerMessage& reply) {
  const int object = movingObject(request.object(), reply);
  if (object < 0) return;
  const SessionProximity& proximity = *session_->proximity;
  if (!proximity.unavailable().empty()) {
    fail(reply, "no proximity in this session: " + proximity.unavailable());
    return;
  }
  const double voxelM = session_->built->model.staticVoxmap->grid().voxelSizeM;
  const double withinM = request.within_m();
  if (!(withinM >= 0.0 && withinM <= kMaxProximityVoxels * voxelM)) {
    fail(reply,
         "within_m wants 0 to " + std::to_string(kMaxProximityVoxels) + " static voxels (" +
             std::to_string(kMaxProximityVoxels * voxelM) + " m)",
         "within_m");
    return;
  }
  const FrameSnapshot& s = session_->loop->latest();
  ProximityResult result;
  proximity.measure(static_cast<std::size_t>(object), s.objects[static_cast<std::size_t>(object)].pose,
                    withinM, result);
  pb::Proximity& out = *reply.mutable_proximity();
  out.set_object(request.object());
  out.set_frame(s.frame);
  out.set_voxel_size_m(result.staticVoxelSizeM);
  out.mutable_vertex_distance_m()->Add(result.vertexDistanceM.begin(), result.vertexDistanceM.end());
  net::appendXyz(result.nearStaticVoxelsWorld, *out.mutable_near_voxel_centre_m());
}

void ControllerService::frameUpdate(pb::FrameUpdate& update) {
  if (!session_) return;
  const FrameSnapshot& s = session_->loop->latest();
  update.set_frame(s.frame);
  update.set_time_s(s.timeS);
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    const ObjectSnapshot& o = s.objects[i];
    pb::ObjectState& out = *update.add_objects();
    out.set_index(static_cast<std::uint32_t>(i));
    toProto(o.pose, *out.mutable_pose());
    if (o.held) toProto(o.handle, *out.mutable_handle());
    toProto(o.forceWorld, *out.mutable_force_n());
    out.set_contacts(o.contacts);
    net::appendXyz(o.contactSample.points(), *out.mutable_contact_point_m());
    out.set_travel_share(o.travelShare);
    out.set_owner_peer(o.owner);
    if (o.shared) {
      out.set_divergent(o.port.coupling.divergent);
      out.set_shared_apart_m(o.port.coupling.apartM);
    }
  }
  if (peerHooks_ && peerHooks_->annotate) peerHooks_->annotate(update);
}

void ControllerService::disconnected(std::uint64_t client) {
  for (std::size_t i = 0; i < heldByClient_.size(); ++i) {
    if (heldByClient_[i] != client) continue;
    // its handle is gone: the object stays where it is, free
    pb::ServerMessage ignored;
    release(session_->built->model.objects[i].name, ignored);
  }
}

void ControllerService::statistics(pb::Statistics& out) const {
  out.set_dropped_commands(droppedCommands_);
  if (!session_) return;
  HapticLoop& loop = *session_->loop;
  const FrameSnapshot& s = loop.latest();
  out.set_frames(s.frame);
  out.set_overruns(s.period.overruns);
  out.set_period_p50_s(seconds(s.period.p50Ns));
  out.set_period_p99_s(seconds(s.period.p99Ns));
  out.set_period_p999_s(seconds(s.period.p999Ns));
  out.set_period_max_s(seconds(s.period.maxNs));
  out.set_compute_p50_s(seconds(s.compute.p50Ns));
  out.set_compute_p99_s(seconds(s.compute.p99Ns));
  out.set_compute_max_s(seconds(s.compute.maxNs));
  out.set_missed_deadlines(s.missedDeadlines);
  out.set_resyncs(s.resyncs);
  out.set_realtime(loop.realtime().fifo.ok);
  out.set_memory_locked(loop.realtime().memoryLock.ok);
  out.set_fifo_given_up(s.fifoGivenUp);
}

void ControllerService::load(std::uint64_t client, std::uint64_t id, const pb::LoadScene& request,
                             const LoadKind& kind, pb::ServerMessage& reply) {
  if (loading_) {
    fail(reply, "a scene is loading already; wait for its reply");
    return;
  }
  if (peerHooks_) {
    fail(reply, peerHooks_->whyNotReload, kind.errorField);
    return;
  }
  if (request.scene().empty()) {
    fail(reply, "load_scene wants a scene (a .gltf/.glb path or a built-in name)", "scene");
    return;
  }
  if (request.move_size() == 0) {
    fail(reply, "load_scene wants at least one object to move", "move");
    return;
  }
  if (!sizesInRange(request, reply)) return;
  if (loadThread_.joinable()) loadThread_.join();
  loading_ = true;
  log_("client " + std::to_string(client) + (kind.rebuild ? " rebuilds " : " loads ") + request.scene());
  loadThread_ = std::thread([this, client, id, request, kind] {
    auto lastPercent = std::make_shared<int>(-1);
    const ProgressFn progress = [this, client, id, lastPercent](double fraction) {
      if (cancelLoad_) throw Error("the load was cancelled");
      const int percent = static_cast<int>(fraction * 100.0);
      if (percent == *lastPercent) return;
      *lastPercent = percent;
      asio::post(io_, [this, client, id, fraction] {
        pb::ServerMessage event;
        pb::LoadProgress& p = *event.mutable_load_progress();
        p.set_request_id(id);
        p.set_stage("preparing voxels");
        p.set_fraction(fraction);
        if (send_) send_(client, event);
      });
    };
    std::unique_ptr<ControllerSession> loaded;
    std::string error;
    try {
      loaded = loader_(request, progress);
    } catch (const std::exception& e) {
      error = e.what();
    }
    auto result = std::make_shared<std::unique_ptr<ControllerSession>>(std::move(loaded));
    asio::post(io_, [this, client, id, kind, result, error] {
      finishLoad(client, id, kind, std::move(*result), error);
    });
  });
  // the reply follows when the load is done (finishLoad)
}

void ControllerService::finishLoad(std::uint64_t client, std::uint64_t id, const LoadKind& kind,
                                   std::unique_ptr<ControllerSession> loaded, const std::string& error) {
  loading_ = false;
  pb::ServerMessage reply;
  reply.set_id(id);
  if (!loaded) {
    log_("load for client " + std::to_string(client) + " failed: " + error);
    fail(reply, error, kind.errorField);
  } else {
    log_("now simulating " + loaded->sceneName);
    pb::ServerMessage done;
    done.mutable_load_progress()->set_request_id(id);
    done.mutable_load_progress()->set_stage("loaded");
    done.mutable_load_progress()->set_fraction(1.0);
    if (send_) send_(client, done);
    std::optional<SimState> start;
    if (kind.rebuild && session_) {
      // the same objects, where they are now, at rest; the force layer kept when it fits
      const SimModel& model = loaded->built->model;
      start = makeSimState(model);
      const FrameSnapshot& now = session_->loop->latest();
      for (std::size_t i = 0; i < model.objects.size() && i < now.objects.size(); ++i)
        start->bodies[i] = restingState(model.objects[i].body, now.objects[i].pose);
      if (model.forceLayerInRange(static_cast<std::uint8_t>(forceLayer_)))
        start->forceLayer = static_cast<std::uint8_t>(forceLayer_);
    } else {
      couplingStiffnessShare_ = 1.0;
      couplingDampingRatio_ = kCouplingDampingRatio;
    }
    replaceSession(std::move(loaded), std::move(start));
    if (kind.rebuild) {
      parameters(*reply.mutable_parameters());
    } else {
      listObjects(*reply.mutable_object_list());
    }
  }
  if (send_) send_(client, reply);
}

}  // namespace voxhap::controller

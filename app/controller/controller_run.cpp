#include "app/controller/controller_run.h"

#include <chrono>
#include <csignal>
#include <iomanip>

#include <asio/io_context.hpp>
#include <asio/post.hpp>
#include <asio/signal_set.hpp>
#include <asio/steady_timer.hpp>
#include <nlohmann/json.hpp>

#include "app/controller/controller_service.h"
#include "app/controller/peer_link.h"
#include "app/scene_source.h"
#include "haptics/core/error.h"
#include "haptics/scene/object_selection.h"
#include "net/frontend/pose_proto.h"
#include "net/peer/peer_session.h"

namespace voxhap::cli {
namespace {

using controller::ControllerService;
using controller::HapticLoop;

/// How often the comms thread looks after the haptic thread (retired devices, a stop).
constexpr auto kHousekeepingPeriod = std::chrono::milliseconds(50);
/// How long a stopping controller waits for its clients to take their last messages.
constexpr auto kLastWrites = std::chrono::seconds(2);

/// What a refusal's errno text says, or that nobody asked (--no-realtime).
std::string why(const RealtimeOutcome& outcome) {
  return " (" + (outcome.error.empty() ? std::string("not asked: --no-realtime") : outcome.error) + ")";
}

std::string realtimeLine(const HapticLoop& loop) {
  const RealtimeStatus& status = loop.realtime();
  std::string line = status.fifo.ok
                         ? "haptic thread under SCHED_FIFO priority " + std::to_string(status.fifoPriority)
                         : "haptic thread without SCHED_FIFO" + why(status.fifo);
  line += status.memoryLock.ok ? ", memory locked" : ", memory not locked" + why(status.memoryLock);
  if (loop.frameHelperCpu() >= 0) line += ", a frame helper on CPU " + std::to_string(loop.frameHelperCpu());
  if (!status.fifo.ok) line += "; periods may stretch when the machine is busy";
  return line;
}

double us(std::int64_t ns) {
  return static_cast<double>(ns) * 1e-3;
}

nlohmann::ordered_json summaryJson(const PeriodSummary& s) {
  return {{"count", s.count},          {"overruns", s.overruns},  {"p50_us", us(s.p50Ns)},
          {"p99_us", us(s.p99Ns)},     {"p999_us", us(s.p999Ns)}, {"max_us", us(s.maxNs)},
          {"mean_us", s.meanNs * 1e-3}};
}

void printSummary(std::ostream& out, const char* label, const PeriodSummary& s) {
  out << std::left << std::setw(17) << label << std::right << std::fixed << std::setprecision(1) << "p50 "
      << us(s.p50Ns) << " µs, p99 " << us(s.p99Ns) << " µs, p99.9 " << us(s.p999Ns) << " µs, max "
      << us(s.maxNs) << " µs; " << s.overruns << " over " << (label[0] == 'p' ? "1.5 ms" : "1 ms") << "\n";
}

/// What peers compare at join: every object's name, settings and meshes, and the moving names.
Digest128 sceneHash(const Scene& scene, const std::vector<std::string>& moving) {
  ContentHash hash;
  const auto addText = [&hash](const std::string& text) {
    hash.addArray(std::span(text.data(), text.size()));
  };
  hash.add(static_cast<std::uint64_t>(scene.objects.size()));
  for (const SceneObject& object : scene.objects) {
    addText(object.name);
    hash.add(static_cast<std::uint32_t>(object.settings.role));
    hash.addDouble(object.settings.densityKgPerM3.value_or(0.0));  // 0: the engine's default
    hash.addDouble(object.settings.pointOffsetM.value_or(0.0));
    hash.add(std::uint32_t{object.settings.forceLayer.value_or(0)});  // 0: the session's
    hash.add(static_cast<std::uint64_t>(object.parts.size()));
    for (const Part& part : object.parts) {
      hash.addArray(std::span<const glm::vec3>(part.mesh.positionsWorld));
      hash.addArray(std::span<const glm::uvec3>(part.mesh.triangles));
    }
  }
  for (const std::string& name : moving) addText(name);
  return hash.digest();
}

/// Loads the scene `source` names and builds it with `model` (the sizes and offset already
/// taken from `source`), all but its haptic loop.
std::unique_ptr<controller::ControllerSession> loadSession(const net::pb::LoadScene& source,
                                                           const SceneModelOptions& model, Console& console,
                                                           const ProgressFn& progress) {
  auto session = std::make_unique<controller::ControllerSession>();
  const Scene scene = loadScene(source.scene(), kDefaultSeed, console);
  // none named: the scene's dynamic objects (a peer's default)
  const std::vector<std::string> moving =
      source.move().empty() ? dynamicObjectNames(scene)
                            : std::vector<std::string>(source.move().begin(), source.move().end());
  if (moving.empty()) throw Error("nothing to move in " + source.scene() + ": name an object or group");
  session->source = source;
  if (source.move().empty()) {
    for (const std::string& name : moving) session->source.add_move(name);
  }
  session->sceneName = scene.sourceName;
  session->sceneHash = sceneHash(scene, moving);
  session->voxelSizeM = model.staticVoxelSizeM;
  session->pointSpacingM = model.pointSpacingM;
  const ObjectSelection selection = selectObjects(scene, moving);
  session->pointOffsetM = pointDisplacementOf(*selection.picked.front(), model);
  for (const SceneObject* o : selection.rest) session->staticObjects.push_back(o->name);
  // the voxels take most of the load; the moving objects' own surface voxmaps the rest
  const ProgressFn voxels = [&progress](double f) {
    if (progress) progress(0.9 * f);
  };
  session->built = std::make_unique<BuiltScene>(buildScene(scene, moving, model, voxels));
  const SimModel& m = session->built->model;
  std::vector<std::string> names;
  for (const MovingObjectModel& o : m.objects) names.push_back(o.name);
  session->proximity = std::make_unique<controller::SessionProximity>(selectObjects(scene, names), m, model,
                                                                      [&progress](double f) {
                                                                        if (progress) progress(0.9 + 0.1 * f);
                                                                      });
  return session;
}

/// The session key: from the file, or (for the first member only) a new one, printed.
net::SessionKey sessionKey(const PeerRunOptions& peer, Console& console) {
  if (!peer.keyFile.empty()) return net::SessionKey::fromFile(peer.keyFile);
  if (!peer.joinHost.empty())
    throw Error("--join needs --key FILE: the session key its first member printed");
  const net::SessionKey key = net::SessionKey::generate();
  console.info("session key " + key.toHex() + " (the others join with it in a file: --key FILE)");
  return key;
}

/// Binds the peer's socket and, when asked, joins through a member: the loop of `session`
/// then starts from the member's snapshot.
std::unique_ptr<net::PeerSession> startPeer(const PeerRunOptions& peer,
                                            controller::ControllerSession& session, asio::io_context& io,
                                            Console& console) {
  const SimModel& model = session.built->model;
  net::PeerSessionOptions o;
  o.listenHost = peer.listenHost;
  o.listenPort = peer.listenPort;
  o.advertise = peer.advertise;
  o.name = peer.name;
  o.timeout = std::chrono::milliseconds(std::llround(peer.timeoutS * 1e3));
  o.parameters.set_scene_hash(&session.sceneHash, sizeof session.sceneHash);
  o.parameters.set_voxel_size_m(session.voxelSizeM);
  o.parameters.set_point_spacing_m(session.pointSpacingM);
  o.parameters.set_point_offset_m(session.pointOffsetM);
  o.parameters.set_force_layer(makeSimState(model).forceLayer);
  o.parameters.set_moving_objects(static_cast<std::uint32_t>(model.objects.size()));
  o.parameters.set_surface_contact(model.usesSurfaceContact());
  auto peerSession =
      std::make_unique<net::PeerSession>(io, sessionKey(peer, console), std::move(o),
                                         [&console](const std::string& line) { console.info(line); });
  console.info("peer " + std::to_string(peerSession->self()) + " listening for peers on " + peer.listenHost +
               ":" + std::to_string(peerSession->port()) + " (UDP)");
  if (!peer.joinHost.empty()) {
    const auto started = std::chrono::steady_clock::now();
    const std::vector<std::byte> snapshot = peerSession->join(
        peer.joinHost, peer.joinPort, std::chrono::milliseconds(std::llround(peer.joinPatienceS * 1e3)));
    session.start = restoreState(model, snapshot);
    console.info("joined through " + peer.joinHost + ":" + std::to_string(peer.joinPort) + " in " +
                 std::to_string(std::llround(secondsSince(started) * 1e3)) + " ms (" +
                 std::to_string(snapshot.size()) + " bytes of state)");
  }
  return peerSession;
}

/// Why a client of a peer may not grab `object`: it is another's, or nobody's yet (either
/// way this peer asks for it).
std::string whyNotGrab(net::PeerSession& peer, const SimModel& model, std::size_t object) {
  const PeerId owner = peer.owners()[object];
  if (owner == peer.self() || peer.sharing(static_cast<std::uint32_t>(object))) return {};
  peer.want(static_cast<std::uint32_t>(object));
  const std::string name = "'" + model.objects[object].name + "'";
  if (owner == kNoPeer) return name + " was nobody's: this peer takes it now; grab it again in a moment";
  return name + " is peer " + std::to_string(owner) +
         "'s: asked for it; it comes here once nobody holds it there; grab it again then";
}

/// The shared objects' sharers in `update`, whether any of them sees its instance
/// divergent, and then the instances this peer does not show: on a sharer every other
/// one, elsewhere all but the owner's.
void annotateShared(const net::PeerSession& peer, const SimModel& model, net::pb::FrameUpdate& update) {
  for (net::pb::ObjectState& o : *update.mutable_objects()) {
    const std::vector<net::SharerView> others = peer.sharers(o.index());
    if (peer.sharing(o.index())) o.add_sharer_peers(peer.self());
    for (const net::SharerView& v : others) {
      o.add_sharer_peers(v.peer);
      if (v.divergent) o.set_divergent(true);
    }
    if (!o.divergent() || o.index() >= model.objects.size()) continue;
    const PeerId shown = peer.sharing(o.index())            ? peer.self()
                         : o.index() < peer.owners().size() ? peer.owners()[o.index()]
                                                            : kNoPeer;
    for (const net::SharerView& v : others) {
      if (v.peer != shown)
        net::toProto(v.instance.pose(model.objects[o.index()].body), *o.add_other_instances());
    }
  }
}

/// Every object somebody shares: its sharers, who of them sees it divergent, and (when
/// this peer is one of them) how its coupling went.
nlohmann::ordered_json sharedJson(const net::PeerSession& peer, const controller::PeerLink& link,
                                  const SimModel& model) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (std::uint32_t o = 0; o < model.objects.size(); ++o) {
    const std::vector<net::SharerView> others = peer.sharers(o);
    const bool here = static_cast<int>(o) == link.sharedObject();
    if (others.empty() && !here) continue;
    nlohmann::ordered_json sharers = nlohmann::ordered_json::array(),
                           divergent = nlohmann::ordered_json::array();
    for (const net::SharerView& v : others) {
      sharers.push_back(v.peer);
      if (v.divergent) divergent.push_back(v.peer);
    }
    nlohmann::ordered_json j = {{"object", model.objects[o].name},
                                {"shared_here", here},
                                {"other_sharers", sharers},
                                {"divergent_at", divergent}};
    if (here) {
      const controller::SharedLinkStats& s = link.sharedStats();
      const double coupled = static_cast<double>(std::max<std::uint64_t>(s.coupledTicks, 1));
      j["coupling"] = {{"ticks", s.ticks},
                       {"coupled_ticks", s.coupledTicks},
                       {"divergent_ticks", s.divergentTicks},
                       {"mean_apart_mm", 1e3 * s.sumApartM / coupled},
                       {"max_apart_mm", 1e3 * s.maxApartM},
                       {"max_stiffness_share", s.maxStiffnessShare},
                       {"min_observed_j", s.minObservedJ},
                       {"in_j", s.inJ},
                       {"dissipated_j", s.dissipatedJ},
                       {"largest_force_step_n", s.largestForceStepN},
                       {"remote_instance_states", s.sharedStates}};
    }
    out.push_back(j);
  }
  return out;
}

nlohmann::ordered_json peerJson(const net::PeerSession& peer, const controller::PeerLink& linked,
                                const SimModel& model) {
  const controller::PeerLinkCounts& link = linked.counts();
  const net::PeerSessionCounts& c = peer.counts();
  nlohmann::ordered_json members = nlohmann::ordered_json::array();
  for (const net::MemberView& m : peer.members()) {
    members.push_back(
        {{"peer", m.peer},
         {"endpoint", m.endpoint},
         {"name", m.name},
         {"rtt_ms", m.rttMs < 0.0 ? nlohmann::ordered_json() : nlohmann::ordered_json(m.rttMs)},
         {"one_way_ms", m.oneWayMs < 0.0 ? nlohmann::ordered_json() : nlohmann::ordered_json(m.oneWayMs)},
         {"bytes_in", m.bytesIn},
         {"bytes_out", m.bytesOut}});
  }
  nlohmann::ordered_json opened;
  static constexpr const char* kResults[] = {"opened",   "bad_size", "not_ours", "no_window",
                                             "replayed", "too_old",  "forged",   "payload_too_big"};
  for (std::size_t i = 0; i < c.opened.size(); ++i) opened[kResults[i]] = c.opened[i];
  return {{"self", peer.self()},
          {"members", members},
          {"owners", peer.owners()},
          {"warnings", peer.warnings()},
          {"datagrams_in", c.datagramsIn},
          {"bytes_in", c.bytesIn},
          {"datagrams_out", c.datagramsOut},
          {"bytes_out", c.bytesOut},
          {"flooded", c.flooded},
          {"malformed", c.malformed},
          {"unexpected", c.unexpected},
          {"send_failures", c.sendFailures},
          {"open_results", opened},
          {"remote_states", link.remoteStates},
          {"remote_states_dropped", link.remoteStatesDropped},
          {"owner_changes", link.ownerChanges},
          {"ticks", link.ticks},
          {"shared", sharedJson(peer, linked, model)}};
}

}  // namespace

void runController(const ControllerOptions& options, Console& console, std::ostream& out) {
  asio::error_code ec;
  const asio::ip::address address = asio::ip::make_address(options.listenHost, ec);
  if (ec) throw Error("--listen: '" + options.listenHost + "' is not an IP address");
  if (!address.is_loopback() && options.token.empty())
    throw Error("--listen " + options.listenHost +
                " is beyond loopback: give a --token FILE that clients must present");

  controller::HapticLoopOptions loopOptions;
  loopOptions.realtime = options.realtime;
  loopOptions.frameHelper = options.frameHelper;
  // what a LoadScene asks for, with this controller's options for the rest
  const controller::SessionLoader loader = [&options, &console](const net::pb::LoadScene& request,
                                                                const ProgressFn& progress) {
    SceneModelOptions model = options.model;
    if (request.voxel_size_m() > 0.0) model.staticVoxelSizeM = request.voxel_size_m();
    model.pointSpacingM =
        request.point_spacing_m() > 0.0 ? request.point_spacing_m() : model.staticVoxelSizeM;
    if (request.has_point_offset_m()) model.pointDisplacementM = request.point_offset_m();
    return loadSession(request, model, console, progress);
  };
  std::unique_ptr<controller::ControllerSession> initial;
  if (!options.scene.empty()) {
    net::pb::LoadScene source;
    source.set_scene(options.scene);
    for (const std::string& name : options.moving) source.add_move(name);
    // a point spacing equal to the voxel size follows it when a client changes the voxel size
    if (options.model.pointSpacingM != options.model.staticVoxelSizeM)
      source.set_point_spacing_m(options.model.pointSpacingM);
    initial = loadSession(source, options.model, console, console.progress("preparing voxels"));
  }

  asio::io_context io;
  std::unique_ptr<net::PeerSession> peer;
  if (options.peer) {
    if (!initial) throw Error("a peer needs a SCENE: every peer of a session loads the same");
    peer = startPeer(*options.peer, *initial, io, console);
    loopOptions.localPeer = peer->self();
  }
  std::unique_ptr<controller::PeerLink> link;
  asio::signal_set signals(io, SIGINT, SIGTERM);
  asio::steady_timer housekeeping(io);
  asio::steady_timer lastWrites(io);
  bool stopping = false;
  std::string stopReason;
  std::unique_ptr<net::FrontendServer> server;
  std::function<void(std::chrono::steady_clock::time_point)> awaitClients = [&](auto giveUpAt) {
    if (server->clients() == 0 || std::chrono::steady_clock::now() >= giveUpAt) {
      io.stop();
      return;
    }
    lastWrites.expires_after(std::chrono::milliseconds(10));
    lastWrites.async_wait([&, giveUpAt](const asio::error_code&) { awaitClients(giveUpAt); });
  };
  // ends io.run() once every connection has written what it was sent (a reply to Shutdown),
  // or after kLastWritesS for a client that does not read
  auto stop = [&](const std::string& reason) {
    if (stopping) return;
    stopping = true;
    stopReason = reason;
    asio::post(io, [&] {
      if (link) link->stop();
      if (server) server->close();
      signals.cancel();
      housekeeping.cancel();
      awaitClients(std::chrono::steady_clock::now() + kLastWrites);
    });
  };
  const auto log = [&console](const std::string& line) { console.info(line); };
  ControllerService service(
      io, std::move(initial), loader, loopOptions, peer ? std::string() : options.device,
      [&] { stop("a client asked it to shut down"); }, log);
  net::FrontendServerOptions serverOptions;
  serverOptions.token = options.token;
  try {
    server = std::make_unique<net::FrontendServer>(io, asio::ip::tcp::endpoint(address, options.listenPort),
                                                   service, serverOptions, log);
  } catch (const std::system_error& e) {
    throw Error("cannot listen on " + options.listenHost + ":" + std::to_string(options.listenPort) + ": " +
                e.code().message());
  }
  service.setSender([&server](std::uint64_t client, const net::pb::ServerMessage& message) {
    return server->send(client, message);
  });

  if (const controller::ControllerSession* session = service.session())
    console.info(realtimeLine(*session->loop));
  if (peer) {
    const SimModel& model = service.session()->built->model;
    service.setPeerHooks(
        {[&peer, &model](std::size_t object) { return whyNotGrab(*peer, model, object); },
         "in a peer session the scene, its sizes and the force layer are every peer's",
         [&peer, &model](net::pb::FrameUpdate& update) { annotateShared(*peer, model, update); }});
    link = std::make_unique<controller::PeerLink>(
        io, *peer, service,
        controller::PeerLinkOptions{options.peer->streamHz, options.peer->take, options.device,
                                    options.peer->share, options.peer->passivity},
        log);
  }
  const asio::ip::tcp::endpoint listening = server->endpoint();
  console.info("listening on " + listening.address().to_string() + ":" + std::to_string(listening.port()));
  if (options.onListening) options.onListening(listening.port());

  signals.async_wait([&](const asio::error_code& e, int signal) {
    if (!e) stop(signal == SIGINT ? "SIGINT" : "SIGTERM");
  });
  const auto started = std::chrono::steady_clock::now();
  std::function<void()> keepHouse = [&] {
    service.collectRetired();
    service.pollDevices();
    if (service.session() && service.session()->loop->latest().stopped)
      stop("the haptic thread stopped (paging could not keep up)");
    if (options.durationS && secondsSince(started) >= *options.durationS) stop("the duration ran out");
    if (options.stopRequested && options.stopRequested->load()) stop("its owner asked it to stop");
    housekeeping.expires_after(kHousekeepingPeriod);
    housekeeping.async_wait([&](const asio::error_code& e) {
      if (!e && !stopping) keepHouse();
    });
  };
  keepHouse();
  io.run();

  service.stopLoop();
  const controller::ControllerSession* session = service.session();
  const controller::FrameSnapshot last = session ? session->loop->latest() : controller::FrameSnapshot{};
  const PeriodSummary period = session ? session->loop->periodStats().summary() : PeriodSummary{};
  const PeriodSummary compute = session ? session->loop->computeStats().summary() : PeriodSummary{};
  const bool fifo = session && session->loop->realtime().fifo.ok;
  const bool locked = session && session->loop->realtime().memoryLock.ok;
  const int helperCpu = session ? session->loop->frameHelperCpu() : -1;
  const std::string sceneName = session ? session->sceneName : std::string();
  const net::FrontendServerCounters& c = server->counters();
  console.info("stopped: " + stopReason);
  if (options.json) {
    nlohmann::ordered_json j = {
        {"scene", sceneName},
        {"stopped_by", stopReason},
        {"wall_s", secondsSince(started)},
        {"frames", last.frame},
        {"simulated_s", last.timeS},
        {"sched_fifo", fifo},
        {"sched_fifo_given_up", last.fifoGivenUp},
        {"memory_locked", locked},
        {"frame_helper_cpu", helperCpu >= 0 ? nlohmann::ordered_json(helperCpu) : nlohmann::ordered_json()},
        {"period", summaryJson(period)},
        {"compute", summaryJson(compute)},
        {"resyncs", last.resyncs},
        {"skipped_periods", last.skippedPeriods},
        {"missed_deadlines", last.missedDeadlines},
        {"dropped_commands", service.droppedCommands()},
        {"connections", c.connections},
        {"refused_connections", c.refused},
        {"protocol_violations", c.violations},
        {"requests", c.requests},
        {"updates_sent", c.updatesSent},
        {"updates_skipped", c.updatesSkipped},
        {"updates_unchanged", c.updatesUnchanged}};
    if (peer) j["peer"] = peerJson(*peer, *link, session->built->model);
    out << j.dump(2) << "\n";
    return;
  }
  out << "scene            " << sceneName << "\nstopped by       " << stopReason << " after " << std::fixed
      << std::setprecision(1) << secondsSince(started) << " s\nframes           " << last.frame << " ("
      << last.timeS << " s simulated)\n";
  printSummary(out, "period", period);
  printSummary(out, "compute", compute);
  out << "re-syncs         " << last.resyncs << " (" << last.skippedPeriods << " periods skipped)\n";
  if (fifo) out << "SCHED_FIFO       given up " << last.fifoGivenUp << " times, the frames overrunning\n";
  if (helperCpu >= 0) out << "frame helper     on CPU " << helperCpu << "\n";
  out << "missed deadlines " << last.missedDeadlines << "\nclients          " << c.connections << " ("
      << c.violations << " closed for protocol violations, " << c.refused << " refused), " << c.requests
      << " requests\n";
  if (peer) {
    const net::PeerSessionCounts& pc = peer->counts();
    std::uint64_t dropped = pc.flooded + pc.malformed + pc.unexpected;
    for (std::size_t r = 1; r < pc.opened.size(); ++r) dropped += pc.opened[r];
    out << "peer             " << peer->self() << ", " << peer->members().size() << " members at the end; "
        << pc.datagramsOut << " datagrams (" << pc.bytesOut << " bytes) out, " << pc.datagramsIn << " ("
        << pc.bytesIn << " bytes) in, " << dropped << " of them dropped\n";
  }
}

}  // namespace voxhap::cli

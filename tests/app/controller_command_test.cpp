// `voxhap controller`, run as the real executable on the committed ball-and-socket scene,
// with clients of the front-end protocol talking to it over loopback while it runs.
// Every wait is bounded; no assertion is about how long anything took.

#include <cmath>
#include <csignal>
#include <fstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "haptics/core/error.h"
#include "net/frontend/frontend_client.h"
#include "support/child_process.h"
#include "support/cli_runner.h"
#include "support/helper_thread.h"

namespace voxhap::test {
namespace {

using namespace std::chrono_literals;
namespace pb = net::pb;

class ControllerCommand : public CliTest {
protected:
  /// Starts the controller with the ball-and-socket on a free loopback port with `extra`
  /// arguments, and waits until it listens.
  void start(std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {asset("ball-and-socket.glb"), "--move", "ball", "--voxel-size", "1mm"};
    args.insert(args.end(), extra.begin(), extra.end());
    startWithout(args);
  }
  /// The same with only `extra` arguments (no scene unless they give one). Without
  /// SCHED_FIFO unless `realtime_`: as root, two controllers of tests run side by side
  /// would spin on both cores and starve their clients.
  void startWithout(std::vector<std::string> extra) {
    std::vector<std::string> args = {"controller", "--listen", "127.0.0.1:0", "--json"};
    if (!realtime_) args.push_back("--no-realtime");
    args.insert(args.end(), extra.begin(), extra.end());
    child_ = std::make_unique<ChildProcess>(VOXHAP_EXE, args, dir_);
    const auto port = child_->waitForStderr("listening on 127.0.0.1:", 120s);
    ASSERT_TRUE(port) << child_->err();
    port_ = static_cast<std::uint16_t>(std::stoi(*port));
  }
  net::FrontendClient connect() const { return net::FrontendClient("127.0.0.1", port_, 5000ms); }
  /// Waits for the controller to exit and returns its JSON summary.
  nlohmann::json finish() {
    const auto status = child_->wait(30s);
    EXPECT_TRUE(status) << "still running\n" << child_->err();
    EXPECT_EQ(status.value_or(-2), 0) << child_->err();
    return nlohmann::json::parse(child_->out());
  }
  static pb::ClientMessage request(void (*fill)(pb::ClientMessage&)) {
    pb::ClientMessage m;
    fill(m);
    return m;
  }
  static pb::ClientMessage forceLayer(std::uint32_t value) {
    pb::ClientMessage m;
    m.mutable_set_parameters()->set_force_layer(value);
    return m;
  }
  static pb::ClientMessage subscribe(double rateHz) {
    pb::ClientMessage m;
    m.mutable_subscribe()->set_rate_hz(rateHz);
    return m;
  }

  std::unique_ptr<ChildProcess> child_;
  std::uint16_t port_ = 0;
  bool realtime_ = false;
};

TEST_F(ControllerCommand, AClientListsSubscribesChangesTheForceLayerAndShutsItDown) {
  realtime_ = true;  // SCHED_FIFO and mlockall where the system allows them
  start({"--device", "script:" + asset("scripts/ball-turn.txt")});
  net::FrontendClient client = connect();
  const pb::HelloReply hello = client.hello("test");
  EXPECT_NE(hello.scene().find("ball-and-socket"), std::string::npos);
  EXPECT_DOUBLE_EQ(hello.frame_period_s(), 1e-3);

  const pb::ServerMessage objects =
      client.request(request([](pb::ClientMessage& m) { m.mutable_list_objects(); }));
  ASSERT_TRUE(objects.has_object_list()) << objects.DebugString();
  ASSERT_EQ(objects.object_list().objects_size(), 2);
  EXPECT_EQ(objects.object_list().objects(0).name(), "ball");
  EXPECT_TRUE(objects.object_list().objects(0).moving());
  EXPECT_EQ(objects.object_list().objects(0).held_by().rfind("script:", 0), 0u);
  EXPECT_GT(objects.object_list().objects(0).points(), 0u);
  EXPECT_FALSE(objects.object_list().objects(1).moving());

  ASSERT_TRUE(client.request(subscribe(200.0)).has_done());
  std::vector<pb::FrameUpdate> updates;
  while (updates.size() < 20) {
    const auto event = client.nextEvent(5000ms);
    ASSERT_TRUE(event && event->has_frame_update());
    updates.push_back(event->frame_update());
  }
  for (std::size_t i = 1; i < updates.size(); ++i) EXPECT_GT(updates[i].frame(), updates[i - 1].frame());
  ASSERT_EQ(updates.back().objects_size(), 1);
  EXPECT_TRUE(updates.back().objects(0).has_handle());  // held by the script
  // the script turns the ball about x: its orientation leaves the identity
  const auto& q = updates.back().objects(0).pose().orientation();
  EXPECT_LT(q.w(), 0.99999) << updates.back().DebugString();

  const pb::ServerMessage set = client.request(forceLayer(3));
  ASSERT_TRUE(set.has_parameters()) << set.DebugString();
  EXPECT_EQ(set.parameters().force_layer(), 3u);
  EXPECT_GE(set.parameters().max_force_layer(), 4u);
  EXPECT_EQ(set.parameters().min_force_layer(), 3u);  // surface planes, the default: 3 (contact_params.h)
  const pb::ServerMessage refused = client.request(forceLayer(200));
  ASSERT_TRUE(refused.has_error());
  EXPECT_EQ(refused.error().field(), "force_layer");

  const pb::ServerMessage stats =
      client.request(request([](pb::ClientMessage& m) { m.mutable_get_statistics(); }));
  ASSERT_TRUE(stats.has_statistics());
  EXPECT_GT(stats.statistics().frames(), 0u);
  EXPECT_GT(stats.statistics().period_max_s(), 0.0);

  EXPECT_TRUE(client.request(request([](pb::ClientMessage& m) { m.mutable_shutdown(); })).has_done());
  const nlohmann::json summary = finish();
  EXPECT_NE(summary.at("stopped_by").get<std::string>().find("client"), std::string::npos);
  EXPECT_GT(summary.at("frames").get<std::uint64_t>(), 0u);
  EXPECT_GE(summary.at("requests").get<std::uint64_t>(), 6u);
  for (const char* key : {"p50_us", "p99_us", "p999_us", "max_us"})
    EXPECT_TRUE(summary.at("period").at(key).is_number()) << key;
  // whether SCHED_FIFO took effect or not, the summary and a line on stderr say it
  const bool fifo = summary.at("sched_fifo").get<bool>();
  EXPECT_EQ(stats.statistics().realtime(), fifo);
  EXPECT_NE(child_->err().find(fifo ? "under SCHED_FIFO" : "without SCHED_FIFO"), std::string::npos)
      << child_->err();
}

TEST_F(ControllerCommand, BadClientsAreClosedAndTheOthersGoOn) {
  start();
  net::FrontendClient good = connect();
  good.hello("good");
  ASSERT_TRUE(good.request(subscribe(100.0)).has_done());

  const std::vector<std::string> badBytes = {
      std::string("\xff\xff\xff\x7f", 4),              // announces 2 GiB
      std::string("\x03\x00\x00\x00\xff\xff\xff", 7),  // not a ClientMessage
  };
  for (const std::string& bytes : badBytes) {
    net::FrontendClient bad = connect();
    bad.hello("bad");
    bad.sendRaw(bytes);
    EXPECT_TRUE(bad.waitClosed(5000ms));
  }
  {
    net::FrontendClient oldVersion = connect();
    pb::ClientMessage hello;
    hello.mutable_hello()->set_protocol_version(0);
    EXPECT_TRUE(oldVersion.request(hello).has_error());
    EXPECT_TRUE(oldVersion.waitClosed(5000ms));
  }
  {
    net::FrontendClient vanishing = connect();  // leaves in the middle of a frame
    vanishing.hello("vanishing");
    vanishing.sendRaw(std::string("\x40\x00\x00\x00\x08\x01", 6));
  }
  {
    net::FrontendClient grabbing = connect();  // holds the ball with its handle, then vanishes
    grabbing.hello("grabbing");
    pb::ClientMessage grab;
    grab.mutable_grab()->set_object("ball");
    grab.mutable_grab()->set_device("client");
    ASSERT_TRUE(grabbing.request(grab).has_done());
  }

  // the first client is still served: updates keep coming, requests are answered
  const auto first = good.nextEvent(5000ms);
  ASSERT_TRUE(first && first->has_frame_update());
  std::uint64_t last = first->frame_update().frame();
  for (int i = 0; i < 5; ++i) {
    const auto event = good.nextEvent(5000ms);
    ASSERT_TRUE(event && event->has_frame_update());
    EXPECT_GT(event->frame_update().frame(), last);
    last = event->frame_update().frame();
  }
  const pb::ServerMessage objects =
      good.request(request([](pb::ClientMessage& m) { m.mutable_list_objects(); }));
  ASSERT_TRUE(objects.has_object_list());
  EXPECT_EQ(objects.object_list().objects(0).held_by(), "") << "the vanished client's grab is released";

  child_->signal(SIGTERM);
  const nlohmann::json summary = finish();
  EXPECT_EQ(summary.at("stopped_by"), "SIGTERM");
  EXPECT_EQ(summary.at("protocol_violations").get<int>(), 4);  // 2 bad frames, a version, a truncation
  EXPECT_EQ(summary.at("connections").get<int>(), 6);
  const std::string err = child_->err();
  for (const char* reason : {"over the limit", "not a ClientMessage", "protocol version 0", "inside a frame"})
    EXPECT_NE(err.find(reason), std::string::npos) << reason << "\n" << err;
}

TEST_F(ControllerCommand, AClientHandleTurnsTheBall) {
  start();
  net::FrontendClient client = connect();
  client.hello("mouse");
  pb::ClientMessage grab;
  grab.mutable_grab()->set_object("ball");
  grab.mutable_grab()->set_device("client");
  ASSERT_TRUE(client.request(grab).has_done());

  // turn the handle 45° about x; the ball turns in its socket after it, through the coupling
  const double half = 0.5 * 0.7853981633974483;
  pb::ClientMessage move;
  move.mutable_move_handle()->set_object("ball");
  move.mutable_move_handle()->mutable_handle()->mutable_orientation()->set_w(std::cos(half));
  move.mutable_move_handle()->mutable_handle()->mutable_orientation()->set_x(std::sin(half));
  ASSERT_TRUE(client.request(move).has_done());
  ASSERT_TRUE(client.request(subscribe(50.0)).has_done());
  double alignment = 0.0;  // |q · target|: 1 when the ball's orientation is the handle's
  for (int i = 0; i < 250 && alignment < 0.9995; ++i) {
    const auto event = client.nextEvent(5000ms);
    ASSERT_TRUE(event && event->has_frame_update());
    const auto& q = event->frame_update().objects(0).pose().orientation();
    alignment = std::abs(q.w() * std::cos(half) + q.x() * std::sin(half));
  }
  EXPECT_GT(alignment, 0.9995);  // within 3.6°

  pb::ClientMessage bad = move;
  bad.mutable_move_handle()->mutable_handle()->mutable_orientation()->set_w(2.0);
  const pb::ServerMessage refused = client.request(bad);
  ASSERT_TRUE(refused.has_error());
  EXPECT_EQ(refused.error().field(), "handle");
  pb::ClientMessage unknown;
  unknown.mutable_grab()->set_object("socket");
  unknown.mutable_grab()->set_device("client");
  const pb::ServerMessage notMoving = client.request(unknown);
  ASSERT_TRUE(notMoving.has_error());
  EXPECT_EQ(notMoving.error().field(), "object");

  child_->signal(SIGINT);
  EXPECT_EQ(finish().at("stopped_by"), "SIGINT");
}

TEST_F(ControllerCommand, ProximityOfTheSeatedBallIsSmallBelowAndFarAbove) {
  start();
  net::FrontendClient client = connect();
  client.hello("colours");
  pb::ClientMessage ask;
  ask.mutable_get_proximity()->set_object("ball");
  ask.mutable_get_proximity()->set_within_m(0.002);
  const pb::ServerMessage reply = client.request(ask);
  ASSERT_TRUE(reply.has_proximity()) << reply.DebugString();
  const pb::Proximity& p = reply.proximity();
  EXPECT_DOUBLE_EQ(p.voxel_size_m(), 0.001);
  ASSERT_GT(p.vertex_distance_m_size(), 100);
  // the ball sits in its socket: the vertices of the seated half are within a few voxels
  // of the socket, those of the top (out of the socket) farther than that or beyond the field
  int near = 0;
  int far = 0;
  for (const float d : p.vertex_distance_m()) {
    ASSERT_GE(d, 0.0f);
    if (d <= 0.003f) ++near;
    if (d > 0.005f) ++far;
  }
  EXPECT_GT(near, p.vertex_distance_m_size() / 10);
  EXPECT_GT(far, p.vertex_distance_m_size() / 10);
  // the socket's surface voxels under the ball, within 2 mm of it
  ASSERT_GT(p.near_voxel_centre_m_size(), 0);
  EXPECT_EQ(p.near_voxel_centre_m_size() % 3, 0);

  ask.mutable_get_proximity()->set_within_m(0.0);
  EXPECT_EQ(client.request(ask).proximity().near_voxel_centre_m_size(), 0);
  ask.mutable_get_proximity()->set_within_m(1.0);
  const pb::ServerMessage tooFar = client.request(ask);
  ASSERT_TRUE(tooFar.has_error());
  EXPECT_EQ(tooFar.error().field(), "within_m");
  ask.mutable_get_proximity()->set_object("socket");
  ask.mutable_get_proximity()->set_within_m(0.0);
  const pb::ServerMessage notMoving = client.request(ask);
  ASSERT_TRUE(notMoving.has_error());
  EXPECT_EQ(notMoving.error().field(), "object");

  child_->signal(SIGTERM);
  EXPECT_EQ(finish().at("stopped_by"), "SIGTERM");
}

/// The last frame update of those that arrive in the next `forMs`; when none has come by
/// then, the first that comes within 10 s more (a loaded machine may stall the controller).
pb::FrameUpdate lastUpdateWithin(net::FrontendClient& client, std::chrono::milliseconds forMs) {
  using Clock = std::chrono::steady_clock;
  std::optional<pb::FrameUpdate> last;
  const auto until = Clock::now() + forMs;
  const auto giveUp = until + 10s;
  for (auto now = Clock::now(); now < (last ? until : giveUp); now = Clock::now()) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>((last ? until : giveUp) - now);
    const auto event = client.nextEvent(left + 1ms);
    if (!event) break;
    if (event->has_frame_update()) last = event->frame_update();
  }
  if (!last) {
    ADD_FAILURE() << "no frame update in " << (forMs + 10s).count() << " ms";
    return {};
  }
  return *last;
}

/// The first frame update at least `simulatedS` of simulated time after the first one that
/// arrives: the ball settles in simulated time, and a controller under a sanitizer on a
/// loaded machine simulates far slower than the wall clock (it re-syncs, never catches up).
pb::FrameUpdate updateAfterSimulated(net::FrontendClient& client, double simulatedS) {
  const auto giveUp = std::chrono::steady_clock::now() + 60s;
  std::optional<double> startS;
  while (std::chrono::steady_clock::now() < giveUp) {
    const auto event = client.nextEvent(1000ms);
    if (!event || !event->has_frame_update()) continue;
    const pb::FrameUpdate& update = event->frame_update();
    if (!startS) startS = update.time_s();
    if (update.time_s() >= *startS + simulatedS) return update;
  }
  ADD_FAILURE() << "no frame update " << simulatedS << " s of simulated time on within 60 s";
  return {};
}

/// The contact force on the ball once it has settled against a handle pressed 1 mm into
/// its socket, over the coupling's linear stiffness times the handle's lead: 1 when the
/// coupling alone balances the contacts.
double settledForceOverSpring(net::FrontendClient& client, double stiffnessNPerM) {
  const pb::ObjectState ball = updateAfterSimulated(client, 0.7).objects(0);
  const double leadM = std::abs(ball.handle().position_m().z() - ball.pose().position_m().z());
  const double forceN = std::hypot(ball.force_n().x(), ball.force_n().y(), ball.force_n().z());
  EXPECT_GT(leadM, 0.0005);  // the ball does not follow the handle into the socket
  return forceN / (stiffnessNPerM * leadM);
}

TEST_F(ControllerCommand, ASofterCouplingPressesLessAndARebuildKeepsTheBallWhereItIs) {
  start();
  net::FrontendClient client = connect();
  client.hello("parameters");
  pb::ClientMessage grab;
  grab.mutable_grab()->set_object("ball");
  grab.mutable_grab()->set_device("client");
  ASSERT_TRUE(client.request(grab).has_done());
  // press the handle 1 mm down into the socket, turned 30° about z (the ball turns freely in it)
  const double half = 0.5 * 0.5235987755982988;
  pb::ClientMessage move;
  move.mutable_move_handle()->set_object("ball");
  move.mutable_move_handle()->mutable_handle()->mutable_position_m()->set_z(-0.001);
  move.mutable_move_handle()->mutable_handle()->mutable_orientation()->set_w(std::cos(half));
  move.mutable_move_handle()->mutable_handle()->mutable_orientation()->set_z(std::sin(half));
  ASSERT_TRUE(client.request(move).has_done());
  ASSERT_TRUE(client.request(subscribe(100.0)).has_done());

  pb::ClientMessage ask;
  ask.mutable_set_parameters();
  const pb::ServerMessage defaults = client.request(ask);
  ASSERT_TRUE(defaults.has_parameters()) << defaults.DebugString();
  EXPECT_EQ(defaults.parameters().coupling_stiffness_share(), 1.0);
  EXPECT_DOUBLE_EQ(defaults.parameters().voxel_size_m(), 0.001);
  ASSERT_EQ(defaults.parameters().coupling_size(), 1);
  const double stiffNPerM = defaults.parameters().coupling(0).linear_stiffness_n_per_m();
  ASSERT_GT(stiffNPerM, 0.0);
  const double stiffRatio = settledForceOverSpring(client, stiffNPerM);
  EXPECT_NEAR(stiffRatio, 1.0, 0.2);

  pb::ClientMessage soften;
  soften.mutable_set_parameters()->set_coupling_stiffness_share(0.25);
  soften.mutable_set_parameters()->set_coupling_damping_ratio(1.5);
  soften.mutable_set_parameters()->set_force_layer(3);
  const pb::ServerMessage softer = client.request(soften);
  ASSERT_TRUE(softer.has_parameters()) << softer.DebugString();
  const pb::CouplingGains& gains = softer.parameters().coupling(0);
  EXPECT_DOUBLE_EQ(gains.linear_stiffness_n_per_m(), 0.25 * stiffNPerM);
  // the spring four times softer, and the ball pressing with it: a quarter of the force at the same lead
  EXPECT_NEAR(settledForceOverSpring(client, gains.linear_stiffness_n_per_m()), 1.0, 0.2);

  for (const auto& [field, set] : std::vector<std::pair<std::string, void (*)(pb::SetParameters&)>>{
           {"coupling_stiffness_share", [](pb::SetParameters& p) { p.set_coupling_stiffness_share(0.0); }},
           {"coupling_stiffness_share", [](pb::SetParameters& p) { p.set_coupling_stiffness_share(1.5); }},
           {"coupling_damping_ratio", [](pb::SetParameters& p) { p.set_coupling_damping_ratio(3.0); }},
           {"voxel_size_m", [](pb::SetParameters& p) { p.set_voxel_size_m(-0.001); }},
           {"point_spacing_m", [](pb::SetParameters& p) { p.set_point_spacing_m(2.0); }},
           {"point_offset_m", [](pb::SetParameters& p) { p.set_point_offset_m(std::nan("")); }},
       }) {
    pb::ClientMessage bad;
    set(*bad.mutable_set_parameters());
    bad.mutable_set_parameters()->set_force_layer(4);  // refused with the rest: nothing changes
    const pb::ServerMessage refused = client.request(bad);
    ASSERT_TRUE(refused.has_error()) << bad.DebugString();
    EXPECT_EQ(refused.error().field(), field);
  }
  EXPECT_EQ(client.request(ask).parameters().force_layer(), 3u);

  // a coarser voxel, and points 8 mm inward (beyond the force layer: nothing touches),
  // rebuild the model; the ball stays where it was, free. (With its points on the surface
  // the coarser voxels turn it back to where its voxels line up with the socket's.)
  const pb::ObjectState before = updateAfterSimulated(client, 0.1).objects(0);
  EXPECT_LT(before.pose().orientation().w(), 0.97);  // turned about 30° (cos 15° = 0.966)
  pb::ClientMessage coarser;
  coarser.mutable_set_parameters()->set_voxel_size_m(0.0015);
  coarser.mutable_set_parameters()->set_point_offset_m(-0.008);
  client.setTimeout(120000ms);
  const pb::ServerMessage rebuilt = client.request(coarser);
  ASSERT_TRUE(rebuilt.has_parameters()) << rebuilt.DebugString();
  EXPECT_DOUBLE_EQ(rebuilt.parameters().voxel_size_m(), 0.0015);
  EXPECT_DOUBLE_EQ(rebuilt.parameters().point_spacing_m(), 0.0015);  // it followed the voxel size
  EXPECT_DOUBLE_EQ(rebuilt.parameters().point_offset_m(), -0.008);
  EXPECT_EQ(rebuilt.parameters().coupling_stiffness_share(), 0.25);
  EXPECT_EQ(rebuilt.parameters().force_layer(), 3u);
  // the updates that came during the rebuild were kept: the last is of the new model
  const pb::FrameUpdate after = lastUpdateWithin(client, 300ms);
  ASSERT_EQ(after.objects_size(), 1);
  const pb::ObjectState& ball = after.objects(0);
  EXPECT_FALSE(ball.has_handle());  // the grab ended
  EXPECT_EQ(ball.contacts(), 0u) << after.DebugString();
  // where it was when the rebuild began: the ball may still have been closing on its handle
  // then (slowly under a sanitizer), so within 0.01 of each component, while the scene's
  // placement is 0.03 (w) and 0.26 (z) away
  EXPECT_NEAR(ball.pose().position_m().z(), before.pose().position_m().z(), 1e-4) << after.DebugString();
  EXPECT_NEAR(ball.pose().orientation().w(), before.pose().orientation().w(), 0.01) << after.DebugString();
  EXPECT_NEAR(ball.pose().orientation().z(), before.pose().orientation().z(), 0.01) << after.DebugString();
  EXPECT_LT(ball.pose().orientation().w(), 0.97);  // still turned 30° (cos 15° = 0.966)
  const pb::ServerMessage objects =
      client.request(request([](pb::ClientMessage& m) { m.mutable_list_objects(); }));
  EXPECT_EQ(objects.object_list().objects(0).held_by(), "");

  child_->signal(SIGTERM);
  EXPECT_EQ(finish().at("stopped_by"), "SIGTERM");
}

TEST_F(ControllerCommand, ASimulatedHandIsHeldBackByTheForceItFeels) {
  start();
  {
    std::ofstream script(dir_ / "press.txt");
    script << "# the hand 5 mm down into the socket, from the start\n0 1 0 0 0 0 0 -0.005\n10 1 0 0 0 0 0 "
              "-0.005\n";
  }
  net::FrontendClient client = connect();
  client.hello("hand");
  for (const char* device : {"script:", "hand:"}) {
    pb::ClientMessage grab;
    grab.mutable_grab()->set_object("ball");
    grab.mutable_grab()->set_device(device + (dir_ / "press.txt").string());
    ASSERT_TRUE(client.request(grab).has_done());
    ASSERT_TRUE(client.request(subscribe(100.0)).has_done());
    const pb::ObjectState ball = updateAfterSimulated(client, 0.7).objects(0);
    client.request(subscribe(0.0));
    const double handleZ = ball.handle().position_m().z();
    if (std::string(device) == "script:") {
      EXPECT_DOUBLE_EQ(handleZ, -0.005);  // a rigid handle goes where the script says
    } else {
      // the contact's force pushes the handle back against the hand's 500 N/m: it stops
      // near the ball, which the socket holds within a voxel
      EXPECT_GT(handleZ, -0.001) << ball.DebugString();
      EXPECT_GT(std::abs(ball.force_n().z()), 0.1);
    }
  }
  child_->signal(SIGTERM);
  EXPECT_EQ(finish().at("stopped_by"), "SIGTERM");
}

TEST_F(ControllerCommand, AClientLoadsASceneWithProgressAndThenSimulatesIt) {
  startWithout({});
  net::FrontendClient client = connect();
  EXPECT_EQ(client.hello("loader").scene(), "");
  const pb::ServerMessage none =
      client.request(request([](pb::ClientMessage& m) { m.mutable_list_objects(); }));
  ASSERT_TRUE(none.has_object_list());
  EXPECT_EQ(none.object_list().objects_size(), 0);
  pb::ClientMessage grab;
  grab.mutable_grab()->set_object("ball");
  grab.mutable_grab()->set_device("client");
  EXPECT_NE(client.request(grab).error().message().find("no scene"), std::string::npos);

  pb::ClientMessage missing;
  missing.mutable_load_scene()->set_scene((dir_ / "nowhere.glb").string());
  missing.mutable_load_scene()->add_move("ball");
  const pb::ServerMessage notFound = client.request(missing);
  ASSERT_TRUE(notFound.has_error());
  EXPECT_EQ(notFound.error().field(), "scene");
  pb::ClientMessage nothingMoves;
  nothingMoves.mutable_load_scene()->set_scene(asset("ball-and-socket.glb"));
  EXPECT_EQ(client.request(nothingMoves).error().field(), "move");

  pb::ClientMessage load;
  load.mutable_load_scene()->set_scene(asset("ball-and-socket.glb"));
  load.mutable_load_scene()->add_move("ball");
  load.mutable_load_scene()->set_voxel_size_m(0.001);
  client.setTimeout(120000ms);
  const pb::ServerMessage loaded = client.request(load);
  ASSERT_TRUE(loaded.has_object_list()) << loaded.DebugString();
  EXPECT_EQ(loaded.object_list().objects(0).name(), "ball");
  double lastFraction = -1.0;
  int progressEvents = 0;
  while (const auto event = client.nextEvent(0ms)) {
    ASSERT_TRUE(event->has_load_progress());
    EXPECT_EQ(event->load_progress().request_id(), 6u);  // after hello, list, grab and two failed loads
    EXPECT_GE(event->load_progress().fraction(), lastFraction);
    lastFraction = event->load_progress().fraction();
    ++progressEvents;
  }
  EXPECT_GT(progressEvents, 0);
  EXPECT_EQ(lastFraction, 1.0);

  EXPECT_TRUE(client.request(grab).has_done());
  ASSERT_TRUE(client.request(subscribe(100.0)).has_done());
  const auto update = client.nextEvent(5000ms);
  ASSERT_TRUE(update && update->has_frame_update());
  EXPECT_EQ(update->frame_update().objects_size(), 1);
  child_->signal(SIGTERM);
  EXPECT_GT(finish().at("frames").get<std::uint64_t>(), 0u);
}

// --frame-helper: the controller says on which CPU its helper runs, on stderr and in its
// summary, and turns the ball as without
TEST_F(ControllerCommand, AFrameHelperIsNamedInTheSummary) {
  if (const char* why = noSpareCore()) GTEST_SKIP() << why;
  start({"--device", "script:" + asset("scripts/ball-turn.txt"), "--frame-helper", "--duration", "1"});
  const nlohmann::json summary = finish();
  EXPECT_GT(summary.at("frames").get<std::uint64_t>(), 0u);
  ASSERT_TRUE(summary.at("frame_helper_cpu").is_number()) << summary.dump();
  const int cpu = summary.at("frame_helper_cpu").get<int>();
  EXPECT_GE(cpu, 0);
  EXPECT_NE(child_->err().find("a frame helper on CPU " + std::to_string(cpu)), std::string::npos)
      << child_->err();
}

TEST_F(ControllerCommand, BeyondLoopbackItWantsAToken) {
  const CliRun r =
      voxhap({"controller", asset("ball-and-socket.glb"), "--move", "ball", "--listen", "0.0.0.0:0"});
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("--token"), std::string::npos) << r.err;
}

TEST_F(ControllerCommand, AClientWithoutTheTokenIsRefused) {
  const std::string tokenFile = (dir_ / "token").string();
  std::ofstream(tokenFile) << "correct horse battery staple\n";
  start({"--token", tokenFile});
  net::FrontendClient without = connect();
  EXPECT_THROW(without.hello("without"), Error);
  net::FrontendClient with = connect();
  EXPECT_NO_THROW(with.hello("with", "correct horse battery staple"));
  child_->signal(SIGTERM);
  finish();
}

}  // namespace
}  // namespace voxhap::test

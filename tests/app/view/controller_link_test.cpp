// The front end's link against a controller running in this process, over loopback: the
// state fills in by itself, requests queued from the test thread (standing in for the
// window) reach the controller, and a load shows its progress. Waits are bounded.

#include "app/view/controller_link.h"

#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "app/controller/inprocess_controller.h"
#include "app/sim_options.h"
#include "support/cli_runner.h"

namespace voxhap::view {
namespace {

using namespace std::chrono_literals;

class ControllerLinkTest : public test::CliTest {
protected:
  /// A controller in this process on the ball-and-socket at 1 mm (or none), no SCHED_FIFO.
  std::unique_ptr<cli::InProcessController> startController(bool withScene) {
    cli::ControllerOptions options;
    if (withScene) {
      options.scene = asset("ball-and-socket.glb");
      options.moving = {"ball"};
    }
    cli::SimOptions sim;
    sim.cacheDir = (dir_ / "cache").string();
    options.model = cli::sceneModelOptions(sim, console_, 1e-3, std::nullopt);
    options.realtime = false;
    return std::make_unique<cli::InProcessController>(options, console_);
  }
  /// The link's state once `done` holds for it, or the last one after 60 s.
  template <class Done>
  static LinkState waitFor(const ControllerLink& link, Done done) {
    const auto giveUp = std::chrono::steady_clock::now() + 60s;
    LinkState s = link.state();
    while (!done(s) && std::chrono::steady_clock::now() < giveUp) {
      std::this_thread::sleep_for(5ms);
      s = link.state();
    }
    return s;
  }
  static LinkOptions to(const cli::InProcessController& controller) {
    LinkOptions options;
    options.port = controller.port();
    return options;
  }

  std::ostringstream log_;
  cli::Console console_{log_, false};
};

TEST_F(ControllerLinkTest, TheStateFillsInAndQueuedRequestsReachTheController) {
  const auto controller = startController(true);
  ControllerLink link(to(*controller));
  const LinkState ready = waitFor(link, [](const LinkState& s) {
    return s.connected && !s.objects.empty() && s.frame && s.parameters && s.statistics &&
           !s.proximity.empty() && s.proximity[0];
  });
  ASSERT_TRUE(ready.connected) << ready.error;
  EXPECT_NE(ready.hello.scene().find("ball-and-socket"), std::string::npos);
  ASSERT_EQ(ready.objects.size(), 2u);
  EXPECT_EQ(ready.objects[0].name(), "ball");
  ASSERT_TRUE(ready.parameters);
  EXPECT_DOUBLE_EQ(ready.parameters->voxel_size_m(), 0.001);
  ASSERT_TRUE(ready.proximity[0]);  // the seated ball's vertices, near the socket
  EXPECT_GT(ready.proximity[0]->vertex_distance_m_size(), 100);
  EXPECT_GT(ready.proximity[0]->near_voxel_centre_m_size(), 0);

  link.grab("ball");
  const LinkState held = waitFor(link, [](const LinkState& s) { return s.objects[0].held_by() == "client"; });
  EXPECT_EQ(held.objects[0].held_by(), "client");
  Pose turned;
  turned.orientation = glm::angleAxis(0.3, glm::dvec3(1.0, 0.0, 0.0));
  link.moveHandle("ball", turned);
  const LinkState moved = waitFor(link, [&](const LinkState& s) {
    return s.frame && s.frame->objects(0).has_handle() &&
           std::abs(s.frame->objects(0).handle().orientation().x() - turned.orientation.x) < 1e-12;
  });
  ASSERT_TRUE(moved.frame && moved.frame->objects(0).has_handle());
  EXPECT_NEAR(moved.frame->objects(0).handle().orientation().x(), turned.orientation.x, 1e-12);

  pb::SetParameters layer;
  layer.set_force_layer(3);
  link.setParameters(layer);
  EXPECT_EQ(waitFor(link, [](const LinkState& s) { return s.parameters->force_layer() == 3; })
                .parameters->force_layer(),
            3u);
  pb::SetParameters bad;
  bad.set_force_layer(0);
  link.setParameters(bad);
  EXPECT_NE(waitFor(link, [](const LinkState& s) { return !s.error.empty(); }).error.find("force_layer"),
            std::string::npos);

  link.release("ball");
  EXPECT_EQ(
      waitFor(link, [](const LinkState& s) { return s.objects[0].held_by().empty(); }).objects[0].held_by(),
      "");
  link.shutdown();
  const LinkState closed = waitFor(link, [](const LinkState& s) { return !s.connected; });
  EXPECT_FALSE(closed.connected);
  EXPECT_FALSE(closed.error.empty());
}

TEST_F(ControllerLinkTest, ALoadShowsItsProgressAndThenTheNewScene) {
  const auto controller = startController(false);
  ControllerLink link(to(*controller));
  ASSERT_TRUE(waitFor(link, [](const LinkState& s) { return s.connected; }).connected);
  link.loadScene(asset("ball-and-socket.glb"), {"ball"});
  bool sawLoading = false;
  const LinkState loaded = waitFor(link, [&](const LinkState& s) {
    sawLoading = sawLoading || s.loading.has_value();
    return !s.objects.empty() && s.parameters && s.frame;
  });
  EXPECT_TRUE(sawLoading);
  EXPECT_FALSE(loaded.loading);
  ASSERT_EQ(loaded.objects.size(), 2u);
  EXPECT_EQ(loaded.proximity.size(), 1u);
  EXPECT_DOUBLE_EQ(loaded.parameters->voxel_size_m(), 0.001);
}

TEST_F(ControllerLinkTest, NoControllerIsAnErrorInTheState) {
  LinkOptions options;
  options.port = 1;  // nothing listens there
  options.connectTimeout = 2000ms;
  ControllerLink link(options);
  const LinkState s = waitFor(link, [](const LinkState& s) { return !s.error.empty(); });
  EXPECT_FALSE(s.connected);
  EXPECT_NE(s.error.find("cannot connect"), std::string::npos) << s.error;
}

}  // namespace
}  // namespace voxhap::view

// `voxhap view` as the real executable: its usage errors, and headless screenshots under
// a virtual X server (xvfb-run) of the peg-in-hole and of a box over a plate, checked for
// what the scene must show.
// Every wait is bounded; no assertion is about how long anything took.

#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "haptics/geometry/mesh_builder.h"
#include "haptics/scene/gltf_writer.h"
#include "render/orbit_camera.h"
#include "support/child_process.h"
#include "support/cli_runner.h"
#include "support/contact_scenes.h"
#include "support/png_decode.h"
#include "support/sanitizers.h"

namespace voxhap::test {
namespace {

using namespace std::chrono_literals;

class ViewCommand : public CliTest {
protected:
  /// Keeps the test's screenshots in $VOXHAP_RENDER_TEST_PNG_DIR (as the render tests do),
  /// named after the test, before its folder goes.
  void TearDown() override {
    const char* keep = std::getenv("VOXHAP_RENDER_TEST_PNG_DIR");
    if (keep && *keep && std::filesystem::exists(dir_)) {
      const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
      for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
        if (entry.path().extension() != ".png") continue;
        std::filesystem::copy_file(
            entry.path(), std::filesystem::path(keep) / (test + "_" + entry.path().filename().string()),
            std::filesystem::copy_options::overwrite_existing);
      }
    }
    CliTest::TearDown();
  }
  /// `voxhap ARGS` (a command with a window) under `xvfb-run -a`; its JSON summary (exit
  /// status checked).
  nlohmann::json underXvfb(const std::vector<std::string>& args) {
    windowChildrenWithoutLeakCheck();
    std::vector<std::string> all = {"-a", VOXHAP_EXE};
    all.insert(all.end(), args.begin(), args.end());
    ChildProcess view("/usr/bin/xvfb-run", all, dir_);
    const auto status = view.wait(300s);
    EXPECT_EQ(status.value_or(-2), 0) << view.err();
    return status == 0 ? nlohmann::json::parse(view.out()) : nlohmann::json::object();
  }
  static bool haveXvfb() { return std::filesystem::exists("/usr/bin/xvfb-run"); }
  /// A script device that holds its part where the scene puts it: the --device value.
  std::string holdScript() const {
    std::ofstream(dir_ / "hold.txt") << "0 1 0 0 0 0 0 0\n1000 1 0 0 0 0 0 0\n";
    return "script:" + (dir_ / "hold.txt").string();
  }
  /// How far a summary's object ended from its place in the scene, m.
  static double distanceFromPlaceM(const nlohmann::json& object) {
    const nlohmann::json& d = object.at("displacement_m");
    return std::hypot(d[0].get<double>(), d[1].get<double>(), d[2].get<double>());
  }
};

TEST_F(ViewCommand, UsageErrorsExitTwo) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"view"},
        {"view", "peg-in-hole", "--frames", "3"},
        {"view", "peg-in-hole", "--screenshot", "x.png", "--size", "10x10"},
        {"view", "peg-in-hole", "--token", "t"},
        {"view", "--connect", "nowhere"},
        {"view", "peg-in-hole", "--passive", "--device", "spacemouse"},
        {"view", "peg-in-hole", "--max-frame-rate", "0"},
        {"view", "peg-in-hole", "--max-frame-rate", "fast"},
        {"view", "peg-in-hole", "--capacity", "0"}}) {
    const CliRun r = voxhap(args);
    EXPECT_EQ(r.exitCode, 2) << args.back() << "\n" << r.err;
  }
  const CliRun help = voxhap({"view", "--help"});
  EXPECT_EQ(help.exitCode, 0);
  EXPECT_NE(help.out.find("--screenshot"), std::string::npos);
}

TEST_F(ViewCommand, AHeadlessScreenshotShowsTheSceneTheSameWithAndWithoutTheStaticCache) {
  if (!haveXvfb()) GTEST_SKIP() << "no /usr/bin/xvfb-run (apt-get install xvfb xauth)";
  // the peg held where the scene puts it, so that both pictures see it in the same place
  const std::vector<std::string> common = {"peg-in-hole", "--voxel-size", "1mm",      "--no-realtime",
                                           "--device",    holdScript(),   "--frames", "60",
                                           "--size",      "640x480",      "--json"};
  std::vector<std::string> cachedArgs = {"view"};
  cachedArgs.insert(cachedArgs.end(), common.begin(), common.end());
  cachedArgs.insert(cachedArgs.end(), {"--screenshot", (dir_ / "cached.png").string()});
  std::vector<std::string> fullArgs = {"view"};
  fullArgs.insert(fullArgs.end(), common.begin(), common.end());
  fullArgs.insert(fullArgs.end(), {"--screenshot", (dir_ / "full.png").string(), "--no-static-cache"});
  const nlohmann::json cached = underXvfb(cachedArgs);
  const nlohmann::json full = underXvfb(fullArgs);
  ASSERT_FALSE(cached.empty());
  ASSERT_FALSE(full.empty());
  EXPECT_EQ(cached.at("frames_cached"), 60);
  EXPECT_GE(cached.at("cache_reuses").get<int>(), 59)
      << cached.dump();  // drawn once, reused while the eye stays
  EXPECT_EQ(full.at("frames_uncached"), 60);
  EXPECT_EQ(full.at("cache_redraws"), 0);
  // the summary says where the held peg ended: held at its place, it stayed within 2 mm
  ASSERT_EQ(cached.at("objects").size(), 1u) << cached.dump();
  const nlohmann::json& peg = cached.at("objects")[0];
  EXPECT_EQ(peg.at("name"), "peg");
  EXPECT_EQ(peg.at("held_by").get<std::string>().rfind("script:", 0), 0u) << peg.dump();
  EXPECT_LT(distanceFromPlaceM(peg), 0.002) << peg.dump();

  const DecodedPng a = decodePng(dir_ / "cached.png");
  const DecodedPng b = decodePng(dir_ / "full.png");
  ASSERT_EQ(a.width, 640u);
  ASSERT_EQ(a.height, 480u);
  ASSERT_EQ(b.width, 640u);
  // the camera frames the scene: its centre shows a part, the bottom-right corner the background
  const std::array<int, 3> background = a.at(639, 479);
  EXPECT_NE(a.at(320, 300), background);
  // the two paths draw the same picture (outside the HUD, top left, whose figures differ)
  int differing = 0;
  for (std::uint32_t y = 280; y < 480; ++y) {
    for (std::uint32_t x = 0; x < 640; ++x) {
      const auto p = a.at(x, y);
      const auto q = b.at(x, y);
      for (int c = 0; c < 3; ++c) differing += std::abs(p[c] - q[c]) > 2 ? 1 : 0;
    }
  }
  // two runs of a real-time simulation: the held peg's contacts, hence its proximity
  // colours, can differ a little between them (a few hundred values); a broken cache (static
  // parts missing, moving ones not depth-tested) changes tens of thousands
  EXPECT_LT(differing, 3840) << "of " << 3 * 640 * 200 << " channel values";
}

TEST_F(ViewCommand, ABoxIsWarmNearThePlateItRestsOnAndItsOwnBlueLiftedAway) {
  if (!haveXvfb()) GTEST_SKIP() << "no /usr/bin/xvfb-run (apt-get install xvfb xauth)";
  // a blue 20 mm box held 1 mm above a plate, then lifted 20 mm; the view colours it by the
  // distances the controller measures: warmer within five voxels of the plate, its own
  // colour beyond
  Scene scene;
  scene.objects.push_back(plate());
  scene.objects.push_back(meshObject("box", ObjectRole::Dynamic, [](TriangleMesh& m) {
    appendBox(m, at(0.0, 0.0, 0.011), glm::dvec3(0.01));  // z from 1 to 21 mm
  }));
  const glm::vec3 blue{0.1f, 0.2f, 0.9f};
  scene.objects[1].parts[0].baseColor = glm::vec4(blue, 1.0f);
  scene.objects[0].parts[0].baseColor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);  // grey: white is for contacts
  writeGlbFile(scene, dir_ / "box-on-plate.glb");
  { std::ofstream(dir_ / "lift.txt") << "0 1 0 0 0 0 0 0\n0.3 1 0 0 0 0 0 0.02\n1000 1 0 0 0 0 0 0.02\n"; }
  const auto shoot = [this](const std::string& device, const std::string& png) {
    return underXvfb({"view", (dir_ / "box-on-plate.glb").string(), "--move", "box", "--voxel-size", "1mm",
                      "--no-realtime", "--device", device, "--max-frame-rate", "60", "--frames", "120",
                      "--size", "1024x768", "--screenshot", (dir_ / png).string(), "--json"});
  };
  const nlohmann::json resting = shoot(holdScript(), "resting.png");
  const nlohmann::json lifted = shoot("script:" + (dir_ / "lift.txt").string(), "lifted.png");
  ASSERT_FALSE(resting.empty());
  ASSERT_FALSE(lifted.empty());
  EXPECT_NEAR(lifted.at("objects")[0].at("displacement_m")[2].get<double>(), 0.02, 0.002) << lifted.dump();

  // the view's eye: the scene framed for the window, as the view opens it
  render::OrbitCamera eye;
  eye.frame(scene.bounds(), 1024.0 / 768.0);
  // a point on the box's face towards the eye, 2 mm above its bottom edge
  const glm::dvec3 towardsEye = -eye.forwardWorld();
  const glm::dvec3 face = std::abs(towardsEye.x) > std::abs(towardsEye.y)
                              ? glm::dvec3(std::copysign(0.01, towardsEye.x), 0.0, 0.0)
                              : glm::dvec3(0.0, std::copysign(0.01, towardsEye.y), 0.0);
  const auto hueAt = [&eye](const DecodedPng& png, const glm::dvec3& pointWorld) {
    const glm::dvec2 px = eye.project(pointWorld, {1024, 768}).pixelPx;
    EXPECT_GT(px.y, 270.0) << "under the HUD, whose controls end about 260 px down";
    const std::array<int, 3> p = png.at(static_cast<std::uint32_t>(px.x), static_cast<std::uint32_t>(px.y));
    return glm::normalize(glm::vec3(p[0], p[1], p[2]) + 1e-3f);
  };
  const glm::vec3 red{1.0f, 0.0f, 0.0f};
  const glm::vec3 restingHue = hueAt(decodePng(dir_ / "resting.png"), face + glm::dvec3(0.0, 0.0, 0.003));
  const glm::vec3 liftedHue = hueAt(decodePng(dir_ / "lifted.png"), face + glm::dvec3(0.0, 0.0, 0.023));
  EXPECT_GT(glm::dot(restingHue, red), glm::dot(restingHue, glm::normalize(blue)))
      << restingHue.x << " " << restingHue.y << " " << restingHue.z;
  EXPECT_GT(glm::dot(liftedHue, glm::normalize(blue)), glm::dot(liftedHue, red))
      << liftedHue.x << " " << liftedHue.y << " " << liftedHue.z;

  // the contact points the controller sends, drawn white (unlit) at the box's foot: resting only
  const auto whitePixelsUnderTheHud = [](const DecodedPng& png) {
    int count = 0;
    for (std::uint32_t y = 300; y < png.height; ++y) {
      for (std::uint32_t x = 0; x < png.width; ++x) {
        const std::array<int, 3> p = png.at(x, y);
        count += std::min({p[0], p[1], p[2]}) >= 250 ? 1 : 0;
      }
    }
    return count;
  };
  EXPECT_GT(whitePixelsUnderTheHud(decodePng(dir_ / "resting.png")), 0);
  EXPECT_EQ(whitePixelsUnderTheHud(decodePng(dir_ / "lifted.png")), 0);
}

TEST_F(ViewCommand, APassiveViewConnectsToARunningControllerAndShowsItsScene) {
  if (!haveXvfb()) GTEST_SKIP() << "no /usr/bin/xvfb-run (apt-get install xvfb xauth)";
  // a `voxhap controller` process of its own (not the view's in-process one), the view its
  // front end over loopback, loading its own copy of the scene the controller names
  ChildProcess controller(VOXHAP_EXE,
                          {"controller", "peg-in-hole", "--move", "peg", "--voxel-size", "1mm", "--listen",
                           "127.0.0.1:0", "--no-realtime", "--json"},
                          dir_, "controller");
  const auto port = controller.waitForStderr("listening on 127.0.0.1:", 120s);
  ASSERT_TRUE(port) << controller.err();
  const nlohmann::json view =
      underXvfb({"view", "--connect", "127.0.0.1:" + *port, "--passive", "--frames", "30", "--size",
                 "640x480", "--screenshot", (dir_ / "connected.png").string(), "--json"});
  ASSERT_FALSE(view.empty());
  EXPECT_EQ(view.at("frames_cached"), 30) << view.dump();
  ASSERT_EQ(view.at("objects").size(), 1u) << view.dump();
  const nlohmann::json& peg = view.at("objects")[0];
  EXPECT_EQ(peg.at("name"), "peg");
  EXPECT_EQ(peg.at("held_by"), "") << peg.dump();  // a passive view grabs nothing
  EXPECT_LT(distanceFromPlaceM(peg), 0.002) << peg.dump();
  const DecodedPng png = decodePng(dir_ / "connected.png");
  ASSERT_EQ(png.width, 640u);
  EXPECT_NE(png.at(320, 300), png.at(639, 479));  // a part at the centre, background in the corner

  controller.signal(SIGINT);
  EXPECT_EQ(controller.wait(30s).value_or(-2), 0) << controller.err();
}

TEST_F(ViewCommand, APeerWithAWindowEndsWithItsDurationAndSummarisesBoth) {
  if (!haveXvfb()) GTEST_SKIP() << "no /usr/bin/xvfb-run (apt-get install xvfb xauth)";
  // the controller stops on --duration and closes the window's connection: the window
  // closes as its user had closed it, and the peer leaves and says what both saw (a
  // sanitizer's build takes longer to show the scene)
  const nlohmann::json summary =
      underXvfb({"peer", "peg-in-hole", "--voxel-size", "1mm", "--take", "peg", "--device", holdScript(),
                 "--duration", kAddressSanitizer ? "20" : "3", "--no-realtime", "--json"});
  ASSERT_FALSE(summary.empty());
  EXPECT_EQ(summary.at("stopped_by"), "the duration ran out");
  EXPECT_GT(summary.at("frames").get<std::uint64_t>(), 0u);
  EXPECT_TRUE(summary.at("peer").at("members").empty());
  const nlohmann::json& view = summary.at("view");
  EXPECT_GT(view.at("frames_cached").get<int>() + view.at("frames_uncached").get<int>(), 0) << view.dump();
  EXPECT_FALSE(view.at("scene_shown_s").is_null()) << view.dump();
}

}  // namespace
}  // namespace voxhap::test

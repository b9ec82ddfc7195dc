// `voxhap view` driven with the real mouse: the executable's window under a virtual X
// server (xvfb-run), the pointer and buttons moved by xdotool through the X server's XTEST
// extension, as a user's hand would. The test finds where to click the way the view does
// (the same camera framing and Embree picking), orbits the eye to a side view with the
// right button, drags the part with the left and reads where the view's summary says it
// ended. Every wait is bounded; no assertion is about how long anything took.

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/scene_source.h"
#include "app/view/scene_picker.h"
#include "render/orbit_camera.h"
#include "support/child_process.h"
#include "support/cli_runner.h"
#include "support/sanitizers.h"

namespace voxhap::test {
namespace {

using namespace std::chrono_literals;

/// The window's size in the tests, px (the view frames the scene for its aspect).
const glm::ivec2 kWindowPx{1024, 768};
/// The HUD's corner (top left) is left alone: a click there is the HUD's.
const glm::dvec2 kHudCornerPx{420.0, 420.0};
/// Longest stroke of a drag, px: the pointer stays in the window, as a user's does.
constexpr double kStrokePx = 200.0;
/// A stroke moves the pointer this far between two events, px.
constexpr double kStepPx = 4.0;
/// The view's zoom per wheel notch (app/view/view_run.cpp).
constexpr double kZoomPerNotch = 0.9;
/// The seconds a script leaves the view between two mouse events, so that each lands in a
/// frame of its own (llvmpipe draws the landing gear at tens of frames a second).
constexpr double kEventGapS = 0.15;

/// A bash script run under one virtual X server: it starts the view, waits for its window
/// to say that the scene shows, then sends the mouse events added to it and Escape. It
/// keeps the view's eye as those events turn it (the same OrbitCamera calls as the view's).
class MouseScript {
public:
  MouseScript(const std::vector<std::string>& viewArgs, const Scene& scene) {
    eye_.frame(scene.bounds(), static_cast<double>(kWindowPx.x) / kWindowPx.y);
    s_ << "set -eu\n" << VOXHAP_EXE << " view";
    for (const std::string& a : viewArgs) s_ << " '" << a << "'";
    s_ << " > summary.json 2> view.err &\nview=$!\ntrap 'kill \"$view\" 2> /dev/null || true' EXIT\n"
       << "w=$(timeout 600 xdotool search --sync --name '^Voxhap — [^(]*$' | head -n 1)\n"  // no "(loading…)"
       << "xdotool windowfocus --sync \"$w\"\n";
  }
  /// The pointer to a window pixel, no button held.
  void moveTo(glm::dvec2 px) { event("mousemove --window \"$w\" " + xy(px)); }
  /// Holds `button` (1 left, 2 middle, 3 right) and the key `modifier` (none when empty),
  /// moves the pointer by `deltaPx` in `steps` even steps and lets go.
  void drag(int button, glm::dvec2 deltaPx, int steps, const std::string& modifier = "") {
    if (!modifier.empty()) event("keydown " + modifier);
    event("mousedown " + std::to_string(button));
    glm::dvec2 sent{0.0};
    for (int i = 1; i <= steps; ++i) {
      const glm::dvec2 to = glm::round(deltaPx * (static_cast<double>(i) / steps));
      event("mousemove_relative -- " + xy(to - sent));
      sent = to;
    }
    event("mouseup " + std::to_string(button));
    if (!modifier.empty()) event("keyup " + modifier);
  }
  void wait(double seconds) { s_ << "sleep " << seconds << "\n"; }
  /// A right-drag from the window's lower right quarter: orbits the eye.
  void orbit(glm::dvec2 deltaPx) {
    moveTo(0.75 * glm::dvec2(kWindowPx));
    drag(3, deltaPx, 1);
    eye_.orbit(deltaPx.x, deltaPx.y);
  }
  /// A middle-drag from there: pans the eye.
  void pan(glm::dvec2 deltaPx) {
    moveTo(0.75 * glm::dvec2(kWindowPx));
    drag(2, deltaPx, 1);
    eye_.pan(deltaPx.x, deltaPx.y, kWindowPx);
  }
  /// Wheel notches at the window's centre, up (positive: nearer) or down: zooms the eye.
  void zoom(int notches) {
    moveTo(0.5 * glm::dvec2(kWindowPx));
    for (int i = 0; i < std::abs(notches); ++i) event(notches > 0 ? "click 4" : "click 5");
    eye_.zoom(std::pow(kZoomPerNotch, notches));
  }
  const render::OrbitCamera& eye() const { return eye_; }
  /// The whole script: Escape closes the view, which prints its summary.
  std::string text() { return s_.str() + "xdotool key --window \"$w\" Escape\nwait $view\n"; }

private:
  static std::string xy(glm::dvec2 px) {
    return std::to_string(std::lround(px.x)) + " " + std::to_string(std::lround(px.y));
  }
  void event(const std::string& xdotool) { s_ << "xdotool " << xdotool << "\nsleep " << kEventGapS << "\n"; }
  std::ostringstream s_;
  render::OrbitCamera eye_;
};

class ViewMouse : public CliTest {
protected:
  /// A built-in scene, as the view loads it.
  static Scene builtIn(const std::string& name) {
    std::ostringstream messages;
    cli::Console quiet(messages, false, cli::Verbosity::Quiet);
    return cli::loadScene(name, 1, quiet);
  }
  /// The index of the scene object `name`, or the object count.
  static std::size_t indexOf(const Scene& scene, const std::string& name) {
    std::size_t i = 0;
    while (i < scene.objects.size() && scene.objects[i].name != name) ++i;
    return i;
  }
  /// Where an object's vertices lie, at the scene's placement.
  static Bounds boundsOf(const SceneObject& object) {
    Bounds b;
    for (const Part& part : object.parts) {
      for (const glm::vec3& v : part.mesh.positionsWorld) b.add(glm::dvec3(v));
    }
    return b;
  }

  static bool haveTools() {
    return std::filesystem::exists("/usr/bin/xvfb-run") && std::filesystem::exists("/usr/bin/xdotool");
  }

  /// A window pixel and the point of the scene a click there meets.
  struct Grab {
    glm::dvec2 px{0.0};
    glm::dvec3 pointWorld{0.0};
  };

  /// The window pixel, off the HUD, at which a click meets scene object `object` first,
  /// nearest the middle of where it shows; none when it does not show.
  static std::optional<Grab> grabOn(const Scene& scene, std::size_t object, const render::OrbitCamera& eye) {
    const view::ScenePicker picker(scene);
    const std::vector<Pose> posesWorld(scene.objects.size());
    // every other pixel; a pixel is taken when it and its eight such neighbours meet the object
    constexpr int kGridPx = 2;
    const int columns = kWindowPx.x / kGridPx;
    const int rows = kWindowPx.y / kGridPx;
    std::vector<std::optional<glm::dvec3>> met(static_cast<std::size_t>(columns * rows));
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < columns; ++c) {
        // where the pointer is when xdotool puts it on that pixel
        const render::RayWorld ray = eye.rayThroughPixel(glm::dvec2(c, r) * double(kGridPx), kWindowPx);
        const auto hit = picker.pick(ray.originWorld, ray.directionWorld, posesWorld);
        if (hit && hit->object == object) met[static_cast<std::size_t>(r * columns + c)] = hit->pointWorld;
      }
    }
    std::vector<Grab> hits;
    for (int r = 1; r + 1 < rows; ++r) {
      for (int c = 1; c + 1 < columns; ++c) {
        const glm::dvec2 px = glm::dvec2(c, r) * double(kGridPx);
        if (px.x < kHudCornerPx.x && px.y < kHudCornerPx.y) continue;
        bool solid = true;
        for (int dr = -1; dr <= 1; ++dr) {
          for (int dc = -1; dc <= 1; ++dc)
            solid = solid && met[static_cast<std::size_t>((r + dr) * columns + c + dc)];
        }
        if (solid) hits.push_back({px, *met[static_cast<std::size_t>(r * columns + c)]});
      }
    }
    if (hits.empty()) return std::nullopt;
    glm::dvec2 meanPx{0.0};
    for (const Grab& h : hits) meanPx += h.px / static_cast<double>(hits.size());
    return *std::min_element(hits.begin(), hits.end(), [&meanPx](const Grab& a, const Grab& b) {
      return glm::distance(a.px, meanPx) < glm::distance(b.px, meanPx);
    });
  }

  /// Runs `script` under `xvfb-run -a`; the view's JSON summary (exit status checked).
  nlohmann::json run(MouseScript& script, std::chrono::seconds limit) {
    { std::ofstream(dir_ / "mouse.sh") << script.text(); }
    windowChildrenWithoutLeakCheck();
    // a screen larger than the window (xvfb-run's default, 640x480, would stop the pointer)
    ChildProcess session("/usr/bin/xvfb-run",
                         {"-a", "-s", "-screen 0 1600x1200x24", "bash", (dir_ / "mouse.sh").string()}, dir_);
    const auto status = session.wait(limit);
    EXPECT_EQ(status.value_or(-2), 0) << session.err() << "\n" << script.text();
    if (status != 0) return nlohmann::json::object();
    std::ifstream in(dir_ / "summary.json");
    return nlohmann::json::parse(in);
  }

  /// The summary's entry for `name`.
  static nlohmann::json objectOf(const nlohmann::json& summary, const std::string& name) {
    for (const nlohmann::json& o : summary.at("objects")) {
      if (o.at("name") == name) return o;
    }
    ADD_FAILURE() << name << " is not in " << summary.dump();
    return nlohmann::json::object();
  }

  /// Drags the part whose point `anchorWorld` shows at its pixel by `deltaWorld`, which lies
  /// in the view plane of the script's eye (a plain drag) or along its line of sight (a
  /// Shift-drag: down brings the part nearer), as a user whose pointer must stay in the
  /// window: in strokes of at most kStrokePx, each a click on the point where the part should
  /// then be, a drag and a pause of `settleS` for the part to follow. Returns where the point
  /// should end.
  static glm::dvec3 dragInStrokes(MouseScript& script, glm::dvec3 anchorWorld, const glm::dvec3& deltaWorld,
                                  double settleS) {
    const render::OrbitCamera& eye = script.eye();
    const double alongSightM = glm::dot(deltaWorld, eye.forwardWorld());
    // within a hundredth (the eye's angles are whole pixels of a drag)
    const bool depth = std::abs(alongSightM) > 0.01 * glm::length(deltaWorld);
    EXPECT_TRUE(!depth ||
                glm::length(deltaWorld - alongSightM * eye.forwardWorld()) < 0.01 * glm::length(deltaWorld))
        << "neither in the view plane nor along the line of sight";
    // HandleDrag's scale: a pixel moves a point at the anchor's depth this far
    const auto pixelsFor = [&eye, depth](const glm::dvec3& fromWorld, const glm::dvec3& toWorld) {
      if (!depth) return eye.project(toWorld, kWindowPx).pixelPx - eye.project(fromWorld, kWindowPx).pixelPx;
      const double depthM = glm::dot(fromWorld - eye.eyeWorld(), eye.forwardWorld());
      const double metresPerPx = 2.0 * depthM * std::tan(0.5 * render::OrbitCamera::kFovYRad) / kWindowPx.y;
      return glm::dvec2(0.0, -glm::dot(toWorld - fromWorld, eye.forwardWorld()) / metresPerPx);
    };
    const int strokes =
        std::max(1, static_cast<int>(std::ceil(glm::length(pixelsFor(anchorWorld, anchorWorld + deltaWorld)) /
                                               kStrokePx)));
    for (int k = 1; k <= strokes; ++k) {
      const glm::dvec3 fromWorld = anchorWorld + deltaWorld * (static_cast<double>(k - 1) / strokes);
      const glm::dvec3 toWorld = anchorWorld + deltaWorld * (static_cast<double>(k) / strokes);
      const glm::dvec2 strokePx = pixelsFor(fromWorld, toWorld);
      script.moveTo(eye.project(fromWorld, kWindowPx).pixelPx);
      script.drag(1, strokePx, static_cast<int>(std::ceil(glm::length(strokePx) / kStepPx)),
                  depth ? "shift" : "");
      script.wait(settleS);
    }
    return anchorWorld + deltaWorld;
  }
};

TEST_F(ViewMouse, ThePegIsPulledOutOfItsHoleByDraggingIt) {
  if (!haveTools()) GTEST_SKIP() << "no xvfb-run or xdotool (apt-get install xvfb xauth xdotool)";
  const Scene scene = builtIn("peg-in-hole");
  const std::size_t peg = indexOf(scene, "peg");
  ASSERT_LT(peg, scene.objects.size());
  const Bounds pegBounds = boundsOf(scene.objects[peg]);
  const double pegLengthM = pegBounds.max.z - pegBounds.min.z;

  MouseScript script({"peg-in-hole", "--voxel-size", "1mm", "--no-realtime", "--size",
                      std::to_string(kWindowPx.x) + "x" + std::to_string(kWindowPx.y), "--json"},
                     scene);
  // level the eye (a right-drag up lowers it to the xy plane), so that up on the screen is +z,
  // and pan the scene down a third of the window, to leave room above the peg
  script.orbit({0.0, -std::round(script.eye().pitchRad() / render::OrbitCamera::kOrbitRadPerPx)});
  ASSERT_NEAR(script.eye().upWorld().z, 1.0, 1e-3);
  script.pan({0.0, kWindowPx.y / 3.0});
  const std::optional<Grab> grab = grabOn(scene, peg, script.eye());
  ASSERT_TRUE(grab) << "the peg does not show in a side view";
  dragInStrokes(script, grab->pointWorld, {0.0, 0.0, pegLengthM + 0.01}, 1.0);  // up by its length and 10 mm
  const nlohmann::json summary = run(script, kSanitizer ? 600s : 300s);
  ASSERT_FALSE(summary.empty());
  const nlohmann::json o = objectOf(summary, "peg");
  EXPECT_EQ(o.at("held_by"), "client") << o.dump();  // the view's own grab
  ASSERT_TRUE(o.contains("displacement_m")) << o.dump();
  const nlohmann::json& d = o.at("displacement_m");
  // out of its hole: risen by more than its length, and not beside it
  EXPECT_GT(d[2].get<double>(), pegLengthM) << o.dump() << " peg length " << pegLengthM;
  EXPECT_LT(std::hypot(d[0].get<double>(), d[1].get<double>()), 0.5 * pegLengthM) << o.dump();
}

TEST_F(ViewMouse, TheActuatorIsPulledOutOfTheLandingGearByDraggingIt) {
  if (!haveTools()) GTEST_SKIP() << "no xvfb-run or xdotool (apt-get install xvfb xauth xdotool)";
  // voxelizing the landing gear takes about 2 minutes in Release; the view's code is under
  // the sanitizers in the peg's case
  if (kSanitizer) GTEST_SKIP() << "Release only";
  const Scene scene = builtIn("landing-gear");
  const std::size_t actuator = indexOf(scene, "actuator");
  ASSERT_LT(actuator, scene.objects.size());
  // the controller's haptic thread at SCHED_FIFO where the system grants it, as a user runs
  // it: without, on two cores, the window starved it (period p99 22 ms) and the actuator
  // lagged its handle by tens of centimetres
  MouseScript script(
      {"landing-gear", "--size", std::to_string(kWindowPx.x) + "x" + std::to_string(kWindowPx.y), "--json"},
      scene);
  // a level eye on the -y side, the side the actuator comes out of; the actuator panned to
  // the window's centre and the eye brought nearer
  script.orbit(
      {std::round((script.eye().yawRad() + 0.5 * std::numbers::pi) / render::OrbitCamera::kOrbitRadPerPx),
       -std::round(script.eye().pitchRad() / render::OrbitCamera::kOrbitRadPerPx)});
  ASSERT_NEAR(script.eye().forwardWorld().y, 1.0, 1e-3);
  const Bounds actuatorBounds = boundsOf(scene.objects[actuator]);
  const glm::dvec2 centrePx =
      script.eye().project(0.5 * (actuatorBounds.min + actuatorBounds.max), kWindowPx).pixelPx;
  script.pan(glm::round(0.5 * glm::dvec2(kWindowPx) - centrePx));
  script.zoom(5);
  const std::optional<Grab> grab = grabOn(scene, actuator, script.eye());
  ASSERT_TRUE(grab) << "the actuator does not show from the -y side";
  // assets/scripts/actuator-extract.txt's path, without its rocking: out of the clevis jaws
  // (-y, towards the eye), down beside the brace, out under the hydraulic lines (-y)
  glm::dvec3 at = dragInStrokes(script, grab->pointWorld, {0.0, -0.16, 0.0}, 2.0);
  at = dragInStrokes(script, at, {0.0, 0.0, -0.36}, 2.0);
  dragInStrokes(script, at, {0.0, -1.09, 0.0}, 2.0);
  const nlohmann::json summary = run(script, 900s);
  ASSERT_FALSE(summary.empty());
  const nlohmann::json o = objectOf(summary, "actuator");
  EXPECT_EQ(o.at("held_by"), "client") << o.dump();
  ASSERT_TRUE(o.contains("displacement_m")) << o.dump();
  // out: most of the way along the last leg, below the hydraulic lines (the script's end is
  // 0, -1.25, -0.36 m), where it meets nothing
  const nlohmann::json& d = o.at("displacement_m");
  EXPECT_LT(d[1].get<double>(), -1.0) << o.dump();
  EXPECT_NEAR(d[2].get<double>(), -0.36, 0.05) << o.dump();
  EXPECT_EQ(o.at("contacts"), 0) << o.dump();
}

}  // namespace
}  // namespace voxhap::test

#include "app/view/view_run.h"

#include <algorithm>
#include <chrono>
#include <future>
#include <iomanip>
#include <limits>
#include <memory>
#include <set>
#include <thread>

#include <GLFW/glfw3.h>
#include <nlohmann/json.hpp>

#include "app/controller/inprocess_controller.h"
#include "app/scene_source.h"
#include "app/view/controller_link.h"
#include "app/view/handle_drag.h"
#include "app/view/scene_picker.h"
#include "haptics/core/error.h"
#include "haptics/scene/object_selection.h"
#include "net/frontend/pose_proto.h"
#include "render/gl_context.h"
#include "render/hud.h"
#include "render/orbit_camera.h"
#include "render/scene_renderer.h"
#include "render/screenshot.h"

namespace voxhap::cli {
namespace {

namespace pb = net::pb;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

/// Longest a headless run waits for the scene to load and its first frame to arrive.
constexpr auto kHeadlessLoadLimit = 600s;
/// Proximity colours reach the parts' own colour this many static voxels away.
constexpr double kProximityRangeVoxels = 5.0;
/// A wheel notch zooms by this factor.
constexpr double kZoomPerNotch = 0.9;

/// What GLFW told us between two frames (its callbacks run inside pollEvents).
/// Motions are summed as they come, so that a drag begun and ended within one slow frame
/// still turns the eye.
struct WindowInput {
  glm::dvec2 cursorPx{0.0};  ///< window coordinates, y down
  glm::dvec2 orbitPx{0.0};   ///< cursor motion with the right button down, this frame
  glm::dvec2 panPx{0.0};     ///< with the middle button down
  bool leftDown = false;
  bool rightDown = false;
  bool middleDown = false;
  bool leftPressed = false;   ///< went down this frame
  bool leftReleased = false;  ///< went up this frame
  double scrollNotches = 0.0;
  bool frameKey = false;  ///< F
  bool cacheKey = false;  ///< C toggles the static cache
  bool closeKey = false;  ///< Esc
};

WindowInput& inputOf(GLFWwindow* window) {
  return *static_cast<WindowInput*>(glfwGetWindowUserPointer(window));
}

void installInput(GLFWwindow* window, WindowInput& input) {
  glfwSetWindowUserPointer(window, &input);
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
    WindowInput& in = inputOf(w);
    const glm::dvec2 motionPx = glm::dvec2(x, y) - in.cursorPx;
    if (in.rightDown) in.orbitPx += motionPx;
    if (in.middleDown) in.panPx += motionPx;
    in.cursorPx = {x, y};
  });
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
    WindowInput& in = inputOf(w);
    const bool down = action == GLFW_PRESS;
    if (button == GLFW_MOUSE_BUTTON_LEFT) {
      in.leftPressed = in.leftPressed || (down && !in.leftDown);
      in.leftReleased = in.leftReleased || (!down && in.leftDown);
      in.leftDown = down;
    }
    if (button == GLFW_MOUSE_BUTTON_RIGHT) in.rightDown = down;
    if (button == GLFW_MOUSE_BUTTON_MIDDLE) in.middleDown = down;
  });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) { inputOf(w).scrollNotches += dy; });
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
    WindowInput& in = inputOf(w);
    if (action != GLFW_PRESS) return;
    if (key == GLFW_KEY_F) in.frameKey = true;
    if (key == GLFW_KEY_C) in.cacheKey = true;
    if (key == GLFW_KEY_ESCAPE) in.closeKey = true;
  });
}

/// The link's state once `done` holds, or an Error with `what` after `limit`.
template <class Done>
view::LinkState waitForLink(const view::ControllerLink& link, Done done, std::chrono::seconds limit,
                            const std::string& what) {
  const auto giveUp = Clock::now() + limit;
  for (;;) {
    view::LinkState s = link.state();
    if (done(s)) return s;
    if (!s.error.empty() && !s.connected) throw Error("the controller: " + s.error);
    if (Clock::now() > giveUp) throw Error(what + " within " + std::to_string(limit.count()) + " s");
    std::this_thread::sleep_for(10ms);
  }
}

/// The window's title: the scene, and what is being done until the scene shows.
std::string windowTitle(const std::string& sceneName, bool shown,
                        const std::optional<pb::LoadProgress>& loading) {
  std::string title = "Voxhap — " + sceneName;
  if (shown) return title;
  if (!loading) return title + " (waiting for the controller)";
  return title + " (" + loading->stage() + " " +
         std::to_string(static_cast<int>(100.0 * loading->fraction())) + " %)";
}

/// Frames and their time, for the summary.
struct FrameTally {
  std::uint64_t frames = 0;
  double seconds = 0.0;
  double fps() const { return seconds > 0.0 ? static_cast<double>(frames) / seconds : 0.0; }
};

}  // namespace

void runView(const ViewOptions& options, Console& console, std::ostream& out) {
  const Clock::time_point started = Clock::now();
  std::unique_ptr<InProcessController> controller;
  view::LinkOptions linkOptions;
  linkOptions.clientName = options.passive ? "voxhap view (passive)" : "voxhap view";
  if (options.connect) {
    linkOptions.host = options.connect->host;
    linkOptions.port = options.connect->port;
    linkOptions.token = options.token;
  } else {
    ControllerOptions c;  // no scene: the window asks for it, and shows the load
    c.model = options.model;
    c.realtime = options.realtime;
    controller = std::make_unique<InProcessController>(c, console);
    linkOptions.port = controller->port();
  }
  view::ControllerLink link(linkOptions);
  const view::LinkState hello = waitForLink(
      link, [](const view::LinkState& s) { return s.connected; }, 30s, "no hello from the controller");

  // this machine's copy of the scene, for drawing and picking
  const std::string sceneName = !options.scene.empty() ? options.scene : hello.hello.scene();
  if (sceneName.empty())
    throw Error("the controller simulates no scene yet: name one (voxhap view SCENE --connect HOST:PORT)");
  const Scene scene = loadScene(sceneName, kDefaultSeed, console);
  std::vector<std::string> moving = options.moving;
  if (options.connect) {
    const view::LinkState listed = waitForLink(
        link, [](const view::LinkState& s) { return !s.objects.empty(); }, 30s, "no object list");
    moving.clear();
    for (const pb::ObjectInfo& o : listed.objects) {
      if (o.moving()) moving.push_back(o.name());
    }
  } else {
    if (moving.empty()) moving = dynamicObjectNames(scene);
    if (moving.empty())
      throw Error(scene.sourceName + " has no dynamic object: name what moves with --move NAME");
    link.loadScene(sceneName, moving);
  }
  // built while the window opens; the first click waits for it if need be
  const std::shared_future<std::shared_ptr<view::ScenePicker>> picker =
      std::async(std::launch::async, [&scene] { return std::make_shared<view::ScenePicker>(scene); }).share();
  // which moving object a scene object is (itself, or in a group that moves), or -1
  const auto movingIndexOf = [&scene, &moving](std::size_t sceneObject) {
    for (std::size_t i = 0; i < moving.size(); ++i) {
      if (scene.objects[sceneObject].name == moving[i]) return static_cast<int>(i);
      for (const SceneGroup& g : scene.groups) {
        if (g.name == moving[i] && std::count(g.objects.begin(), g.objects.end(), sceneObject) > 0)
          return static_cast<int>(i);
      }
    }
    return -1;
  };

  // each moving object's centre at the scene placement, where its force arrow starts
  std::vector<glm::dvec3> centreLocal(moving.size(), glm::dvec3(0.0));
  for (std::size_t i = 0; i < moving.size(); ++i) {
    Bounds b;
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
      if (movingIndexOf(o) != static_cast<int>(i)) continue;
      for (const Part& part : scene.objects[o].parts) {
        for (const glm::vec3& v : part.mesh.positionsWorld) b.add(glm::dvec3(v));
      }
    }
    if (!b.empty()) centreLocal[i] = 0.5 * (b.min + b.max);
  }

  render::GlContextOptions windowOptions;
  windowOptions.widthPx = options.sizePx.x;
  windowOptions.heightPx = options.sizePx.y;
  windowOptions.title = windowTitle(scene.sourceName, false, std::nullopt);
  windowOptions.visible = !options.screenshot;
  windowOptions.vsync = !options.screenshot;
  render::GlContext window(windowOptions);
  WindowInput input;
  installInput(window.window(), input);  // before the HUD, which chains to these
  render::SceneRenderer renderer(scene, moving);
  Hud hud(window.window());
  render::OrbitCamera camera;
  camera.frame(renderer.sceneBounds(), static_cast<double>(options.sizePx.x) / options.sizePx.y);
  console.note("renderer: " + window.rendererDescription());

  std::set<std::string> myGrabs;
  std::optional<view::HandleDrag> drag;
  std::string dragObject;
  view::DragMode dragMode = view::DragMode::Plane;
  Pose lastHandle;
  glm::dvec3 anchorLocal{0.0};  ///< the grabbed point, in the handle's frame
  bool useCache = options.staticCache;
  bool showForceOverlay = true;
  FrameTally cached;
  FrameTally uncached;
  std::optional<double> firstFrameS;
  std::optional<double> sceneShownS;
  std::optional<std::uint64_t> framesLeft;  // headless: counting down once the scene shows
  // the haptic rate: frames counted between statistics at least 1 s apart by this clock
  // (the first statistics only start the count: the controller may have run long before)
  std::optional<std::uint64_t> lastHapticFrames;
  Clock::time_point lastHapticAt;
  double hapticRateHz = 0.0;
  double fpsSmoothed = 0.0;
  view::LinkState state;
  bool deviceGrabbed = options.device.empty();
  Clock::time_point frameStart = Clock::now();

  while (!window.shouldClose() && !input.closeKey) {
    input.leftPressed = input.leftReleased = false;
    input.frameKey = input.cacheKey = false;
    input.scrollNotches = 0.0;
    input.orbitPx = input.panPx = glm::dvec2(0.0);
    window.pollEvents();
    state = link.state();
    if (!state.connected && !state.error.empty()) {
      if (options.endsWithController && state.closedByController) break;
      throw Error("the controller: " + state.error);
    }
    const glm::ivec2 fb = window.framebufferSizePx();
    int windowW = 0;
    int windowH = 0;
    glfwGetWindowSize(window.window(), &windowW, &windowH);
    const double pxPerScreen = windowW > 0 ? static_cast<double>(fb.x) / windowW : 1.0;
    const glm::dvec2 cursorPx = input.cursorPx * pxPerScreen;

    // the controller's moving objects, by the renderer's index
    std::vector<int> controllerIndex(moving.size(), -1);
    for (std::size_t k = 0; k < state.objects.size(); ++k) {
      const auto it = std::find(moving.begin(), moving.end(), state.objects[k].name());
      if (state.objects[k].moving() && it != moving.end())
        controllerIndex[it - moving.begin()] = static_cast<int>(k);
    }
    std::vector<Pose> movingPose(moving.size());
    const double voxelM = state.parameters ? state.parameters->voxel_size_m() : 0.0;
    renderer.setProximityRange(static_cast<float>(kProximityRangeVoxels * std::max(voxelM, 1e-4)));
    std::vector<glm::vec3> shadow;
    std::vector<glm::vec3> contactPoints;
    std::optional<render::ForceArrow> arrow;
    for (std::size_t i = 0; i < moving.size(); ++i) {
      const int k = controllerIndex[i];
      if (k < 0) continue;
      if (state.frame && k < state.frame->objects_size()) {
        const pb::ObjectState& o = state.frame->objects(k);
        movingPose[i] = net::fromProto(o.pose());
        renderer.setPose(i, movingPose[i]);
        renderer.setOtherInstance(i, net::furthestOtherInstance(o));
        const glm::dvec3 forceN(o.force_n().x(), o.force_n().y(), o.force_n().z());
        if (showForceOverlay && myGrabs.count(moving[i]) && glm::length(forceN) > 0.0)
          arrow = render::ForceArrow{apply(movingPose[i], centreLocal[i]), forceN, 0.002};
        if (showForceOverlay) net::appendPoints(o.contact_point_m(), contactPoints);
      }
      if (static_cast<std::size_t>(k) < state.proximity.size() && state.proximity[k]) {
        const pb::Proximity& p = *state.proximity[k];
        if (static_cast<std::uint32_t>(p.vertex_distance_m_size()) == renderer.movingVertexCount(i)) {
          renderer.setProximity(
              i, {p.vertex_distance_m().data(), static_cast<std::size_t>(p.vertex_distance_m_size())});
        }
        net::appendPoints(p.near_voxel_centre_m(), shadow);
      }
    }
    renderer.setShadowVoxels(shadow, static_cast<float>(voxelM));
    if (!deviceGrabbed && !state.loading && controllerIndex[0] >= 0) {
      link.grab(moving[0], options.device);
      deviceGrabbed = true;
    }
    renderer.setForceArrow(arrow);
    renderer.setContactPoints(contactPoints, static_cast<float>(voxelM));

    // the mouse: the HUD first, then a drag of a held part, else the eye
    const bool hudHasMouse = hud.wantsMouse();
    GLFWwindow* w = window.window();
    const bool shift =
        glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    const bool ctrl = glfwGetKey(w, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
                      glfwGetKey(w, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
    const view::DragMode mode = shift  ? view::DragMode::Depth
                                : ctrl ? view::DragMode::Rotate
                                       : view::DragMode::Plane;
    const view::DragView dragView{camera.viewMatrix(), render::OrbitCamera::kFovYRad,
                                  static_cast<double>(fb.y)};
    if (input.leftPressed && !hudHasMouse && !options.passive) {
      std::vector<Pose> posesWorld(scene.objects.size());
      for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        if (const int i = movingIndexOf(o); i >= 0) posesWorld[o] = movingPose[static_cast<std::size_t>(i)];
      }
      const render::RayWorld ray = camera.rayThroughPixel(cursorPx, fb);
      const std::optional<view::Pick> hit =
          picker.get()->pick(ray.originWorld, ray.directionWorld, posesWorld);
      const int i = hit ? movingIndexOf(hit->object) : -1;
      if (i >= 0 && controllerIndex[static_cast<std::size_t>(i)] >= 0) {
        const std::string& name = moving[static_cast<std::size_t>(i)];
        const pb::ObjectState* o =
            state.frame ? &state.frame->objects(controllerIndex[static_cast<std::size_t>(i)]) : nullptr;
        // a new grab starts the client's handle at the object; a held one where it was left
        lastHandle = myGrabs.count(name) && o && o->has_handle() ? net::fromProto(o->handle())
                                                                 : movingPose[static_cast<std::size_t>(i)];
        if (!myGrabs.count(name)) {
          link.grab(name);
          myGrabs.insert(name);
        }
        drag.emplace(dragView, lastHandle, hit->pointWorld, cursorPx);
        anchorLocal = glm::conjugate(lastHandle.orientation) * (hit->pointWorld - lastHandle.position);
        dragObject = name;
        dragMode = mode;
      }
    }
    if (drag && (input.leftDown || input.leftReleased)) {  // a release: the drag's last motion
      if (mode != dragMode) {  // a modifier pressed or let go: go on from where the handle is
        drag.emplace(dragView, lastHandle, apply(lastHandle, anchorLocal), cursorPx);
        dragMode = mode;
      }
      const Pose next = drag->at(cursorPx, mode);
      if (next.position != lastHandle.position || next.orientation != lastHandle.orientation) {
        link.moveHandle(dragObject, next);
      }
      lastHandle = next;
      if (!input.leftDown) drag.reset();  // a later click elsewhere must not go on with it
    }
    if (!hudHasMouse) {
      const glm::dvec2 orbitPx = input.orbitPx * pxPerScreen;
      const glm::dvec2 panPx = input.panPx * pxPerScreen;
      if (orbitPx != glm::dvec2(0.0)) camera.orbit(orbitPx.x, orbitPx.y);
      if (panPx != glm::dvec2(0.0)) camera.pan(panPx.x, panPx.y, fb);
      if (input.scrollNotches != 0.0) camera.zoom(std::pow(kZoomPerNotch, input.scrollNotches));
    }
    if (input.frameKey) camera.frame(renderer.sceneBounds(), static_cast<double>(fb.x) / std::max(1, fb.y));
    if (input.cacheKey) useCache = !useCache;

    renderer.draw(camera, fb, useCache);
    hud.newFrame();
    HudModel model;
    model.renderFps = fpsSmoothed;
    model.passive = options.passive;
    model.message = state.error;
    model.forceOverlay = showForceOverlay;
    if (state.loading) model.loading = HudLoading{state.loading->stage(), state.loading->fraction()};
    if (state.statistics) {
      const pb::Statistics& s = *state.statistics;
      const Clock::time_point now = Clock::now();
      const double dt = std::chrono::duration<double>(now - lastHapticAt).count();
      if (!lastHapticFrames || (s.frames() > *lastHapticFrames && dt >= 1.0)) {
        if (lastHapticFrames) hapticRateHz = static_cast<double>(s.frames() - *lastHapticFrames) / dt;
        lastHapticFrames = s.frames();
        lastHapticAt = now;
      }
      model.hapticFrames = s.frames();
      model.hapticRateHz = hapticRateHz;
      model.periodP50S = s.period_p50_s();
      model.periodP99S = s.period_p99_s();
      model.periodMaxS = s.period_max_s();
      model.overruns = s.overruns();
    }
    if (state.parameters) {
      const pb::Parameters& p = *state.parameters;
      model.voxelSizeM = p.voxel_size_m();
      model.forceLayer = static_cast<int>(p.force_layer());
      model.forceLayerMin = static_cast<int>(p.min_force_layer());
      model.forceLayerMax = static_cast<int>(p.max_force_layer());
      model.pointOffsetM = p.point_offset_m();
      model.pointOffsetMaxM = 2.0 * p.point_spacing_m();
      model.couplingShare = p.coupling_stiffness_share();
    }
    for (std::size_t i = 0; i < moving.size(); ++i) {
      HudObject row;
      row.name = moving[i];
      const int k = controllerIndex[i];
      if (k >= 0) {
        row.heldBy = state.objects[k].held_by();
        if (row.heldBy != "client") myGrabs.erase(moving[i]);
        row.heldByMe = myGrabs.count(moving[i]) > 0;
        if (state.frame && k < state.frame->objects_size()) {
          const pb::ObjectState& o = state.frame->objects(k);
          row.contacts = o.contacts();
          row.forceWorldN = {o.force_n().x(), o.force_n().y(), o.force_n().z()};
          row.travelShare = o.travel_share();
          row.sharers = static_cast<std::size_t>(o.sharer_peers_size());
          row.divergent = o.divergent();
        }
        if (static_cast<std::size_t>(k) < state.proximity.size() && state.proximity[k]) {
          const auto& d = state.proximity[k]->vertex_distance_m();
          const float nearest =
              d.empty() ? std::numeric_limits<float>::infinity() : *std::min_element(d.begin(), d.end());
          if (nearest > 0.0f && std::isfinite(nearest)) row.clearanceM = nearest;
        }
      }
      model.objects.push_back(std::move(row));
    }
    const HudActions actions = hud.draw(model);
    hud.render();
    window.swapBuffers();

    if (!options.passive) {
      if (actions.grabObject) {
        link.grab(moving[*actions.grabObject]);
        myGrabs.insert(moving[*actions.grabObject]);
      }
      if (actions.releaseObject) {
        link.release(moving[*actions.releaseObject]);
        myGrabs.erase(moving[*actions.releaseObject]);
      }
      pb::SetParameters set;
      if (actions.forceLayer) set.set_force_layer(static_cast<std::uint32_t>(*actions.forceLayer));
      if (actions.pointOffsetM) set.set_point_offset_m(*actions.pointOffsetM);
      if (actions.couplingShare) set.set_coupling_stiffness_share(*actions.couplingShare);
      if (set.ByteSizeLong() > 0) link.setParameters(set);
    }
    if (actions.forceOverlay) showForceOverlay = *actions.forceOverlay;
    if (actions.frameScene)
      camera.frame(renderer.sceneBounds(), static_cast<double>(fb.x) / std::max(1, fb.y));

    if (options.maxFrameRateHz > 0.0)
      std::this_thread::sleep_until(frameStart +
                                    std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(1.0 / options.maxFrameRateHz)));
    const Clock::time_point frameEnd = Clock::now();
    const double frameS = std::chrono::duration<double>(frameEnd - frameStart).count();
    frameStart = frameEnd;
    if (!firstFrameS) firstFrameS = std::chrono::duration<double>(frameEnd - started).count();
    fpsSmoothed = fpsSmoothed == 0.0 ? 1.0 / frameS : 0.9 * fpsSmoothed + 0.1 / frameS;
    // the scene is shown once its poses and, where the session has them, proximity came
    const bool proximityShown =
        state.proximityUnavailable ||
        (!state.proximity.empty() && std::all_of(state.proximity.begin(), state.proximity.end(),
                                                 [](const auto& p) { return p.has_value(); }));
    const bool shown = state.frame && !state.loading && !state.objects.empty() && proximityShown;
    if (shown && !sceneShownS) sceneShownS = std::chrono::duration<double>(frameEnd - started).count();
    // the title says when the scene shows (scripts driving the window wait for it)
    if (std::string title = windowTitle(scene.sourceName, shown, state.loading);
        title != windowOptions.title) {
      glfwSetWindowTitle(window.window(), title.c_str());
      windowOptions.title = std::move(title);
    }
    if (shown) {
      FrameTally& tally = useCache ? cached : uncached;
      ++tally.frames;
      tally.seconds += frameS;
    }
    if (options.screenshot) {
      if (shown && !framesLeft) framesLeft = static_cast<std::uint64_t>(std::max(1, options.frames));
      if (framesLeft && --*framesLeft == 0) {
        // the last frame drawn is in the back buffer no longer: draw it once more to read it
        renderer.draw(camera, fb, useCache);
        hud.newFrame();
        hud.draw(model);
        hud.render();
        render::saveScreenshot(*options.screenshot, fb);
        console.info("wrote " + *options.screenshot);
        break;
      }
      if (!shown && Clock::now() - started > kHeadlessLoadLimit)
        throw Error("the scene did not load within " + std::to_string(kHeadlessLoadLimit.count()) + " s");
    }
  }

  const render::SceneRendererStats r = renderer.stats();
  nlohmann::ordered_json j = {
      {"scene", scene.sourceName},
      {"size_px", {window.framebufferSizePx().x, window.framebufferSizePx().y}},
      {"first_frame_s", firstFrameS.value_or(0.0)},
      {"scene_shown_s", sceneShownS ? nlohmann::ordered_json(*sceneShownS) : nlohmann::ordered_json()},
      {"frames_cached", cached.frames},
      {"fps_cached", cached.fps()},
      {"frames_uncached", uncached.frames},
      {"fps_uncached", uncached.fps()},
      {"cache_redraws", r.cache.redraws},
      {"cache_reuses", r.cache.reuses},
  };
  if (state.statistics) {
    j["haptic_period_p50_us"] = state.statistics->period_p50_s() * 1e6;
    j["haptic_period_p99_us"] = state.statistics->period_p99_s() * 1e6;
    j["haptic_period_max_us"] = state.statistics->period_max_s() * 1e6;
    j["haptic_overruns"] = state.statistics->overruns();
  }
  // where each moving object ended, so that a run can tell whether a part came out
  nlohmann::ordered_json objects = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < state.objects.size(); ++k) {
    if (!state.objects[k].moving()) continue;
    nlohmann::ordered_json o = {{"name", state.objects[k].name()}, {"held_by", state.objects[k].held_by()}};
    if (state.frame && static_cast<int>(k) < state.frame->objects_size()) {
      const pb::ObjectState& f = state.frame->objects(static_cast<int>(k));
      // the displacement of its centre (a pose turns about the scene's origin, far from the part)
      const Pose pose = net::fromProto(f.pose());
      const auto it = std::find(moving.begin(), moving.end(), state.objects[k].name());
      const glm::dvec3 centre = it != moving.end() ? centreLocal[it - moving.begin()] : glm::dvec3(0.0);
      const glm::dvec3 d = apply(pose, centre) - centre;
      o["displacement_m"] = {d.x, d.y, d.z};
      o["turned_deg"] = glm::degrees(2.0 * std::acos(std::min(1.0, std::abs(pose.orientation.w))));
      o["contacts"] = f.contacts();
    }
    objects.push_back(std::move(o));
  }
  j["objects"] = std::move(objects);
  if (options.json) {
    out << j.dump(2) << "\n";
    return;
  }
  out << std::fixed << std::setprecision(1) << "scene            " << scene.sourceName
      << "\nfirst frame      " << firstFrameS.value_or(0.0) << " s; scene shown at "
      << sceneShownS.value_or(0.0) << " s\nframes           " << cached.frames << " cached at "
      << cached.fps() << " fps, " << uncached.frames << " uncached at " << uncached.fps()
      << " fps\nstatic cache     " << r.cache.redraws << " redraws, " << r.cache.reuses << " reuses\n";
  out << std::setprecision(4);
  for (const auto& o : j["objects"]) {
    out << "moved            " << o["name"].get<std::string>() << " (" << o["held_by"].get<std::string>()
        << ")";
    if (o.contains("displacement_m")) {
      const auto& d = o["displacement_m"];
      out << " by " << d[0].get<double>() << ", " << d[1].get<double>() << ", " << d[2].get<double>()
          << " m from its place, turned " << std::setprecision(1) << o["turned_deg"].get<double>() << "°, "
          << o["contacts"].get<std::uint32_t>() << " contacts" << std::setprecision(4);
    }
    out << "\n";
  }
}

}  // namespace voxhap::cli

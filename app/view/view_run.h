#pragma once
/// `voxhap view`: the front end (DESIGN §9, paper §3.1 and §7). A GLFW window shows the
/// scene through render::SceneRenderer (static parts from the FlyThru cache), the moving
/// parts where the controller says they are and coloured by proximity, and the HUD; the
/// mouse picks, grabs and drags parts (HandleDrag) and turns the eye. It talks to a
/// haptic controller over the front-end protocol only (ControllerLink): one it starts in
/// this process for `voxhap view SCENE`, or a running one for `--connect`.

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "app/cli/console.h"
#include "app/cli/endpoint_options.h"
#include "haptics/sim/scene_model.h"

namespace voxhap::cli {

struct ViewOptions {
  /// The scene: loaded by a controller started in this process, or, with `connect`, this
  /// machine's copy of what that controller simulates (empty: the path its hello names).
  std::string scene;
  std::vector<std::string> moving;  ///< objects or groups that move; empty: the scene's dynamic ones
  std::optional<HostPort> connect;  ///< a running controller instead of one in this process
  std::string token;                ///< for `connect`
  SceneModelOptions model;          ///< the in-process controller's sizes
  bool realtime = true;             ///< the in-process controller tries SCHED_FIFO
  bool passive = false;             ///< sees, cannot grab or change anything
  /// Once the scene is loaded, the first moving object is grabbed with this device (a
  /// Grab's device string: script:FILE, hand:FILE, spacemouse); empty: none.
  std::string device;
  bool staticCache = true;                ///< FlyThru: static parts drawn once while the eye is still
  std::optional<std::string> screenshot;  ///< headless: a hidden window, this PNG after `frames`
  int frames = 60;                        ///< frames drawn before the screenshot (after loading)
  glm::ivec2 sizePx{1280, 720};
  /// At most this many frames a second (0: as the display's vsync allows), to leave the
  /// processor to haptic threads on the same small machine.
  double maxFrameRateHz = 0.0;
  bool json = false;  ///< the summary as one JSON document
  /// The controller may end the run (a peer's, on its duration or a signal): the window
  /// then closes as if its user had closed it, instead of failing.
  bool endsWithController = false;
};

/// Runs the window until it is closed (or the screenshot is written), then prints a
/// summary on `out`: frames, frame rate, cache use, time to the first frame, the haptic
/// period. Throws voxhap::Error when there is no display, the scene cannot be loaded, or
/// the controller cannot be reached.
void runView(const ViewOptions& options, Console& console, std::ostream& out);

}  // namespace voxhap::cli

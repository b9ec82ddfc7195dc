#pragma once
/// The front end's heads-up display (issue 11, item 5), drawn with Dear ImGui over the
/// scene: frame and haptic rates, period overruns, per-object contacts, force, MaxTravel
/// share and clearance, the voxel size; the force layer, point offset and coupling
/// stiffness edited live; grab and release; a progress bar while a scene loads.
///
/// Immediate mode, one frame at a time, on the thread that owns the GLFW window and its
/// GL context: `newFrame()`, then `draw(model)` (which returns what the user asked for),
/// then `render()` after the scene so that the HUD lies on top. The app fills a
/// `HudModel` from its latest snapshot every frame; the HUD keeps no engine state, only
/// the value of a slider while the user drags it. An edit is reported once, when the
/// user commits it (releases the slider or presses Enter), never every frame of a drag.
///
/// Input: the GLFW backend chains the window's callbacks installed before the Hud, so
/// the app installs its own first; it asks `wantsMouse()`/`wantsKeyboard()` before it
/// orbits the camera or takes a key. One Hud per window and at a time (it owns the Dear
/// ImGui context).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

struct GLFWwindow;
struct ImGuiContext;

namespace voxhap {

/// One moving object's row in the HUD.
struct HudObject {
  std::string name;
  /// Who holds it (a peer's or device's name); empty when nobody does.
  std::string heldBy;
  /// Whether this front end holds it (then the HUD offers "release", else "grab").
  bool heldByMe = false;
  /// Points of its pointshell in contact this frame.
  std::size_t contacts = 0;
  /// Net penalty force on it, world frame, N (the HUD shows its magnitude).
  glm::dvec3 forceWorldN{0.0};
  /// MaxTravel used this frame as a share of its bound, 0 … 1.
  double travelShare = 0.0;
  /// Clearance to the nearest surface, m; none when it is not measured (or in contact).
  std::optional<double> clearanceM;
  /// The peers that share it (type-2), 0 when nobody does.
  std::size_t sharers = 0;
  /// Its sharers' instances are apart beyond the bound: what each peer shows may differ.
  bool divergent = false;
};

/// A scene being loaded or voxelized.
struct HudLoading {
  /// What is being done, e.g. "voxelizing bunny".
  std::string stage;
  /// Share done, 0 … 1.
  double fraction = 0.0;
};

/// Everything the HUD shows, plain data the app fills every frame.
struct HudModel {
  /// Graphics frames per second.
  double renderFps = 0.0;
  /// Haptic frames since the start.
  std::uint64_t hapticFrames = 0;
  /// Haptic frames per second, Hz.
  double hapticRateHz = 0.0;
  /// Haptic period percentiles and maximum, s.
  double periodP50S = 0.0;
  double periodP99S = 0.0;
  double periodMaxS = 0.0;
  /// Haptic periods over their deadline.
  std::uint64_t overruns = 0;
  /// The moving objects, in the order `HudActions::grabObject` indexes.
  std::vector<HudObject> objects;
  /// Edge of a voxel, m.
  double voxelSizeM = 0.0;
  /// Force layer in use, and the range every pair takes (up to the deepest the voxmaps hold).
  int forceLayer = 0;
  int forceLayerMin = 0;
  int forceLayerMax = 0;
  /// Offset of the pointshell points along their normals, m, and its slider's bound.
  double pointOffsetM = 0.0;
  double pointOffsetMaxM = 0.0;
  /// Coupling stiffness as a share of the stable maximum, 0 … 1.
  double couplingShare = 0.0;
  /// Set while a scene loads or voxelizes: the HUD draws a progress bar.
  std::optional<HudLoading> loading;
  /// A passive viewer: no grab, release or parameter controls.
  bool passive = false;
  /// The last error or notice; empty for none.
  std::string message;
  /// The force arrow is drawn on the parts this front end holds, and the contact points
  /// of every part.
  bool forceOverlay = true;
};

/// What the user asked for during one `Hud::draw`; each field is set at most once.
struct HudActions {
  /// Grab the object at this index of `HudModel::objects`.
  std::optional<std::size_t> grabObject;
  /// Release the object at this index.
  std::optional<std::size_t> releaseObject;
  /// Committed edits (on release of the slider or Enter).
  std::optional<int> forceLayer;
  std::optional<double> pointOffsetM;
  std::optional<double> couplingShare;
  /// "Frame the scene" pressed.
  bool frameScene = false;
  /// The force arrow and contact points ticked on or off.
  std::optional<bool> forceOverlay;

  /// Whether the user asked for anything.
  bool any() const noexcept {
    return grabObject || releaseObject || forceLayer || pointOffsetM || couplingShare || frameScene ||
           forceOverlay;
  }
};

/// A rectangle in window coordinates: pixels from the top-left corner, y down.
struct HudRectPx {
  float minX = 0.0F;
  float minY = 0.0F;
  float maxX = 0.0F;
  float maxY = 0.0F;

  float centerX() const noexcept { return 0.5F * (minX + maxX); }
  float centerY() const noexcept { return 0.5F * (minY + maxY); }
};

/// Where the last `draw` put the HUD and its controls (for tests and for the app to
/// keep its own overlays clear of it). A control not drawn is absent.
struct HudLayout {
  HudRectPx window;
  std::optional<HudRectPx> progressBar;
  /// One per object when the HUD offers grab or release (none when passive); an object
  /// held by somebody else has a disabled button.
  std::vector<HudRectPx> grabButtons;
  std::optional<HudRectPx> forceLayerSlider;
  std::optional<HudRectPx> pointOffsetSlider;
  std::optional<HudRectPx> couplingSlider;
  std::optional<HudRectPx> frameButton;
  std::optional<HudRectPx> forceOverlayCheckbox;
};

/// A pointer that replaces the one the GLFW backend reads, for one frame (tests,
/// scripted demos): window coordinates, px, and the left button.
struct HudPointer {
  float xPx = 0.0F;
  float yPx = 0.0F;
  bool leftDown = false;
};

class Hud {
public:
  /// Installs Dear ImGui's GLFW and OpenGL 3 backends (GLSL "#version 330") on `window`,
  /// whose GL 3.3 core context must be current. Throws voxhap::Error when the window is
  /// null, its context is not current, or a backend fails to start.
  explicit Hud(GLFWwindow* window);
  /// Shuts the backends down (restoring the window's earlier callbacks) and frees the
  /// ImGui context and its GL objects; the context must still be current.
  ~Hud();
  Hud(const Hud&) = delete;
  Hud& operator=(const Hud&) = delete;

  /// Starts a frame: reads the window's size, time and input (or `pointer` instead of
  /// the real mouse).
  void newFrame(std::optional<HudPointer> pointer = std::nullopt);
  /// Lays the HUD out for this frame from `model`; returns what the user asked for.
  HudActions draw(const HudModel& model);
  /// Draws the frame's HUD into the current framebuffer with OpenGL (after the scene).
  void render();

  /// Whether the pointer is over the HUD or a HUD control is held: the app should not
  /// orbit the camera with this mouse input.
  bool wantsMouse() const;
  /// Whether a HUD text field has the keyboard.
  bool wantsKeyboard() const;
  /// Where the last `draw` put things.
  const HudLayout& layout() const noexcept { return layout_; }

private:
  /// Value of a slider while the user drags or types into it.
  template <typename T>
  struct Edit {
    bool active = false;
    T value{};
  };

  /// Undoes what the constructor set up, in reverse order.
  void shutdown() noexcept;

  ImGuiContext* context_ = nullptr;
  bool glfwBackendUp_ = false;
  bool openGlBackendUp_ = false;
  bool inFrame_ = false;
  HudLayout layout_;
  Edit<int> forceLayerEdit_;
  Edit<double> pointOffsetMmEdit_;
  Edit<double> couplingEdit_;
};

}  // namespace voxhap

#include "render/hud.h"

#include <cassert>

#include <GLFW/glfw3.h>
#include <glm/geometric.hpp>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include "haptics/core/error.h"

namespace voxhap {

namespace {

/// GLSL of the OpenGL3 backend's shaders, for a GL 3.3 core context.
constexpr const char* kGlslVersion = "#version 330";
/// Gap between the window's top-left corner and the HUD, px.
constexpr float kMarginPx = 8.0F;
/// Width of the sliders and the progress bar, px.
constexpr float kControlWidthPx = 220.0F;
/// A MaxTravel share from which the HUD shows it as a warning.
constexpr double kTravelWarnShare = 0.9;
constexpr double kMmPerM = 1000.0;
constexpr double kMsPerS = 1000.0;
/// Slider bounds, passed to ImGui by address.
constexpr double kZeroMm = 0.0;
constexpr double kShareMin = 0.0;
constexpr double kShareMax = 1.0;
/// Shown for a figure that is not measured.
constexpr const char* kNone = "-";

const ImVec4 kWarnColour{1.0F, 0.6F, 0.2F, 1.0F};

HudRectPx lastItemRect() {
  const ImVec2 min = ImGui::GetItemRectMin();
  const ImVec2 max = ImGui::GetItemRectMax();
  return HudRectPx{min.x, min.y, max.x, max.y};
}

/// Runs `widget(&value)` on the slider's value (the model's, or the user's while the
/// slider is held) and returns the value once, on the frame the user commits it.
template <typename EditT, typename T, typename Widget>
std::optional<T> commitOnRelease(EditT& edit, T modelValue, Widget widget) {
  T value = edit.active ? edit.value : modelValue;
  widget(&value);
  edit.active = ImGui::IsItemActive();
  edit.value = value;
  if (ImGui::IsItemDeactivatedAfterEdit()) return value;
  return std::nullopt;
}

void drawRates(const HudModel& model) {
  ImGui::Text("render %.0f fps", model.renderFps);
  ImGui::Text("haptic %.0f Hz, %llu frames", model.hapticRateHz,
              static_cast<unsigned long long>(model.hapticFrames));
  ImGui::Text("period p50 %.3f  p99 %.3f  max %.3f ms", model.periodP50S * kMsPerS,
              model.periodP99S * kMsPerS, model.periodMaxS * kMsPerS);
  if (model.overruns > 0) {
    ImGui::TextColored(kWarnColour, "overruns %llu", static_cast<unsigned long long>(model.overruns));
  } else {
    ImGui::Text("overruns 0");
  }
  ImGui::Text("voxel %.3f mm", model.voxelSizeM * kMmPerM);
}

}  // namespace

Hud::Hud(GLFWwindow* window) {
  if (window == nullptr) throw Error("HUD: no window");
  if (glfwGetCurrentContext() != window) {
    throw Error("HUD: the window's OpenGL context is not current (glfwMakeContextCurrent first)");
  }
  IMGUI_CHECKVERSION();
  context_ = ImGui::CreateContext();
  ImGui::SetCurrentContext(context_);
  ImGuiIO& io = ImGui::GetIO();
  // no imgui.ini in the working directory: the HUD's layout is fixed
  io.IniFilename = nullptr;
  io.LogFilename = nullptr;
  ImGui::StyleColorsDark();

  glfwBackendUp_ = ImGui_ImplGlfw_InitForOpenGL(window, true);
  if (!glfwBackendUp_) {
    shutdown();
    throw Error("HUD: Dear ImGui's GLFW backend failed to start");
  }
  openGlBackendUp_ = ImGui_ImplOpenGL3_Init(kGlslVersion);
  if (!openGlBackendUp_) {
    shutdown();
    throw Error("HUD: Dear ImGui's OpenGL 3 backend failed to start (needs a GL 3.3 core context)");
  }
}

Hud::~Hud() {
  shutdown();
}

void Hud::shutdown() noexcept {
  if (context_ == nullptr) return;
  ImGui::SetCurrentContext(context_);
  // a frame begun and never rendered is ended, so that ImGui shuts down cleanly
  if (inFrame_) ImGui::EndFrame();
  if (openGlBackendUp_) ImGui_ImplOpenGL3_Shutdown();
  if (glfwBackendUp_) ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext(context_);
  context_ = nullptr;
  openGlBackendUp_ = glfwBackendUp_ = inFrame_ = false;
}

void Hud::newFrame(std::optional<HudPointer> pointer) {
  assert(!inFrame_ && "Hud::newFrame twice without render()");
  ImGui::SetCurrentContext(context_);
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGuiIO& io = ImGui::GetIO();
  // two frames within the timer's resolution would give ImGui a zero step, which it rejects
  if (io.DeltaTime <= 0.0F) io.DeltaTime = 1e-6F;
  if (pointer) {
    io.MousePos = ImVec2(pointer->xPx, pointer->yPx);
    for (bool& down : io.MouseDown) down = false;
    io.MouseDown[0] = pointer->leftDown;
  }
  ImGui::NewFrame();
  inFrame_ = true;
}

HudActions Hud::draw(const HudModel& model) {
  assert(inFrame_ && "Hud::draw outside newFrame()/render()");
  ImGui::SetCurrentContext(context_);
  HudActions actions;
  layout_ = HudLayout{};

  ImGui::SetNextWindowPos(ImVec2(kMarginPx, kMarginPx), ImGuiCond_Always);
  constexpr ImGuiWindowFlags kFlags = ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove |
                                      ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings;
  ImGui::Begin("Voxhap", nullptr, kFlags);

  if (model.loading) {
    ImGui::TextUnformatted(model.loading->stage.c_str());
    const float fraction = static_cast<float>(model.loading->fraction);
    ImGui::ProgressBar(fraction < 0.0F ? 0.0F : (fraction > 1.0F ? 1.0F : fraction),
                       ImVec2(kControlWidthPx, 0.0F));
    layout_.progressBar = lastItemRect();
    ImGui::Separator();
  }

  drawRates(model);

  if (!model.objects.empty()) {
    const bool offerGrab = !model.passive;
    const int columns = offerGrab ? 7 : 6;
    constexpr ImGuiTableFlags kTableFlags =
        ImGuiTableFlags_Borders | ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_NoHostExtendX;
    if (ImGui::BeginTable("objects", columns, kTableFlags)) {
      ImGui::TableSetupColumn("object");
      ImGui::TableSetupColumn("held by");
      ImGui::TableSetupColumn("contacts");
      ImGui::TableSetupColumn("force N");
      ImGui::TableSetupColumn("travel");
      ImGui::TableSetupColumn("clearance mm");
      if (offerGrab) ImGui::TableSetupColumn("");
      ImGui::TableHeadersRow();
      for (std::size_t i = 0; i < model.objects.size(); ++i) {
        const HudObject& object = model.objects[i];
        ImGui::PushID(static_cast<int>(i));
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(object.name.c_str());
        if (object.divergent) {
          ImGui::SameLine();
          ImGui::TextColored(kWarnColour, "shared by %zu, divergent", object.sharers);
        } else if (object.sharers > 0) {
          ImGui::SameLine();
          ImGui::Text("shared by %zu", object.sharers);
        }
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(object.heldBy.empty() ? kNone : object.heldBy.c_str());
        ImGui::TableNextColumn();
        ImGui::Text("%zu", object.contacts);
        ImGui::TableNextColumn();
        ImGui::Text("%.2f", glm::length(object.forceWorldN));
        ImGui::TableNextColumn();
        if (object.travelShare >= kTravelWarnShare) {
          ImGui::TextColored(kWarnColour, "%.0f %%", object.travelShare * 100.0);
        } else {
          ImGui::Text("%.0f %%", object.travelShare * 100.0);
        }
        ImGui::TableNextColumn();
        if (object.clearanceM) {
          ImGui::Text("%.3f", *object.clearanceM * kMmPerM);
        } else {
          ImGui::TextUnformatted(kNone);
        }
        if (offerGrab) {
          ImGui::TableNextColumn();
          // somebody else's object cannot be grabbed from here
          const bool heldByOther = !object.heldBy.empty() && !object.heldByMe;
          ImGui::BeginDisabled(heldByOther);
          if (ImGui::Button(object.heldByMe ? "release" : "grab")) {
            if (object.heldByMe) {
              actions.releaseObject = i;
            } else {
              actions.grabObject = i;
            }
          }
          layout_.grabButtons.push_back(lastItemRect());
          ImGui::EndDisabled();
        }
        ImGui::PopID();
      }
      ImGui::EndTable();
    }
  }

  if (model.passive) {
    forceLayerEdit_ = {};
    pointOffsetMmEdit_ = {};
    couplingEdit_ = {};
    ImGui::Text("force layer %d of %d", model.forceLayer, model.forceLayerMax);
    ImGui::Text("point offset %.3f mm", model.pointOffsetM * kMmPerM);
    ImGui::Text("coupling %.0f %%", model.couplingShare * 100.0);
  } else {
    ImGui::PushItemWidth(kControlWidthPx);
    actions.forceLayer = commitOnRelease(forceLayerEdit_, model.forceLayer, [&](int* layer) {
      ImGui::SliderInt("force layer", layer, model.forceLayerMin, model.forceLayerMax, "%d",
                       ImGuiSliderFlags_AlwaysClamp);
    });
    layout_.forceLayerSlider = lastItemRect();

    const double offsetMaxMm = model.pointOffsetMaxM * kMmPerM;
    const std::optional<double> offsetMm =
        commitOnRelease(pointOffsetMmEdit_, model.pointOffsetM * kMmPerM, [&](double* mm) {
          ImGui::SliderScalar("point offset", ImGuiDataType_Double, mm, &kZeroMm, &offsetMaxMm, "%.3f mm",
                              ImGuiSliderFlags_AlwaysClamp);
        });
    if (offsetMm) actions.pointOffsetM = *offsetMm / kMmPerM;
    layout_.pointOffsetSlider = lastItemRect();

    actions.couplingShare = commitOnRelease(couplingEdit_, model.couplingShare, [&](double* share) {
      ImGui::SliderScalar("coupling", ImGuiDataType_Double, share, &kShareMin, &kShareMax, "%.2f",
                          ImGuiSliderFlags_AlwaysClamp);
    });
    layout_.couplingSlider = lastItemRect();
    ImGui::PopItemWidth();
  }

  actions.frameScene = ImGui::Button("frame the scene");
  layout_.frameButton = lastItemRect();
  ImGui::SameLine();
  bool forceOverlay = model.forceOverlay;
  if (ImGui::Checkbox("force and contacts", &forceOverlay)) actions.forceOverlay = forceOverlay;
  layout_.forceOverlayCheckbox = lastItemRect();

  if (!model.message.empty()) {
    ImGui::Separator();
    ImGui::TextColored(kWarnColour, "%s", model.message.c_str());
  }

  const ImVec2 pos = ImGui::GetWindowPos();
  const ImVec2 size = ImGui::GetWindowSize();
  layout_.window = HudRectPx{pos.x, pos.y, pos.x + size.x, pos.y + size.y};
  ImGui::End();
  return actions;
}

void Hud::render() {
  assert(inFrame_ && "Hud::render without newFrame()");
  ImGui::SetCurrentContext(context_);
  ImGui::Render();
  inFrame_ = false;
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

bool Hud::wantsMouse() const {
  ImGui::SetCurrentContext(context_);
  return ImGui::GetIO().WantCaptureMouse;
}

bool Hud::wantsKeyboard() const {
  ImGui::SetCurrentContext(context_);
  return ImGui::GetIO().WantCaptureKeyboard;
}

}  // namespace voxhap

#include "render/hud.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include <GL/gl.h>
#include <GLFW/glfw3.h>
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <imgui.h>
#include <link.h>

#include "haptics/core/error.h"
#include "support/sanitizers.h"

namespace voxhap {
namespace {

constexpr int kWidthPx = 640;
constexpr int kHeightPx = 480;
/// The colour every frame is cleared to, as bytes (n/255 values, exact in 8 bits).
constexpr std::array<std::uint8_t, 3> kClear = {51, 102, 153};
/// Frames that let an auto-sized ImGui window settle before a test looks at it.
constexpr int kSettleFrames = 3;
/// Where the pointer rests when a test is not using it: the far corner, px.
constexpr HudPointer kPointerAway{kWidthPx - 4.0F, kHeightPx - 4.0F, false};

std::string g_glfwError;

/// RGBA bytes of the framebuffer, rows bottom-up as glReadPixels gives them.
struct Screenshot {
  int widthPx = 0;
  int heightPx = 0;
  std::vector<std::uint8_t> rgba;

  /// The pixel at window coordinates (y down, as ImGui's).
  const std::uint8_t* at(int xPx, int yPx) const {
    const int row = heightPx - 1 - yPx;
    return &rgba[(static_cast<std::size_t>(row) * static_cast<std::size_t>(widthPx) +
                  static_cast<std::size_t>(xPx)) *
                 4];
  }
  bool isClear(int xPx, int yPx) const {
    const std::uint8_t* p = at(xPx, yPx);
    return p[0] == kClear[0] && p[1] == kClear[1] && p[2] == kClear[2];
  }
  /// Pixels inside `rect` (window coordinates) for which `pred(rgb)` holds.
  template <typename Pred>
  int count(const HudRectPx& rect, Pred pred) const {
    int n = 0;
    for (int y = static_cast<int>(rect.minY); y < static_cast<int>(rect.maxY) && y < heightPx; ++y) {
      for (int x = static_cast<int>(rect.minX); x < static_cast<int>(rect.maxX) && x < widthPx; ++x) {
        if (x >= 0 && y >= 0 && pred(at(x, y))) ++n;
      }
    }
    return n;
  }
};

HudModel sampleModel() {
  HudModel model;
  model.renderFps = 60.0;
  model.hapticFrames = 123456;
  model.hapticRateHz = 1000.0;
  model.periodP50S = 0.001;
  model.periodP99S = 0.0011;
  model.periodMaxS = 0.002;
  model.overruns = 3;
  model.voxelSizeM = 0.001;
  model.forceLayer = 4;
  model.forceLayerMin = 3;
  model.forceLayerMax = 8;
  model.pointOffsetM = 0.0005;
  model.pointOffsetMaxM = 0.002;
  model.couplingShare = 0.5;
  model.objects.push_back(
      HudObject{"peg", "", false, 12, glm::dvec3(0.0, 3.0, 4.0), 0.25, std::optional<double>(0.0004)});
  model.objects.push_back(HudObject{"ball", "", false, 0, glm::dvec3(0.0), 0.0, std::nullopt});
  return model;
}

/// Keeps Mesa's DRI driver loaded to the process's end. glfwTerminate closes the display
/// and Mesa dlcloses its driver, whose globals held some allocations: LeakSanitizer then
/// reports them as leaks from an "<unknown module>", which no suppression can name. With
/// the driver resident they stay reachable, and any real leak is still reported.
void pinDriDriver() {
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void*) {
        const std::string name = info->dlpi_name != nullptr ? info->dlpi_name : "";
        if (name.find("_dri.so") != std::string::npos) {
          // a second reference that is never dropped, to an object already loaded
          dlopen(name.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
        }
        return 0;
      },
      nullptr);
}

class HudTest : public ::testing::Test {
protected:
  // one display connection for the whole suite: an X server resets when its last client
  // leaves, and a connection made during the reset fails
  static void SetUpTestSuite() {
    glfwSetErrorCallback([](int, const char* description) { g_glfwError = description; });
    s_glfwUp = glfwInit() == GLFW_TRUE;
  }
  static void TearDownTestSuite() {
    if (s_glfwUp) glfwTerminate();
    s_glfwUp = false;
  }

  void SetUp() override {
    ASSERT_TRUE(s_glfwUp) << "GLFW: " << g_glfwError << " (run under xvfb-run -a)";
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    window_ = glfwCreateWindow(kWidthPx, kHeightPx, "hud test", nullptr, nullptr);
    ASSERT_NE(window_, nullptr) << "GLFW: " << g_glfwError;
    glfwMakeContextCurrent(window_);
    if (test::kAddressSanitizer) pinDriDriver();
  }

  void TearDown() override {
    glfwMakeContextCurrent(nullptr);
    if (window_ != nullptr) glfwDestroyWindow(window_);
  }

  /// One frame: clear, HUD, read back. `actions` receives what the HUD reported.
  Screenshot frame(Hud& hud, const HudModel& model, HudPointer pointer = kPointerAway,
                   HudActions* actions = nullptr) {
    Screenshot shot;
    glfwGetFramebufferSize(window_, &shot.widthPx, &shot.heightPx);
    glViewport(0, 0, shot.widthPx, shot.heightPx);
    glClearColor(kClear[0] / 255.0F, kClear[1] / 255.0F, kClear[2] / 255.0F, 1.0F);
    glClear(GL_COLOR_BUFFER_BIT);
    hud.newFrame(pointer);
    const HudActions reported = hud.draw(model);
    if (actions != nullptr) *actions = reported;
    hud.render();
    glFinish();
    shot.rgba.resize(static_cast<std::size_t>(shot.widthPx) * static_cast<std::size_t>(shot.heightPx) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, shot.widthPx, shot.heightPx, GL_RGBA, GL_UNSIGNED_BYTE, shot.rgba.data());
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    return shot;
  }

  Screenshot settle(Hud& hud, const HudModel& model) {
    Screenshot shot;
    for (int i = 0; i < kSettleFrames; ++i) shot = frame(hud, model);
    return shot;
  }

  /// Presses and releases the left button at (x, y): hover, down, up. The actions of
  /// the three frames, in order.
  std::vector<HudActions> click(Hud& hud, const HudModel& model, float xPx, float yPx) {
    std::vector<HudActions> actions(3);
    frame(hud, model, HudPointer{xPx, yPx, false}, &actions[0]);
    frame(hud, model, HudPointer{xPx, yPx, true}, &actions[1]);
    frame(hud, model, HudPointer{xPx, yPx, false}, &actions[2]);
    return actions;
  }

  static inline bool s_glfwUp = false;
  GLFWwindow* window_ = nullptr;
};

TEST_F(HudTest, DrawsInItsRegionAndLeavesTheFarCornerClear) {
  Hud hud(window_);
  const Screenshot shot = settle(hud, sampleModel());
  const HudRectPx& window = hud.layout().window;
  ASSERT_GT(window.maxX - window.minX, 50.0F);
  ASSERT_GT(window.maxY - window.minY, 50.0F);
  ASSERT_LT(window.maxX, kWidthPx - 16.0F) << "the HUD covers the far corner";
  ASSERT_LT(window.maxY, kHeightPx - 16.0F) << "the HUD covers the far corner";

  const int inside = shot.count(window, [](const std::uint8_t* p) {
    return p[0] != kClear[0] || p[1] != kClear[1] || p[2] != kClear[2];
  });
  const float area = (window.maxX - window.minX) * (window.maxY - window.minY);
  // the window's background is nearly opaque, so almost every pixel of it changed
  EXPECT_GT(static_cast<float>(inside), 0.8F * area);

  for (int y = kHeightPx - 16; y < kHeightPx; ++y) {
    for (int x = kWidthPx - 16; x < kWidthPx; ++x) ASSERT_TRUE(shot.isClear(x, y)) << x << ", " << y;
  }
}

TEST_F(HudTest, ASharedObjectSaysSoAndItsDivergenceIsInTheWarningColour) {
  // orange text (the warning colour, 1.0/0.6/0.2) is drawn anti-aliased: count the
  // pixels that are clearly orange
  const auto orange = [](const std::uint8_t* p) {
    return p[0] > 200 && p[1] > 90 && p[1] < 170 && p[2] < 90;
  };
  HudModel model = sampleModel();
  model.overruns = 0;  // the only other orange text
  Hud hud(window_);
  const int plain = settle(hud, model).count(hud.layout().window, orange);
  model.objects[0].sharers = 2;
  const int shared = settle(hud, model).count(hud.layout().window, orange);
  model.objects[0].divergent = true;
  const int divergent = settle(hud, model).count(hud.layout().window, orange);
  EXPECT_EQ(shared, plain);
  EXPECT_GT(divergent, plain + 20);
}

TEST_F(HudTest, LoadingBarFillGrowsWithTheFraction) {
  Hud hud(window_);
  const ImVec4 fill = ImGui::GetStyleColorVec4(ImGuiCol_PlotHistogram);
  const std::array<int, 3> fillRgb = {static_cast<int>(fill.x * 255.0F + 0.5F),
                                      static_cast<int>(fill.y * 255.0F + 0.5F),
                                      static_cast<int>(fill.z * 255.0F + 0.5F)};
  const auto isFill = [&](const std::uint8_t* p) {
    for (int c = 0; c < 3; ++c) {
      if (std::abs(static_cast<int>(p[c]) - fillRgb[static_cast<std::size_t>(c)]) > 4) return false;
    }
    return true;
  };

  HudModel model;
  model.loading = HudLoading{"voxelizing peg", 0.25};
  const Screenshot quarter = settle(hud, model);
  ASSERT_TRUE(hud.layout().progressBar);
  const int quarterFill = quarter.count(*hud.layout().progressBar, isFill);

  model.loading->fraction = 0.75;
  const Screenshot threeQuarters = settle(hud, model);
  ASSERT_TRUE(hud.layout().progressBar);
  const int threeQuartersFill = threeQuarters.count(*hud.layout().progressBar, isFill);

  EXPECT_GT(quarterFill, 0);
  // three times the share: clearly more than twice the pixels (the label covers a few)
  EXPECT_GT(threeQuartersFill, 2 * quarterFill);
  EXPECT_LT(threeQuartersFill, 4 * quarterFill);

  model.loading.reset();
  settle(hud, model);
  EXPECT_FALSE(hud.layout().progressBar);
}

TEST_F(HudTest, PassiveModeOffersNoGrabOrEditControls) {
  Hud hud(window_);
  HudModel model = sampleModel();
  settle(hud, model);
  EXPECT_EQ(hud.layout().grabButtons.size(), model.objects.size());
  EXPECT_TRUE(hud.layout().forceLayerSlider);

  model.passive = true;
  settle(hud, model);
  EXPECT_TRUE(hud.layout().grabButtons.empty());
  EXPECT_FALSE(hud.layout().forceLayerSlider);
  EXPECT_FALSE(hud.layout().pointOffsetSlider);
  EXPECT_FALSE(hud.layout().couplingSlider);
  EXPECT_TRUE(hud.layout().frameButton);
}

TEST_F(HudTest, ClickingGrabReportsThatObjectOnce) {
  Hud hud(window_);
  const HudModel model = sampleModel();
  settle(hud, model);
  ASSERT_EQ(hud.layout().grabButtons.size(), 2U);
  const HudRectPx button = hud.layout().grabButtons[1];

  const std::vector<HudActions> actions = click(hud, model, button.centerX(), button.centerY());
  // ImGui buttons fire on release
  EXPECT_FALSE(actions[0].any());
  EXPECT_FALSE(actions[1].any());
  ASSERT_TRUE(actions[2].grabObject);
  EXPECT_EQ(*actions[2].grabObject, 1U);
  EXPECT_FALSE(actions[2].releaseObject);

  HudActions after;
  frame(hud, model, kPointerAway, &after);
  EXPECT_FALSE(after.any());
}

TEST_F(HudTest, ClickingTheForceBoxTurnsItOffOnceAndOnAgain) {
  Hud hud(window_);
  HudModel model = sampleModel();
  settle(hud, model);
  ASSERT_TRUE(hud.layout().forceOverlayCheckbox);
  const HudRectPx box = *hud.layout().forceOverlayCheckbox;
  std::vector<HudActions> actions = click(hud, model, box.centerX(), box.centerY());
  int reported = 0;
  for (const HudActions& a : actions) {
    if (!a.forceOverlay) continue;
    ++reported;
    EXPECT_FALSE(*a.forceOverlay);  // it was on
  }
  EXPECT_EQ(reported, 1);
  model.forceOverlay = false;  // the app keeps the choice
  actions = click(hud, model, box.centerX(), box.centerY());
  EXPECT_TRUE(std::any_of(actions.begin(), actions.end(),
                          [](const HudActions& a) { return a.forceOverlay == true; }));
}

TEST_F(HudTest, ClickingAHeldObjectReleasesIt) {
  Hud hud(window_);
  HudModel model = sampleModel();
  model.objects[0].heldBy = "me";
  model.objects[0].heldByMe = true;
  settle(hud, model);
  const HudRectPx button = hud.layout().grabButtons[0];
  const std::vector<HudActions> actions = click(hud, model, button.centerX(), button.centerY());
  ASSERT_TRUE(actions[2].releaseObject);
  EXPECT_EQ(*actions[2].releaseObject, 0U);
  EXPECT_FALSE(actions[2].grabObject);
}

TEST_F(HudTest, AnObjectHeldByAnotherPeerCannotBeGrabbed) {
  Hud hud(window_);
  HudModel model = sampleModel();
  model.objects[1].heldBy = "peer 2";
  settle(hud, model);
  const HudRectPx button = hud.layout().grabButtons[1];
  for (const HudActions& actions : click(hud, model, button.centerX(), button.centerY())) {
    EXPECT_FALSE(actions.any());
  }
}

TEST_F(HudTest, SliderEditIsReportedOnceWhenReleased) {
  Hud hud(window_);
  const HudModel model = sampleModel();  // force layer 4 of 3 to 8
  settle(hud, model);
  ASSERT_TRUE(hud.layout().forceLayerSlider);
  const HudRectPx slider = *hud.layout().forceLayerSlider;
  const float y = slider.centerY();

  std::vector<HudActions> actions;
  const auto step = [&](float xPx, bool down) {
    HudActions a;
    frame(hud, model, HudPointer{xPx, y, down}, &a);
    actions.push_back(a);
  };
  step(slider.minX + 2.0F, false);
  step(slider.minX + 2.0F, true);
  EXPECT_TRUE(hud.wantsMouse());
  // drag past the right end (the slider clamps to its maximum), held for a few frames
  for (int i = 1; i <= 4; ++i) step(slider.minX + static_cast<float>(i) * (slider.maxX - slider.minX), true);
  step(slider.maxX + 40.0F, false);
  step(slider.maxX + 40.0F, false);

  int reports = 0;
  for (std::size_t i = 0; i < actions.size(); ++i) {
    if (!actions[i].forceLayer) continue;
    ++reports;
    EXPECT_EQ(i, actions.size() - 2) << "reported before the release";
    EXPECT_EQ(*actions[i].forceLayer, model.forceLayerMax);
  }
  EXPECT_EQ(reports, 1);
}

// At its left end the force layer slider gives the smallest layer every pair takes (3 with
// surface planes), not 0, which the controller refuses.
TEST_F(HudTest, TheForceLayerSliderStopsAtTheSmallestLayerEveryPairTakes) {
  Hud hud(window_);
  const HudModel model = sampleModel();  // force layer 4 of 3 to 8
  settle(hud, model);
  ASSERT_TRUE(hud.layout().forceLayerSlider);
  const HudRectPx slider = *hud.layout().forceLayerSlider;
  std::optional<int> committed;
  const auto step = [&](float xPx, bool down) {
    HudActions a;
    frame(hud, model, HudPointer{xPx, slider.centerY(), down}, &a);
    if (a.forceLayer) committed = a.forceLayer;
  };
  // pressed at the slider's left end, held there, released
  step(slider.minX + 1.0F, false);
  for (int i = 0; i < 3; ++i) step(slider.minX + 1.0F, true);
  step(slider.minX + 1.0F, false);
  step(slider.minX + 1.0F, false);
  ASSERT_TRUE(committed);
  EXPECT_EQ(*committed, model.forceLayerMin);
}

TEST_F(HudTest, WantsTheMouseOnlyOverTheHud) {
  Hud hud(window_);
  const HudModel model = sampleModel();
  settle(hud, model);
  const HudRectPx window = hud.layout().window;
  frame(hud, model, HudPointer{window.centerX(), window.centerY(), false});
  EXPECT_TRUE(hud.wantsMouse());
  frame(hud, model, kPointerAway);
  EXPECT_FALSE(hud.wantsMouse());
  EXPECT_FALSE(hud.wantsKeyboard());
}

TEST_F(HudTest, NeedsAWindowWithItsContextCurrent) {
  EXPECT_THROW(Hud(nullptr), Error);
  glfwMakeContextCurrent(nullptr);
  EXPECT_THROW(Hud{window_}, Error);
}

}  // namespace
}  // namespace voxhap

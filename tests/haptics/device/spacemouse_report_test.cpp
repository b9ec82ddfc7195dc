#include "haptics/device/spacemouse_report.h"

#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace voxhap {
namespace {

constexpr double kFullScale = 350.0;
constexpr SpaceMouseReportFormat kSeparate{SpaceMouseMotionLayout::kSeparate, 2};
constexpr SpaceMouseReportFormat kCombined{SpaceMouseMotionLayout::kCombined, 2};
constexpr SpaceMouseReportFormat kAuto{SpaceMouseMotionLayout::kAuto, 2};

void putInt16(std::vector<std::uint8_t>& out, int value) {
  const auto bits = static_cast<std::uint16_t>(static_cast<std::int16_t>(value));
  out.push_back(static_cast<std::uint8_t>(bits & 0xff));
  out.push_back(static_cast<std::uint8_t>(bits >> 8));
}

/// A report of `id` with int16 counts `values`, appended to `out`.
void appendReport(std::vector<std::uint8_t>& out, std::uint8_t id, std::initializer_list<int> values) {
  out.push_back(id);
  for (int v : values) putInt16(out, v);
}

SpaceMouseParseResult parse(const std::vector<std::uint8_t>& bytes, SpaceMouseState& state,
                            const SpaceMouseReportFormat& format = kSeparate) {
  return parseSpaceMouseReports(bytes, format, kFullScale, state);
}

TEST(SpaceMouseReport, TranslationMapsDeviceAxesToTheViewFrame) {
  // device: +x right, +y toward the user, +z down; view: +x right, +y up, +z toward the user
  std::vector<std::uint8_t> bytes;
  appendReport(bytes, 1, {175, 350, -70});
  SpaceMouseState state;
  const SpaceMouseParseResult r = parse(bytes, state);
  EXPECT_EQ(r.reports, 1u);
  EXPECT_EQ(r.errors, 0u);
  EXPECT_EQ(r.changed, kChangedTranslation);
  EXPECT_DOUBLE_EQ(state.deflectionView[kAxisTx], 0.5);
  EXPECT_DOUBLE_EQ(state.deflectionView[kAxisTy], 0.2);  // device z −70 (up) → view +y
  EXPECT_DOUBLE_EQ(state.deflectionView[kAxisTz], 1.0);  // device y (toward the user) → view +z
  EXPECT_EQ(state.deflectionView[kAxisRx], 0.0);
}

TEST(SpaceMouseReport, RotationUsesTheSameAxisTable) {
  std::vector<std::uint8_t> bytes;
  appendReport(bytes, 2, {-350, 35, 350});
  SpaceMouseState state;
  const SpaceMouseParseResult r = parse(bytes, state);
  EXPECT_EQ(r.changed, kChangedRotation);
  EXPECT_DOUBLE_EQ(state.deflectionView[kAxisRx], -1.0);
  EXPECT_DOUBLE_EQ(state.deflectionView[kAxisRy], -1.0);  // twist about device z (down)
  EXPECT_DOUBLE_EQ(state.deflectionView[kAxisRz], 0.1);
  EXPECT_EQ(state.deflectionView[kAxisTx], 0.0);
}

TEST(SpaceMouseReport, CountsBeyondFullScaleAreClamped) {
  std::vector<std::uint8_t> bytes;
  appendReport(bytes, 1, {32767, -32768, 0});
  SpaceMouseState state;
  parse(bytes, state);
  EXPECT_EQ(state.deflectionView[kAxisTx], 1.0);
  EXPECT_EQ(state.deflectionView[kAxisTz], -1.0);
}

TEST(SpaceMouseReport, FullScaleIsAParameter) {
  std::vector<std::uint8_t> bytes;
  appendReport(bytes, 1, {100, 0, 0});
  SpaceMouseState state;
  parseSpaceMouseReports(bytes, kSeparate, 400.0, state);
  EXPECT_DOUBLE_EQ(state.deflectionView[kAxisTx], 0.25);
}

TEST(SpaceMouseReport, CombinedReportCarriesTranslationThenRotation) {
  std::vector<std::uint8_t> bytes;
  appendReport(bytes, 1, {35, 0, 0, 0, 0, 70});
  ASSERT_EQ(bytes.size(), 13u);
  for (const SpaceMouseReportFormat& format : {kCombined, kAuto}) {
    SpaceMouseState state;
    const SpaceMouseParseResult r = parse(bytes, state, format);
    EXPECT_EQ(r.reports, 1u);
    EXPECT_EQ(r.errors, 0u);
    EXPECT_EQ(r.changed, kChangedTranslation | kChangedRotation);
    EXPECT_DOUBLE_EQ(state.deflectionView[kAxisTx], 0.1);
    EXPECT_DOUBLE_EQ(state.deflectionView[kAxisRy], -0.2);
  }
}

TEST(SpaceMouseReport, CoalescedReadIsSplitIntoItsReports) {
  std::vector<std::uint8_t> bytes;
  appendReport(bytes, 1, {0, 175, 0});
  appendReport(bytes, 2, {0, 0, -175});
  bytes.insert(bytes.end(), {3, 0x05, 0x00});
  for (const SpaceMouseReportFormat& format : {kSeparate, kAuto}) {
    SpaceMouseState state;
    const SpaceMouseParseResult r = parse(bytes, state, format);
    EXPECT_EQ(r.reports, 3u);
    EXPECT_EQ(r.errors, 0u);
    EXPECT_EQ(r.changed, kChangedTranslation | kChangedRotation | kChangedButtons);
    EXPECT_DOUBLE_EQ(state.deflectionView[kAxisTz], 0.5);
    EXPECT_DOUBLE_EQ(state.deflectionView[kAxisRy], 0.5);
    EXPECT_EQ(state.buttons, 0x05u);
  }
}

TEST(SpaceMouseReport, ButtonsAreALittleEndianBitmask) {
  SpaceMouseState state;
  const SpaceMouseReportFormat fourBytes{SpaceMouseMotionLayout::kSeparate, 4};
  const std::vector<std::uint8_t> bytes{3, 0x01, 0x00, 0x00, 0x80};
  const SpaceMouseParseResult r = parse(bytes, state, fourBytes);
  EXPECT_EQ(r.reports, 1u);
  EXPECT_EQ(state.buttons, 0x80000001u);
  // the same report again changes nothing
  EXPECT_EQ(parse(bytes, state, fourBytes).changed, 0);
}

TEST(SpaceMouseReport, ARepeatedValueIsNoChange) {
  std::vector<std::uint8_t> bytes;
  appendReport(bytes, 1, {10, 20, 30});
  SpaceMouseState state;
  EXPECT_EQ(parse(bytes, state).changed, kChangedTranslation);
  EXPECT_EQ(parse(bytes, state).changed, 0);
}

TEST(SpaceMouseReport, TruncatedReportIsCountedAndTheRestKept) {
  std::vector<std::uint8_t> bytes;
  appendReport(bytes, 1, {70, 0, 0});
  bytes.insert(bytes.end(), {2, 0x10, 0x00, 0x20});  // rotation cut short
  SpaceMouseState state;
  const SpaceMouseParseResult r = parse(bytes, state);
  EXPECT_EQ(r.reports, 1u);
  EXPECT_EQ(r.errors, 1u);
  EXPECT_EQ(r.bytesDiscarded, 4u);
  EXPECT_EQ(r.changed, kChangedTranslation);
  EXPECT_DOUBLE_EQ(state.deflectionView[kAxisTx], 0.2);
  EXPECT_EQ(state.deflectionView[kAxisRx], 0.0);
}

TEST(SpaceMouseReport, UnknownIdEndsTheBuffer) {
  std::vector<std::uint8_t> bytes{0x17, 1, 2, 3};
  appendReport(bytes, 1, {70, 0, 0});
  SpaceMouseState state;
  const SpaceMouseParseResult r = parse(bytes, state);
  EXPECT_EQ(r.reports, 0u);
  EXPECT_EQ(r.errors, 1u);
  EXPECT_EQ(r.bytesDiscarded, bytes.size());
  EXPECT_EQ(state.deflectionView[kAxisTx], 0.0);
}

TEST(SpaceMouseReport, TrailingGarbageIsCounted) {
  std::vector<std::uint8_t> bytes;
  appendReport(bytes, 2, {0, 0, 35});
  bytes.push_back(0x00);
  SpaceMouseState state;
  const SpaceMouseParseResult r = parse(bytes, state);
  EXPECT_EQ(r.reports, 1u);
  EXPECT_EQ(r.errors, 1u);
  EXPECT_EQ(r.bytesDiscarded, 1u);
}

TEST(SpaceMouseReport, EmptyBufferDoesNothing) {
  SpaceMouseState state;
  const SpaceMouseParseResult r = parseSpaceMouseReports({}, kAuto, kFullScale, state);
  EXPECT_EQ(r.reports, 0u);
  EXPECT_EQ(r.errors, 0u);
  EXPECT_EQ(r.changed, 0);
}

TEST(SpaceMouseReport, KnownModelsAreFoundUnderEitherVendorId) {
  const SpaceMouseModel* navigator = findSpaceMouseModel(kVendorLogitech3Dconnexion, 0xc626);
  ASSERT_NE(navigator, nullptr);
  EXPECT_EQ(navigator->name, "SpaceNavigator");
  EXPECT_EQ(navigator->format.motion, SpaceMouseMotionLayout::kSeparate);
  ASSERT_NE(findSpaceMouseModel(kVendor3Dconnexion, 0xc652), nullptr);
  EXPECT_EQ(findSpaceMouseModel(kVendor3Dconnexion, 0xc652)->format.motion,
            SpaceMouseMotionLayout::kCombined);
  EXPECT_EQ(findSpaceMouseModel(0x046e, 0xc626), nullptr);
  EXPECT_EQ(findSpaceMouseModel(kVendor3Dconnexion, 0x1234), nullptr);
  for (const SpaceMouseModel& model : knownSpaceMouseModels()) {
    EXPECT_GE(model.format.buttonBytes, 1);
    EXPECT_LE(model.format.buttonBytes, 4);
  }
}

// bounded fuzz: random buffers, biased toward valid ids, never read past the end, keep
// every deflection in [−1, 1] and account for every byte
TEST(SpaceMouseReport, RandomBuffersAreParsedSafely) {
  std::mt19937 random(20261202);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> length(0, 40);
  std::uniform_int_distribution<int> layout(0, 2);
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(length(random)));
    for (std::uint8_t& b : bytes)
      b = static_cast<std::uint8_t>(byte(random) % 5 == 0 ? byte(random) % 4 : byte(random));
    const SpaceMouseReportFormat format{static_cast<SpaceMouseMotionLayout>(layout(random)),
                                        static_cast<std::uint8_t>(1 + trial % 4)};
    SpaceMouseState state;
    const SpaceMouseParseResult r = parseSpaceMouseReports(bytes, format, kFullScale, state);
    EXPECT_LE(r.errors, 1u);
    EXPECT_LE(r.bytesDiscarded, bytes.size());
    EXPECT_EQ(r.errors == 0, r.bytesDiscarded == 0);
    for (double d : state.deflectionView) {
      EXPECT_GE(d, -1.0);
      EXPECT_LE(d, 1.0);
    }
  }
}

}  // namespace
}  // namespace voxhap

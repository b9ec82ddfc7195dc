#include "app/cli/option_values.h"

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>

namespace voxhap::cli {
namespace {

/// Parses `words` (without the program name) as CLI11 takes them: reversed.
void parse(CLI::App& app, const std::vector<std::string>& words) {
  std::vector<std::string> reversed(words.rbegin(), words.rend());
  app.parse(reversed);
}

/// The message of the UsageError `f` throws, or "" when it throws none.
template <typename F>
std::string usageErrorOf(F f) {
  try {
    f();
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(OptionValues, ParsesUnsignedStrictly) {
  EXPECT_EQ(parseUnsigned("0", "seed"), 0u);
  EXPECT_EQ(parseUnsigned("18446744073709551615", "seed"), 18446744073709551615ull);
  EXPECT_THROW(parseUnsigned("18446744073709551616", "seed"), UsageError);
  EXPECT_THROW(parseUnsigned("-1", "seed"), UsageError);
  EXPECT_THROW(parseUnsigned("1.5", "seed"), UsageError);
  EXPECT_THROW(parseUnsigned("", "seed"), UsageError);
  EXPECT_THROW(parseUnsigned("7x", "seed"), UsageError);
}

TEST(OptionValues, ParsesLengthsInMetresOrMillimetres) {
  EXPECT_DOUBLE_EQ(parseLengthM("0.35mm", "voxel-size"), 0.35e-3);
  EXPECT_DOUBLE_EQ(parseLengthM("2.5 mm", "voxel-size"), 2.5e-3);
  EXPECT_DOUBLE_EQ(parseLengthM("0.00035m", "voxel-size"), 0.00035);
  EXPECT_DOUBLE_EQ(parseLengthM("0.00035", "voxel-size"), 0.00035);
  EXPECT_DOUBLE_EQ(parseLengthM("-12mm", "slice", LengthSign::Any), -0.012);
  EXPECT_DOUBLE_EQ(parseLengthM("0", "slice", LengthSign::Any), 0.0);
  for (const char* bad :
       {"", "0", "-1mm", "nan", "inf", "1e999", "0.35 cm", "mm", "0.35mmm", "abc", "0.3.5"}) {
    try {
      parseLengthM(bad, "voxel-size");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find("--voxel-size"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(parseLengthM("nan", "slice", LengthSign::Any), UsageError);
}

TEST(OptionValues, ParsesBytesInPowersOf1024) {
  EXPECT_EQ(parseBytes("65536", "voxel-memory"), 65536u);
  EXPECT_EQ(parseBytes("2GiB", "voxel-memory"), 2ull << 30);
  EXPECT_EQ(parseBytes("512 MiB", "voxel-memory"), 512ull << 20);
  EXPECT_EQ(parseBytes("1.5G", "voxel-memory"), 3ull << 29);
  EXPECT_EQ(parseBytes("4K", "voxel-memory"), 4096u);
  for (const char* bad : {"", "0", "0.5", "-1G", "2GB", "2 TiB", "G", "1e30"}) {
    EXPECT_NE(usageErrorOf([&] { parseBytes(bad, "voxel-memory"); }).find("--voxel-memory"),
              std::string::npos)
        << "'" << bad << "'";
  }
}

TEST(OptionValues, ParsesSecondsNotNegative) {
  EXPECT_DOUBLE_EQ(parseSeconds("0", "duration"), 0.0);
  EXPECT_DOUBLE_EQ(parseSeconds("2.5", "duration"), 2.5);
  EXPECT_DOUBLE_EQ(parseSeconds("2.5s", "duration"), 2.5);
  EXPECT_DOUBLE_EQ(parseSeconds("100 ms", "duration"), 0.1);
  for (const char* bad : {"", "-1", "-5ms", "nan", "inf", "2h", "ms", "x", "2 s x"}) {
    EXPECT_NE(usageErrorOf([&] { parseSeconds(bad, "duration"); }).find("--duration"), std::string::npos)
        << "'" << bad << "'";
  }
}

TEST(OptionValues, ParsesSharesAsFractionsOrPercentages) {
  EXPECT_DOUBLE_EQ(parseFraction("0.05", "loss"), 0.05);
  EXPECT_DOUBLE_EQ(parseFraction("5%", "loss"), 0.05);
  EXPECT_DOUBLE_EQ(parseFraction("100 %", "loss"), 1.0);
  EXPECT_DOUBLE_EQ(parseFraction("0", "loss"), 0.0);
  for (const char* bad : {"", "-0.1", "1.5", "150%", "nan", "5 percent", "%"}) {
    EXPECT_NE(usageErrorOf([&] { parseFraction(bad, "loss"); }).find("--loss wants a share"),
              std::string::npos)
        << "'" << bad << "'";
  }
}

TEST(OptionValues, TypedOptionsParseIntoTheirFields) {
  CLI::App app;
  std::optional<double> voxelSizeM, offsetM;
  std::optional<std::uint64_t> capacity;
  std::uint64_t seed = 1;
  addLengthOption(app, "--voxel-size", voxelSizeM, "");
  addLengthOption(app, "--point-offset", offsetM, "", LengthSign::Any);
  addUnsignedOption(app, "--capacity", capacity, "");
  addUnsignedOption(app, "--seed", seed, "");
  parse(app, {"--voxel-size=0.35mm", "--point-offset", "-0.175mm", "--capacity", "5", "--capacity", "7"});
  EXPECT_DOUBLE_EQ(voxelSizeM.value_or(0.0), 0.35e-3);
  EXPECT_DOUBLE_EQ(offsetM.value_or(0.0), -0.175e-3);
  EXPECT_EQ(capacity, 7u);  // the last one given
  EXPECT_EQ(seed, 1u);      // not given: the default stays
}

TEST(OptionValues, BadValueIsAUsageErrorNamingTheOption) {
  CLI::App app;
  std::optional<double> voxelSizeM;
  addLengthOption(app, "--voxel-size", voxelSizeM, "");
  const std::string message = usageErrorOf([&] { parse(app, {"--voxel-size", "0.35cm"}); });
  EXPECT_NE(message.find("--voxel-size"), std::string::npos) << message;
  EXPECT_NE(message.find("0.35cm"), std::string::npos) << message;
}

TEST(OptionValues, RepeatedOptionTakesOneValueEachTimeInOrder) {
  CLI::App app;
  std::vector<std::string> moving;
  std::vector<double> sizesM;
  std::string scene;
  addRepeatedOption(app, "--move", "NAME", "", [&](const std::string& name) { moving.push_back(name); });
  addLengthListOption(app, "--voxel-size", sizesM, "");
  app.add_option("SCENE", scene)->required();
  parse(app, {"--move", "ball", "scene.glb", "--voxel-size", "1mm", "--move=peg", "--voxel-size=2 mm"});
  EXPECT_EQ(moving, (std::vector<std::string>{"ball", "peg"}));
  ASSERT_EQ(sizesM.size(), 2u);
  EXPECT_DOUBLE_EQ(sizesM[0], 1e-3);
  EXPECT_DOUBLE_EQ(sizesM[1], 2e-3);
  EXPECT_EQ(scene, "scene.glb");
}

}  // namespace
}  // namespace voxhap::cli

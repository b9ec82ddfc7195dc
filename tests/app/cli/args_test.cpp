#include "app/cli/args.h"

#include <gtest/gtest.h>

namespace voxhap::cli {
namespace {

const std::vector<OptionSpec> kSpecs = {
    {"json", 0, "", "json"},
    {"output", 'o', "FILE", "output"},
    {"move", 0, "NAME", "repeatable"},
};

TEST(Args, SeparatesPositionalsFromOptions) {
  const ParsedArgs a = parseArgs({"scene.glb", "--json", "-o", "out.glb"}, kSpecs);
  EXPECT_EQ(a.positionals, std::vector<std::string>{"scene.glb"});
  EXPECT_TRUE(a.has("json"));
  EXPECT_EQ(a.value("output"), "out.glb");
  EXPECT_FALSE(a.has("move"));
}

TEST(Args, AcceptsInlineValuesAndRepeats) {
  const ParsedArgs a = parseArgs({"--move=ball", "--move", "peg", "--output=x.glb"}, kSpecs);
  EXPECT_EQ(a.values("move"), (std::vector<std::string>{"ball", "peg"}));
  EXPECT_EQ(a.value("move"), "peg");
  EXPECT_EQ(a.value("output"), "x.glb");
}

TEST(Args, DoubleDashEndsOptions) {
  const ParsedArgs a = parseArgs({"--", "--json", "-o"}, kSpecs);
  EXPECT_EQ(a.positionals, (std::vector<std::string>{"--json", "-o"}));
  EXPECT_FALSE(a.has("json"));
}

TEST(Args, RejectsUnknownOptionByName) {
  try {
    parseArgs({"--jsn"}, kSpecs);
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--jsn"), std::string::npos);
  }
}

TEST(Args, RejectsMissingValueAndValueOnFlag) {
  EXPECT_THROW(parseArgs({"-o"}, kSpecs), UsageError);
  EXPECT_THROW(parseArgs({"--json=yes"}, kSpecs), UsageError);
}

TEST(Args, ParsesUnsignedStrictly) {
  EXPECT_EQ(parseUnsigned("0", "seed"), 0u);
  EXPECT_EQ(parseUnsigned("18446744073709551615", "seed"), 18446744073709551615ull);
  EXPECT_THROW(parseUnsigned("18446744073709551616", "seed"), UsageError);
  EXPECT_THROW(parseUnsigned("-1", "seed"), UsageError);
  EXPECT_THROW(parseUnsigned("1.5", "seed"), UsageError);
  EXPECT_THROW(parseUnsigned("", "seed"), UsageError);
  EXPECT_THROW(parseUnsigned("7x", "seed"), UsageError);
}

TEST(Args, ParsesLengthsInMetresOrMillimetres) {
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

}  // namespace
}  // namespace voxhap::cli

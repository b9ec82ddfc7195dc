// `voxhap extract` (the demo's job for one user, offline), run as the real executable.
// The landing gear itself takes minutes to generate and voxelize in a fresh cache, so the
// runs here pull the peg out of the committed peg-in-hole scene through the same code
// (--scene, --move, --script); the landing-gear figures are measured by hand and by
// `voxhap bench extraction`.

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"

namespace voxhap::test {
namespace {

class ExtractCommand : public CliTest {
protected:
  /// The peg lifted 20 mm out of the mouth of its hole in 0.2 s, then held for 0.1 s.
  std::string liftScript() const {
    const std::filesystem::path file = dir_ / "lift.txt";
    std::ofstream(file) << "0 1 0 0 0 0 0 0\n0.2 1 0 0 0 0 0 0.020\n0.3 1 0 0 0 0 0 0.020\n";
    return file.string();
  }
};

TEST_F(ExtractCommand, HelpExplainsThePathAndHowPenetrationIsMeasured) {
  const CliRun r = voxhap({"extract", "--help"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* text : {"clevis", "Embree", "--penetration-every", "--duration", "--brute-force",
                           "--capacity", "--voxel-size", "--point-spacing", "2.5mm", "1mm", "Examples"}) {
    EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
  }
}

TEST_F(ExtractCommand, JsonSummaryOfAShortExtraction) {
  const CliRun r = voxhap({"extract", "--scene", asset("peg-in-hole.glb"), "--move", "peg", "--script",
                           liftScript(), "--voxel-size", "1mm", "--point-spacing", "1mm", "--json"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("frames"), 300);
  EXPECT_EQ(j.at("moving"), "peg");
  for (const char* key : {"missed_deadlines", "frames_over_budget", "frames_within_1ms", "max_contacts",
                          "mean_contacts", "max_force_n", "mean_travel_scale", "penetration_checks"}) {
    EXPECT_TRUE(j.at(key).is_number()) << key;
  }
  EXPECT_EQ(j.at("frames_within_1ms").get<int>() + j.at("frames_over_budget").get<int>(), 300);
  EXPECT_EQ(j.at("penetration_checks"), 300);
  // 1 mm above the mouth and going up: nothing inside, the exact clearance about that gap
  EXPECT_EQ(j.at("max_penetration_m").get<double>(), 0.0);
  ASSERT_TRUE(j.at("min_clearance_m").is_number()) << j.dump(2);
  EXPECT_GT(j.at("min_clearance_m").get<double>(), 0.0005);
  EXPECT_LT(j.at("min_clearance_m").get<double>(), 0.0015);
  EXPECT_NEAR(j.at("path_length_m").get<double>(), 0.020, 1e-9);
  EXPECT_NEAR(j.at("actuator_progress_m").get<double>(), 0.020, 0.002);
  EXPECT_EQ(j.at("came_out"), true);
  ASSERT_TRUE(j.at("completion_s").is_number());
  EXPECT_GT(j.at("completion_s").get<double>(), 0.0);
  EXPECT_LT(j.at("completion_s").get<double>(), 0.3);
}

TEST_F(ExtractCommand, DurationCutsTheRunShort) {
  const CliRun r = voxhap({"extract", "--scene", asset("peg-in-hole.glb"), "--move", "peg", "--script",
                           liftScript(), "--voxel-size", "1mm", "--point-spacing", "1mm", "--duration",
                           "0.05", "--penetration-every", "10", "--json"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("frames"), 50);
  EXPECT_EQ(j.at("penetration_checks"), 6);  // frames 0, 10, …, 40 and the last
  EXPECT_EQ(j.at("came_out"), false);        // 5 mm up of 20: not out yet
  EXPECT_LT(j.at("actuator_progress_m").get<double>(), 0.010);
}

TEST_F(ExtractCommand, BadOptionsAreUsageErrors) {
  for (const auto& [option, value] : {std::pair{"--penetration-every", "0"}, std::pair{"--duration", "-1"},
                                      std::pair{"--voxel-size", "0mm"}}) {
    const CliRun r = voxhap({"extract", std::string(option) + "=" + value});
    EXPECT_EQ(r.exitCode, 2) << option;
    EXPECT_NE(r.err.find(std::string(option).substr(2)), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace voxhap::test

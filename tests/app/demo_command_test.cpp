// `voxhap demo`, run as the real executable: the three-peer session on the landing gear
// for a crew (ann and bob share the actuator, cyd lifts the spare actuator into its way and
// back). Release only, like the crew test (landing_gear_crew_test.cpp): the scene is
// generated and voxelized in the test's fresh cache, which a sanitizer's build takes many
// minutes for.

#include <cstdio>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/exclusive_section.h"
#include "support/sanitizers.h"

namespace voxhap::test {
namespace {

class DemoCommand : public CliTest {};

TEST_F(DemoCommand, HelpSaysWhoDoesWhatAndWhatTheSummaryMeasures) {
  const CliRun r = voxhap({"demo", "--help"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* text : {"share", "spare actuator", "type-2", "type-1", "--no-passivity", "came out",
                           "voxhap extract", "Examples"}) {
    EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
  }
}

TEST_F(DemoCommand, ThreePeersPlayTheSessionAndReportItWithoutOverlap) {
  if (kAddressSanitizer || kThreadSanitizer) GTEST_SKIP() << "Release only (see the note at the top)";
  const ExclusiveSection alone(kLandingGearSessionLock);
  const CliRun r = voxhap({"demo", "--no-realtime", "--json"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  ASSERT_TRUE(j.is_object()) << r.out;
  ASSERT_EQ(j.at("peers").size(), 3u);
  for (const nlohmann::json& p : j.at("peers")) {
    SCOPED_TRACE(p.at("user").get<std::string>());
    const nlohmann::json& c = p.at("controller");
    EXPECT_GT(c.at("simulated_s").get<double>(), 30.0);
    const nlohmann::json& shared = c.at("peer").at("shared");
    ASSERT_EQ(shared.size(), 1u) << c.dump();
    EXPECT_EQ(shared[0].at("object"), "actuator");
    const bool sharer = p.at("user") != "cyd";
    EXPECT_EQ(shared[0].at("shared_here"), sharer);
    if (sharer) {
      const nlohmann::json& k = shared[0].at("coupling");
      EXPECT_GT(k.at("coupled_ticks").get<std::uint64_t>(), 1000u);
      std::printf(
          "[ figures  ] %s: instances apart %.3f mm on average, %.2f mm at most, divergent for %llu ticks; "
          "period p99 %.0f us; actuator %.1f mm from its path's end\n",
          p.at("user").get<std::string>().c_str(), k.at("mean_apart_mm").get<double>(),
          k.at("max_apart_mm").get<double>(), k.at("divergent_ticks").get<unsigned long long>(),
          c.at("period").at("p99_us").get<double>(), 1e3 * p.at("final_actuator_off_end_m").get<double>());
    }
    // the actuator moved along its path on every peer (1.30 m long)
    EXPECT_LT(p.at("final_actuator_off_end_m").get<double>(), 1.29);
  }
  // no two moving parts overlapped on any peer by more than a tenth of a voxel (2.5 mm)
  for (const nlohmann::json& o : j.at("exact_overlaps")) {
    EXPECT_LT(o.at("deepest_m").get<double>(), 0.00025) << o.dump();
  }
  std::printf("[ figures  ] the actuator %s; %zu samples in %.1f s\n",
              j.at("actuator_came_out").get<bool>() ? "came out" : "did not come out",
              j.at("samples").get<std::size_t>(), j.at("wall_s").get<double>());
}

}  // namespace
}  // namespace voxhap::test

// `voxhap bench`, run as the real executable: the list of benchmarks, bad names and
// options, and `table1 --quick` as JSON and CSV. Figures are checked for plausibility
// only; timings are never asserted (CONVENTIONS: machines are shared and noisy).

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/sanitizers.h"

namespace {

namespace fs = std::filesystem;
using voxhap::test::CliRun;
using voxhap::test::lineCount;
using voxhap::test::slurp;

constexpr const char* kTable1Keys[] = {"scenario",   "voxel_size_m",     "point_spacing_m",
                                       "voxelize_s", "load_s",           "dynamic_triangles",
                                       "points",     "static_triangles", "voxels"};

class BenchCommand : public voxhap::test::CliTest {};

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST_F(BenchCommand, IsListedByTheTopLevelHelp) {
  const CliRun r = voxhap({"--help"});
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_NE(r.out.find("bench"), std::string::npos) << r.out;
}

TEST_F(BenchCommand, HelpListsEveryBenchmark) {
  const CliRun r = voxhap({"bench", "--help"});
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_NE(r.out.find("\n  table1 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n  rotation "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n  extraction "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n  scaling "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n  error "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n  latency "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n  sharing "), std::string::npos) << r.out;
}

TEST_F(BenchCommand, UnknownNameExitsTwoListingTheValidNames) {
  const CliRun r = voxhap({"bench", "table9"});
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_NE(r.err.find("'table9'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("table1"), std::string::npos) << r.err;
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
}

TEST_F(BenchCommand, Table1RefusesSvgBeforeMeasuring) {
  const CliRun r = voxhap({"bench", "table1", "--svg", "t.svg"});
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_NE(r.err.find("--svg"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no curve"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "t.svg"));
}

TEST_F(BenchCommand, CsvIntoAMissingFolderFailsBeforeMeasuring) {
  const CliRun r = voxhap({"bench", "table1", "--quick", "--csv", "no/such/folder/t.csv"});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_NE(r.err.find("no/such/folder"), std::string::npos) << r.err;
}

// One run checks JSON, CSV and clean-up together: it voxelizes the landing gear, and
// CTest runs every test in its own process, so each run costs CI seconds. In Release only:
// under ASan it took 150 s, and the voxelizer, the cache and the bench table it runs are
// every one under ASan in tests of their own.
TEST_F(BenchCommand, Table1QuickPrintsPlausibleJsonWritesMatchingCsvAndCleansUp) {
  if (voxhap::test::kSanitizer) GTEST_SKIP() << "Release only (see the note above)";
  const CliRun run = voxhap({"bench", "table1", "--quick", "--json", "--csv", "table1.csv"});
  ASSERT_EQ(run.exitCode, 0) << run.err;

  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(run.out);  // exactly one document
  EXPECT_EQ(j.at("benchmark"), "table1");
  EXPECT_EQ(j.at("quick"), true);
  const nlohmann::ordered_json& rows = j.at("rows");
  ASSERT_EQ(rows.size(), 2u) << j.dump(2);
  EXPECT_EQ(rows[0].at("scenario"), "ball-and-socket");
  EXPECT_EQ(rows[1].at("scenario"), "landing-gear");
  for (const nlohmann::ordered_json& row : rows) {
    ASSERT_EQ(row.size(), std::size(kTable1Keys)) << row.dump();
    std::size_t k = 0;
    for (const auto& [key, value] : row.items()) EXPECT_EQ(key, kTable1Keys[k++]);  // order fixed
    for (const char* key : {"voxel_size_m", "point_spacing_m", "voxelize_s", "load_s"}) {
      ASSERT_TRUE(row.at(key).is_number()) << key << ": " << row.dump();
      EXPECT_GT(row.at(key).get<double>(), 0.0) << key;
    }
    for (const char* key : {"dynamic_triangles", "points", "static_triangles", "voxels"}) {
      ASSERT_TRUE(row.at(key).is_number_integer()) << key << ": " << row.dump();
      EXPECT_GT(row.at(key).get<std::int64_t>(), 0) << key;
    }
    // the environment's voxels fill its volume and surroundings, the points cover the
    // dynamic object's surface: both outnumber the triangles
    EXPECT_GT(row.at("voxels").get<std::int64_t>(), row.at("static_triangles").get<std::int64_t>());
    EXPECT_GT(row.at("points").get<std::int64_t>(), row.at("dynamic_triangles").get<std::int64_t>());
  }
  // the ball: 2048 triangles, radius 25 mm, one point per surface voxel of 0.35 mm
  EXPECT_EQ(rows[0].at("dynamic_triangles"), 2048);
  EXPECT_DOUBLE_EQ(rows[0].at("voxel_size_m").get<double>(), 0.35e-3);
  const double ballAreaInVoxelFaces = 4.0 * 3.14159265358979 * 25.0 * 25.0 / (0.35 * 0.35);
  EXPECT_GT(rows[0].at("points").get<double>(), ballAreaInVoxelFaces);
  EXPECT_LT(rows[0].at("points").get<double>(), 3.0 * ballAreaInVoxelFaces);
  EXPECT_DOUBLE_EQ(rows[1].at("voxel_size_m").get<double>(), 2.5e-3);
  EXPECT_DOUBLE_EQ(rows[1].at("point_spacing_m").get<double>(), 1.0e-3);
  EXPECT_GT(rows[1].at("static_triangles").get<std::int64_t>(), 1'000'000);

  const std::vector<std::string> lines = splitLines(slurp(dir_ / "table1.csv"));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(
      lines[0],
      "scenario,voxel_size_m,point_spacing_m,voxelize_s,load_s,dynamic_triangles,points,static_triangles,"
      "voxels");
  EXPECT_EQ(lines[1].rfind("ball-and-socket,0.00035,0.00035,", 0), 0u) << lines[1];
  EXPECT_EQ(lines[2].rfind("landing-gear,0.0025,0.001,", 0), 0u) << lines[2];
  for (std::size_t r = 0; r < 2; ++r) {
    const std::string points = std::to_string(rows[r].at("points").get<std::int64_t>());
    EXPECT_NE(lines[r + 1].find("," + points + ","), std::string::npos) << lines[r + 1];
  }

  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir_ / "cache" / "voxels", ec)) {
    EXPECT_NE(entry.path().filename().string().rfind("bench-table1-", 0), 0u) << entry.path();
  }
}

TEST_F(BenchCommand, RotationTurnsTheBallAtItsLimitWhenCapacityIsAmple) {
  const CliRun r = voxhap({"bench", "rotation", "--voxel-size", "2mm", "--capacity", "1000000", "--json"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = nlohmann::json::parse(r.out).at("rows");
  ASSERT_EQ(rows.size(), 2u);  // the paper's 25 mm ball and the 12.5 mm one
  EXPECT_EQ(rows[0].at("scene"), "ball-and-socket");
  EXPECT_EQ(rows[1].at("scene"), "small-ball-and-socket");
  EXPECT_NEAR(rows[0].at("ball_radius_m").get<double>(), 0.025, 1e-6);
  EXPECT_NEAR(rows[1].at("ball_radius_m").get<double>(), 0.0125, 1e-6);
  for (const auto& row : rows) {
    for (const char* key :
         {"voxel_size_m", "points", "rotation_s", "limit_s", "mean_contacts", "missed_deadlines"}) {
      EXPECT_TRUE(row.contains(key)) << key;
    }
    EXPECT_EQ(row.at("missed_deadlines"), 0);
    // frictionless: the ball keeps up with a handle that leads it, at MaxTravel all the way
    const double limitFrames = row.at("limit_s").get<double>() / 1e-3;
    EXPECT_NEAR(row.at("frames").get<double>(), limitFrames, 0.05 * limitFrames);
    EXPECT_GE(row.at("rotation_s").get<double>(), row.at("limit_s").get<double>() * 0.99);
    EXPECT_GT(row.at("mean_contacts").get<double>(), 0.0);
    // the fixed capacity, and the contacts among the mandatory tests
    EXPECT_DOUBLE_EQ(row.at("mean_capacity").get<double>(), 1e6);
    EXPECT_GE(row.at("mean_mandatory").get<double>(), row.at("mean_contacts").get<double>());
    EXPECT_LT(row.at("mean_mandatory").get<double>(), 1e6);
    // seated as a mating pair: its own force layer, the surface voxels, and points a voxel inward
    EXPECT_EQ(row.at("force_layer"), 2);
    EXPECT_DOUBLE_EQ(row.at("point_offset_m").get<double>(), -0.002);
    EXPECT_LT(row.at("max_centre_drift_m").get<double>(), 0.25 * 0.002);
    EXPECT_LT(row.at("max_penetration_m").get<double>(), 0.5 * 0.002);
  }
  // the turn's limit goes with the lever arm: half the radius, about half the time
  EXPECT_NEAR(rows[1].at("limit_s").get<double>() / rows[0].at("limit_s").get<double>(), 0.5, 0.05);
}

TEST_F(BenchCommand, RotationWithTooSmallACapacityMissesEveryDeadlineButStillTurns) {
  const CliRun r = voxhap({"bench", "rotation", "--voxel-size", "2mm", "--capacity", "1", "--json"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto row = nlohmann::json::parse(r.out).at("rows").at(0);
  // every frame is short of capacity: the first stops the ball, the rest abandon
  // time-criticality and turn it at full MaxTravel
  EXPECT_EQ(row.at("missed_deadlines"), row.at("frames"));
  EXPECT_DOUBLE_EQ(row.at("mean_capacity").get<double>(), 1.0);
  EXPECT_GT(row.at("mean_mandatory").get<double>(), 1.0);
  EXPECT_FALSE(row.at("rotation_s").is_null());
  const double limitFrames = row.at("limit_s").get<double>() / 1e-3;
  EXPECT_NEAR(row.at("frames").get<double>(), limitFrames, 0.05 * limitFrames + 1);
}

constexpr const char* kScalingKeys[] = {"points",
                                        "voxel_size_m",
                                        "static_voxel_size_m",
                                        "frames",
                                        "compute_p50_us",
                                        "compute_p99_us",
                                        "compute_p999_us",
                                        "compute_max_us",
                                        "missed_deadlines",
                                        "frames_over_budget",
                                        "mean_tested",
                                        "mean_contacts",
                                        "max_contacts",
                                        "mean_travel_scale",
                                        "mean_max_travel_m",
                                        "brute_frames",
                                        "brute_p50_us",
                                        "speedup",
                                        "build_s"};

// --quick: 10^4 and 10^5 points, 1 s of frames each; a fixed capacity keeps it
// deterministic in what it tests (not in its timings)
TEST_F(BenchCommand, ScalingQuickMeasuresTwoShellSizesCoherentAndBruteForce) {
  const CliRun r =
      voxhap({"bench", "scaling", "--quick", "--capacity", "1000000", "--json", "--svg", "s.svg"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(r.out);
  EXPECT_EQ(j.at("benchmark"), "scaling");
  const nlohmann::ordered_json& rows = j.at("rows");
  ASSERT_EQ(rows.size(), 2u) << j.dump(2);
  for (const nlohmann::ordered_json& row : rows) {
    ASSERT_EQ(row.size(), std::size(kScalingKeys)) << row.dump();
    std::size_t k = 0;
    for (const auto& [key, value] : row.items()) {
      EXPECT_EQ(key, kScalingKeys[k++]);
      EXPECT_TRUE(value.is_number()) << key << ": " << row.dump();
    }
    EXPECT_EQ(row.at("frames"), 1000);
    EXPECT_EQ(row.at("missed_deadlines"), 0) << "the capacity is ample";
    EXPECT_GT(row.at("mean_contacts").get<double>(), 0.0) << "the tile is pressed onto the plate";
    EXPECT_GT(row.at("mean_tested").get<double>(), 0.0);
    EXPECT_LE(row.at("mean_travel_scale").get<double>(), 1.0);
    EXPECT_GE(row.at("compute_p99_us").get<double>(), row.at("compute_p50_us").get<double>());
    EXPECT_GE(row.at("compute_max_us").get<double>(), row.at("compute_p999_us").get<double>());
    EXPECT_GT(row.at("brute_p50_us").get<double>(), 0.0);
  }
  // the counts aimed at, within the edges' extra points
  EXPECT_NEAR(rows[0].at("points").get<double>(), 1e4, 0.1e4);
  EXPECT_NEAR(rows[1].at("points").get<double>(), 1e5, 0.1e5);
  EXPECT_GT(rows[0].at("voxel_size_m").get<double>(), rows[1].at("voxel_size_m").get<double>());
  EXPECT_NE(slurp(dir_ / "s.svg").find("<svg"), std::string::npos);
}

constexpr const char* kErrorKeys[] = {
    "scene",           "contact",  "voxel_size_m",   "bits",   "awareness",       "coherence",
    "point_spacing_m", "points",   "compute_p50_us", "gap_m",  "force_angle_deg", "abs_gap_m",
    "gap_over_voxel",  "contacts", "speed_mps",      "drop_m", "missed_deadlines"};

TEST_F(BenchCommand, ErrorQuickRestsSphereAndBoxOnThePlaneNearTheForceLayer) {
  const CliRun r = voxhap({"bench", "error", "--quick", "--json", "--csv", "e.csv", "--svg", "e.svg"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(r.out);
  EXPECT_EQ(j.at("benchmark"), "error");
  const nlohmann::ordered_json& rows = j.at("rows");
  ASSERT_EQ(rows.size(), 8u) << j.dump(2);
  for (const nlohmann::ordered_json& row : rows) {
    ASSERT_EQ(row.size(), std::size(kErrorKeys)) << row.dump();
    std::size_t k = 0;
    for (const auto& [key, value] : row.items()) EXPECT_EQ(key, kErrorKeys[k++]);
    EXPECT_EQ(row.at("bits"), 4);
    EXPECT_EQ(row.at("awareness"), 1);
    EXPECT_DOUBLE_EQ(row.at("voxel_size_m").get<double>(), 2e-3);
    EXPECT_DOUBLE_EQ(row.at("point_spacing_m").get<double>(), 2e-3);
    // at rest on the plane: clear of it, by no more than the force layer's reach
    ASSERT_TRUE(row.at("gap_m").is_number()) << row.dump();
    EXPECT_GT(row.at("gap_m").get<double>(), 0.0) << row.dump();
    EXPECT_LT(row.at("gap_m").get<double>(), 3.0 * 2e-3) << row.dump();
    // the contacts carry the weight straight up
    ASSERT_TRUE(row.at("force_angle_deg").is_number()) << row.dump();
    EXPECT_LT(row.at("force_angle_deg").get<double>(), 5.0) << row.dump();
    EXPECT_GT(row.at("points").get<std::int64_t>(), 0);
    // dropped from 3 voxels above touching: what it fell and the exact gap left make those 3
    EXPECT_NEAR(row.at("drop_m").get<double>() + row.at("gap_m").get<double>(), 3.0 * 2e-3, 0.1e-3)
        << row.dump();
  }
  EXPECT_EQ(rows[0].at("scene"), "sphere-on-plane");
  EXPECT_EQ(rows[0].at("contact"), "paper");
  EXPECT_EQ(rows[0].at("coherence"), 1);
  EXPECT_EQ(rows[1].at("coherence"), 0);
  EXPECT_EQ(rows[2].at("contact"), "surface");
  EXPECT_EQ(rows[4].at("scene"), "box-on-plane");
  // contact finer than a voxel rests the parts closer than the voxels' planes do
  for (const std::size_t paper : {0u, 4u})
    EXPECT_LT(rows[paper + 2].at("gap_m").get<double>(), rows[paper].at("gap_m").get<double>());
  EXPECT_EQ(lineCount(slurp(dir_ / "e.csv")), 9);
  EXPECT_NE(slurp(dir_ / "e.svg").find("surface"), std::string::npos);
}

// Issue 13's rest-gap target for contact finer than a voxel, with points half a voxel apart.
TEST_F(BenchCommand, ErrorWithTwoPointsPerVoxelRestsSurfaceContactWithinAQuarterVoxel) {
  const CliRun r =
      voxhap({"bench", "error", "--scene", "sphere-on-plane", "--scene", "box-on-plane", "--voxel-size",
              "1mm", "--bits", "4", "--contact", "surface", "--points-per-voxel", "2", "--json"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::ordered_json rows = nlohmann::ordered_json::parse(r.out).at("rows");
  ASSERT_EQ(rows.size(), 8u);  // two scenes, awareness on and off, coherence on and off
  for (const nlohmann::ordered_json& row : rows) {
    EXPECT_DOUBLE_EQ(row.at("point_spacing_m").get<double>(), 0.5e-3);
    ASSERT_TRUE(row.at("gap_m").is_number()) << row.dump();
    EXPECT_GT(row.at("gap_m").get<double>(), 0.0) << row.dump();
    EXPECT_LE(row.at("gap_over_voxel").get<double>(), 0.25) << row.dump();
  }
}

TEST_F(BenchCommand, ErrorRefusesAnUnknownSceneOrBitWidthBeforeMeasuring) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"bench", "error", "--scene", "teapot"},
        std::vector<std::string>{"bench", "error", "--bits", "3"},
        std::vector<std::string>{"bench", "error", "--contact", "exact"},
        std::vector<std::string>{"bench", "error", "--points-per-voxel", "5"}}) {
    const CliRun r = voxhap(args);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

TEST_F(BenchCommand, LatencyTimesEveryHandleMoveBackToTheClient) {
  const CliRun run = voxhap({"bench", "latency", "--samples", "20", "--no-realtime", "--json"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(run.out);
  EXPECT_EQ(j.at("benchmark"), "latency");
  const nlohmann::ordered_json& row = j.at("rows").at(0);
  EXPECT_EQ(row.at("samples"), 20);
  EXPECT_EQ(row.at("lost"), 0);  // each move came back within a second
  EXPECT_GT(row.at("latency_p50_us").get<double>(), 0.0);
  EXPECT_LE(row.at("latency_p50_us").get<double>(), row.at("latency_max_us").get<double>());
  EXPECT_EQ(row.at("sched_fifo"), "no");
  EXPECT_EQ(voxhap({"bench", "latency", "--samples", "3"}).exitCode, 2);
}

TEST_F(BenchCommand, SharingFollowsWithoutDelayNotAtASecondAndStaysStable) {
  const CliRun run = voxhap({"bench", "sharing", "--quick", "--json"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(run.out);
  EXPECT_EQ(j.at("benchmark"), "sharing");
  std::size_t delayRows = 0, bandwidthRows = 0;
  for (const nlohmann::ordered_json& row : j.at("rows")) {
    SCOPED_TRACE(row.dump());
    const double oneWayMs = row.at("one_way_ms").get<double>();
    const double gain = row.at("gain").get<double>();
    if (row.at("sweep") == "delay") {
      ++delayRows;
      // a 10 mm drag at 0.2 Hz: followed closely over a fast link (a spring of ω_n 8 rad/s
      // behind states 30-80 ms old), not at all once the mean delay passes 1 s (k(τ) = 0)
      if (oneWayMs == 0.0) {
        EXPECT_GT(gain, 0.8);
        EXPECT_LT(row.at("tracking_rms_m").get<double>(), 0.004);
      }
      if (oneWayMs == 1000.0) {
        EXPECT_LT(gain, 0.01);
      }
      // let go, the pair's relative energy does not grow, with the controller or without
      EXPECT_EQ(row.at("stable"), "yes");
    } else {
      ++bandwidthRows;
      EXPECT_EQ(row.at("sweep"), "bandwidth");
      EXPECT_GE(gain, 0.0);
    }
  }
  EXPECT_EQ(delayRows, 6u);  // 0, 300 and 1000 ms, each with the controller and without
  EXPECT_EQ(bandwidthRows, 6u);
  EXPECT_EQ(voxhap({"bench", "sharing", "--loss", "1"}).exitCode, 2);
}

}  // namespace

namespace {

constexpr const char* kExtractionKeys[] = {"voxel_size_m",
                                           "point_spacing_m",
                                           "points",
                                           "frames",
                                           "completion_s",
                                           "wall_s",
                                           "frames_over_budget",
                                           "missed_deadlines",
                                           "compute_p50_us",
                                           "compute_p99_us",
                                           "compute_max_us",
                                           "max_contacts",
                                           "max_penetration_m",
                                           "exact_wall_s",
                                           "mean_travel_scale",
                                           "actuator_progress_m",
                                           "path_length_m",
                                           "error"};

// The landing gear takes minutes to generate and voxelize in a fresh cache: the quick row
// runs on the committed peg-in-hole scene instead (the peg lifted out of its hole), which
// exercises the same benchmark code and output.
TEST_F(BenchCommand, ExtractionQuickPrintsOneRowWithEveryKey) {
  { std::ofstream(dir_ / "lift.txt") << "0 1 0 0 0 0 0 0\n0.15 1 0 0 0 0 0 0.04\n0.25 1 0 0 0 0 0 0.04\n"; }
  const CliRun run = voxhap({"bench", "extraction", "--quick", "--scene", asset("peg-in-hole.glb"), "--move",
                             "peg", "--script", (dir_ / "lift.txt").string(), "--json"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(run.out);
  EXPECT_EQ(j.at("benchmark"), "extraction");
  EXPECT_EQ(j.at("quick"), true);
  EXPECT_EQ(j.at("coherence"), true);
  const nlohmann::ordered_json& rows = j.at("rows");
  ASSERT_EQ(rows.size(), 1u) << j.dump(2);
  const nlohmann::ordered_json& row = rows[0];
  ASSERT_EQ(row.size(), std::size(kExtractionKeys)) << row.dump();
  std::size_t k = 0;
  for (const auto& [key, value] : row.items()) EXPECT_EQ(key, kExtractionKeys[k++]);  // order fixed
  EXPECT_DOUBLE_EQ(row.at("voxel_size_m").get<double>(), 2.5e-3);
  EXPECT_DOUBLE_EQ(row.at("point_spacing_m").get<double>(), 1.0e-3);
  EXPECT_EQ(row.at("frames"), 250);
  EXPECT_GT(row.at("points").get<std::int64_t>(), 0);
  EXPECT_TRUE(row.at("completion_s").is_number()) << row.dump();  // 40 mm up: beyond the 20 mm field
  for (const char* key : {"wall_s", "compute_p50_us", "compute_p99_us", "compute_max_us"}) {
    EXPECT_GT(row.at(key).get<double>(), 0.0) << key;
  }
  EXPECT_LE(row.at("compute_p50_us").get<double>(), row.at("compute_max_us").get<double>());
  EXPECT_GE(row.at("max_penetration_m").get<double>(), 0.0);
  EXPECT_GT(row.at("exact_wall_s").get<double>(), 0.0);
  EXPECT_LT(row.at("exact_wall_s").get<double>(), row.at("wall_s").get<double>());
  EXPECT_TRUE(row.at("error").is_null()) << row.dump();
}

}  // namespace

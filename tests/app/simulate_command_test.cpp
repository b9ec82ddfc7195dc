#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/gltf_fixtures.h"

namespace voxhap::test {
namespace {

class SimulateCommand : public CliTest {
protected:
  std::string writeScript(const std::string& text) const {
    const std::filesystem::path file = dir_ / "script.txt";
    std::ofstream(file) << text;
    return file.string();
  }
};

TEST_F(SimulateCommand, BallTurnsInItsSocketWritesTheTraceAndASummary) {
  const std::string script = writeScript("# a small turn\n0 1 0 0 0 0 0 0\n0.05 0.9998 0.02 0 0 0 0 0\n");
  const CliRun r = voxhap({"simulate", asset("ball-and-socket.glb"), "--move", "ball", "--script", script,
                           "--voxel-size", "1mm", "--point-offset=-0.5mm", "--trace", "trace.csv", "--json"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["frames"], 50);
  EXPECT_GT(summary["max_contacts"].get<int>(), 0);
  for (const char* key : {"p50", "p99", "max"}) EXPECT_TRUE(summary["compute_us"].contains(key)) << key;
  std::ifstream trace(dir_ / "trace.csv");
  std::string header;
  std::getline(trace, header);
  EXPECT_EQ(header,
            "frame,t_s,object,qw,qx,qy,qz,tx,ty,tz,fx,fy,fz,taux,tauy,tauz,contacts,tested,max_travel_m,"
            "compute_us");
  int rows = 0;
  for (std::string line; std::getline(trace, line);) ++rows;
  EXPECT_EQ(rows, 50);
}

TEST_F(SimulateCommand, AFixedCapacityRepeatsAndBruteForceTestsEveryPoint) {
  const std::string script = writeScript("0 1 0 0 0 0 0 0\n0.03 0.9998 0.02 0 0 0 0 0\n");
  auto run = [&](const std::string& mode) {
    std::vector<std::string> args = {
        "simulate", asset("ball-and-socket.glb"), "--move", "ball", "--script", script, "--voxel-size",
        "1mm",      "--point-offset=-0.5mm",      "--json", mode};
    const CliRun r = voxhap(args);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const auto fixed = run("--capacity=5000");
  EXPECT_EQ(fixed["coherence"], true);
  EXPECT_LT(fixed["mean_tested"].get<double>(), run("--brute-force")["mean_tested"].get<double>());
  for (const char* key : {"missed_deadlines", "frames_over_budget", "mean_travel_scale", "mean_contacts"}) {
    EXPECT_TRUE(fixed.contains(key)) << key;
  }
  const CliRun bad = voxhap(
      {"simulate", asset("ball-and-socket.glb"), "--move", "ball", "--script", script, "--capacity", "0"});
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("capacity"), std::string::npos) << bad.err;
}

TEST_F(SimulateCommand, MalformedScriptNamesFileAndLine) {
  const std::string script = writeScript("0 1 0 0 0 0 0 0\n0.1 1 0 0 0 0 0\n");
  const CliRun r = voxhap({"simulate", asset("ball-and-socket.glb"), "--move", "ball", "--script", script});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("script.txt:2"), std::string::npos) << r.err;
}

TEST_F(SimulateCommand, UnknownObjectIsNamed) {
  const std::string script = writeScript("0 1 0 0 0 0 0 0\n");
  const CliRun r = voxhap({"simulate", asset("ball-and-socket.glb"), "--move", "wrench", "--script", script});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("wrench"), std::string::npos) << r.err;
}

TEST_F(SimulateCommand, MovesAGroupOfACadFileAsOneObject) {
  // the piston (crown and pin, a group without extras) pushed 1 mm along x over the block
  const std::string file = writeDoc(pistonAssemblyDoc(), dir_, "piston", BufferStorage::Glb).string();
  const std::string script = writeScript("0 1 0 0 0 0 0 0\n0.05 1 0 0 0 0.001 0 0\n");
  const CliRun r = voxhap({"simulate", file, "--move", "piston", "--script", script, "--voxel-size", "1mm",
                           "--trace", "trace.csv", "--json"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["moving"], nlohmann::json::array({"piston"}));
  EXPECT_EQ(summary["frames"], 50);
  // one trace row a frame: crown and pin are one body with one pose, which follows the handle
  std::ifstream trace(dir_ / "trace.csv");
  std::string line;
  std::getline(trace, line);
  int rows = 0;
  double lastTxM = 0.0;
  for (; std::getline(trace, line); ++rows) {
    std::vector<std::string> fields;
    std::stringstream row(line);
    for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
    ASSERT_GE(fields.size(), 10u) << line;
    EXPECT_EQ(fields[2], "piston") << line;
    lastTxM = std::stod(fields[7]);
  }
  EXPECT_EQ(rows, 50);
  EXPECT_GT(lastTxM, 0.0005);  // the coupling lags the handle a little
  EXPECT_LT(lastTxM, 0.0011);
}

TEST_F(SimulateCommand, GroupMistakesAreNamed) {
  const std::string file = writeDoc(pistonAssemblyDoc(), dir_, "piston", BufferStorage::Glb).string();
  const std::string script = writeScript("0 1 0 0 0 0 0 0\n");
  CliRun r = voxhap({"simulate", file, "--move", "piston", "--move", "pin", "--script", script});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("'piston' and 'pin' both hold object 'pin'"), std::string::npos) << r.err;
  r = voxhap({"simulate", file, "--move", "engine", "--script", script});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("objects: crown, pin, block; groups: piston (crown, pin)"), std::string::npos)
      << r.err;
}

TEST_F(SimulateCommand, BadVoxelSizeIsAUsageError) {
  const std::string script = writeScript("0 1 0 0 0 0 0 0\n");
  const CliRun r = voxhap({"simulate", asset("ball-and-socket.glb"), "--move", "ball", "--script", script,
                           "--voxel-size", "-1mm"});
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("voxel-size"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace voxhap::test

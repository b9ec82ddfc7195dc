// Runs the real `voxhap` executable and checks exit codes, stdout and stderr.

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/gltf_fixtures.h"

namespace {

namespace fs = std::filesystem;
using voxhap::test::CliRun;
using voxhap::test::lineCount;
using voxhap::test::slurp;

class VoxhapCli : public voxhap::test::CliTest {};

TEST_F(VoxhapCli, HelpListsOnlyWorkingCommandsAndExitsZero) {
  const CliRun r = voxhap({"--help"});
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_NE(r.out.find("scene"), std::string::npos);
  EXPECT_NE(r.out.find("demo"), std::string::npos);
  EXPECT_NE(r.out.find("simulate"), std::string::npos);
  EXPECT_NE(r.out.find("bench"), std::string::npos);
  EXPECT_NE(r.out.find("controller"), std::string::npos);
  EXPECT_NE(r.out.find("relay"), std::string::npos);
  EXPECT_NE(r.out.find("peer"), std::string::npos);
}

TEST_F(VoxhapCli, EveryCommandHasHelp) {
  for (const auto& args : std::vector<std::vector<std::string>>{{"scene", "--help"},
                                                                {"scene", "info", "--help"},
                                                                {"scene", "generate", "--help"},
                                                                {"demo", "--help"},
                                                                {"controller", "--help"},
                                                                {"relay", "--help"},
                                                                {"peer", "--help"},
                                                                {"voxelize", "--help"},
                                                                {"simulate", "--help"},
                                                                {"bench", "--help"},
                                                                {"bench", "table1", "--help"},
                                                                {"bench", "extraction", "--help"}}) {
    const CliRun r = voxhap(args);
    EXPECT_EQ(r.exitCode, 0) << args[0];
    EXPECT_NE(r.out.find("Usage: voxhap"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("Examples"), std::string::npos) << r.out;
  }
}

TEST_F(VoxhapCli, UsageMistakesExitTwoWithOneLine) {
  for (const auto& args :
       std::vector<std::vector<std::string>>{{},
                                             {"fly"},
                                             {"scene", "info"},
                                             {"scene", "info", "a", "b"},
                                             {"scene", "info", "--bogus", "x"},
                                             {"scene", "generate", "landing-gear", "--seed", "-3"}}) {
    const CliRun r = voxhap(args);
    EXPECT_EQ(r.exitCode, 2) << (args.empty() ? "" : args[0]);
    if (!args.empty()) {
      EXPECT_EQ(lineCount(r.err), 1) << r.err;
      EXPECT_EQ(r.err.rfind("voxhap: error: ", 0), 0u) << r.err;
    }
  }
}

TEST_F(VoxhapCli, UsageMistakesNameTheCommandAndTheOption) {
  for (const auto& [args, named] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"scene", "info", "--bogus", "x"}, "voxhap scene info: unknown option '--bogus'"},
           {{"scene", "generate", "landing-gear", "--seed", "-3"}, "voxhap scene generate: --seed wants"},
           {{"scene", "generate", "landing-gear", "--seed"}, "voxhap scene generate: --seed"},
           {{"scene", "info", "x", "--json=yes"}, "voxhap scene info: --json takes no value"},
           {{"bench", "table1", "extra"}, "voxhap bench table1: takes no arguments, got 'extra'"},
           {{"bench", "rotation", "--voxel-size", "1cm"}, "voxhap bench rotation: --voxel-size wants"},
           {{"demo", "--capacity=0"}, "voxhap demo: --capacity wants at least one point test"}}) {
    const CliRun r = voxhap(args);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(named), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("(see --help)"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

TEST_F(VoxhapCli, HelpComesBeforeTheValuesAreChecked) {
  const CliRun r = voxhap({"demo", "--voxel-size", "0mm", "--help"});
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.out.rfind("Usage: voxhap demo", 0), 0u) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST_F(VoxhapCli, GroupWithoutItsCommandPrintsItsHelpAndExitsTwo) {
  const CliRun r = voxhap({"scene"});
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_EQ(r.out.rfind("Usage: voxhap scene", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("\n  generate "), std::string::npos) << r.out;
}

TEST_F(VoxhapCli, MissingFileExitsOneNamingIt) {
  const CliRun r = voxhap({"scene", "info", "no-such-scene.glb"});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("no-such-scene.glb"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST_F(VoxhapCli, BadFileExitsOneWithOneLine) {
  std::ofstream(dir_ / "junk.glb") << "this is not a glTF file";
  const CliRun r = voxhap({"scene", "info", "junk.glb"});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("junk.glb"), std::string::npos);
  EXPECT_NE(r.err.find("not a glTF file"), std::string::npos) << r.err;
}

TEST_F(VoxhapCli, SceneInfoJsonIsOneDocumentWithTheFigures) {
  const CliRun r = voxhap({"scene", "info", asset("ball-and-socket.glb"), "--json"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);  // throws unless exactly one document
  EXPECT_EQ(j["objects_count"], 2);
  EXPECT_EQ(j["dynamic_triangles"], 2048);
  bool sawBall = false;
  for (const auto& object : j["objects"]) {
    EXPECT_TRUE(object["closed"].get<bool>()) << object["name"];
    EXPECT_TRUE(object["consistently_oriented"].get<bool>()) << object["name"];
    if (object["name"] == "ball") {
      sawBall = true;
      EXPECT_EQ(object["role"], "dynamic");
      EXPECT_NEAR(object["bounds_m"]["extent"][0].get<double>(), 0.050, 1e-4);
    }
  }
  EXPECT_TRUE(sawBall);
}

TEST_F(VoxhapCli, SceneInfoListsTheGroupsThatCanBeMoved) {
  using voxhap::test::BufferStorage;
  const fs::path file =
      voxhap::test::writeDoc(voxhap::test::pistonAssemblyDoc(), dir_, "piston", BufferStorage::Glb);
  const CliRun json = voxhap({"scene", "info", file.string(), "--json"});
  ASSERT_EQ(json.exitCode, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["objects_count"], 3);
  EXPECT_EQ(j["groups_count"], 1);
  ASSERT_EQ(j["groups"].size(), 1u);
  const nlohmann::json& group = j["groups"][0];
  EXPECT_EQ(group["name"], "piston");
  EXPECT_EQ(group["objects"], nlohmann::json::array({"crown", "pin"}));
  EXPECT_EQ(group["parts"], 2);
  EXPECT_EQ(group["triangles"], 24);
  EXPECT_EQ(group["movable"], true);
  EXPECT_NEAR(group["bounds_m"]["extent"][0].get<double>(), 0.015, 1e-6);

  const CliRun text = voxhap({"scene", "info", file.string()});
  ASSERT_EQ(text.exitCode, 0) << text.err;
  EXPECT_NE(text.out.find("groups     1"), std::string::npos) << text.out;
  bool sawGroupRow = false;
  std::istringstream lines(text.out);
  for (std::string line; std::getline(lines, line);) {
    sawGroupRow =
        sawGroupRow || (line.rfind("piston ", 0) == 0 && line.find("crown, pin") != std::string::npos);
  }
  EXPECT_TRUE(sawGroupRow) << text.out;
}

TEST_F(VoxhapCli, BuiltinNameResolvesToTheCommittedAsset) {
  const CliRun byName = voxhap({"scene", "info", "peg-in-hole", "--json"});
  const CliRun byFile = voxhap({"scene", "info", asset("peg-in-hole.glb"), "--json"});
  ASSERT_EQ(byName.exitCode, 0) << byName.err;
  ASSERT_EQ(byFile.exitCode, 0) << byFile.err;
  EXPECT_EQ(nlohmann::json::parse(byName.out)["objects"], nlohmann::json::parse(byFile.out)["objects"]);
}

TEST_F(VoxhapCli, GeneratedSmallScenesEqualTheCommittedAssets) {
  for (const std::string name : {"ball-and-socket", "peg-in-hole"}) {
    const CliRun r = voxhap({"scene", "generate", name, "-o", "out.glb"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(slurp(dir_ / "out.glb"), slurp(asset(name + ".glb")))
        << name << ": regenerate the asset with `voxhap scene generate " << name << " -o assets/" << name
        << ".glb`";
  }
}

TEST_F(VoxhapCli, UnknownBuiltinSceneListsTheKnownOnes) {
  const CliRun r = voxhap({"scene", "generate", "space-station"});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("landing-gear"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "space-station.glb"));
}

TEST_F(VoxhapCli, WarningsGoToStderrAndQuietSilencesThem) {
  // a glTF whose only mesh is open: one triangle
  std::ofstream(dir_ / "open.gltf") << R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],
    "nodes":[{"name":"sheet","mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],
    "bufferViews":[{"buffer":0,"byteLength":36}],
    "buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})";
  const CliRun normal = voxhap({"scene", "info", "open.gltf", "--json"});
  ASSERT_EQ(normal.exitCode, 0) << normal.err;
  EXPECT_NE(normal.err.find("voxhap: warning: "), std::string::npos);
  EXPECT_NE(normal.err.find("'sheet' is open"), std::string::npos) << normal.err;
  EXPECT_FALSE(nlohmann::json::parse(normal.out)["objects"][0]["closed"].get<bool>());
  const CliRun quiet = voxhap({"scene", "info", "open.gltf", "-q"});
  EXPECT_EQ(quiet.exitCode, 0);
  EXPECT_TRUE(quiet.err.empty()) << quiet.err;
}

}  // namespace

namespace {

TEST_F(VoxhapCli, LandingGearIsGeneratedOnceThenCachedWithTheIssueFigures) {
  const CliRun first = voxhap({"scene", "info", "landing-gear", "--json"});
  ASSERT_EQ(first.exitCode, 0) << first.err;
  const nlohmann::json j = nlohmann::json::parse(first.out);
  const double staticTriangles = j["static_triangles"].get<double>();
  EXPECT_NEAR(staticTriangles, 2.7e6, 0.05 * 2.7e6);
  const auto& extent = j["bounds_m"]["extent"];
  EXPECT_NEAR(extent[0].get<double>(), 4.1, 0.03 * 4.1);
  EXPECT_NEAR(extent[1].get<double>(), 1.9, 0.03 * 1.9);
  EXPECT_NEAR(extent[2].get<double>(), 4.8, 0.03 * 4.8);
  int dynamicObjects = 0;
  for (const auto& object : j["objects"]) {
    EXPECT_TRUE(object["closed"].get<bool>()) << object["name"];
    EXPECT_TRUE(object["consistently_oriented"].get<bool>()) << object["name"];
    if (object["role"] != "dynamic") continue;
    ++dynamicObjects;
    EXPECT_EQ(object["name"], "actuator");
    EXPECT_NEAR(object["triangles"].get<double>(), 40000.0, 2000.0);
    EXPECT_GT(object["parts"].size(), 1u);
    std::vector<double> e;
    for (const auto& v : object["bounds_m"]["extent"]) e.push_back(v.get<double>());
    std::sort(e.begin(), e.end());
    EXPECT_NEAR(e[2], 0.9, 0.05 * 0.9);
    EXPECT_NEAR(e[1], 0.2, 0.05 * 0.2);
    EXPECT_NEAR(e[0], 0.2, 0.05 * 0.2);
  }
  EXPECT_EQ(dynamicObjects, 1);

  size_t cachedFiles = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir_ / "cache"))
    cachedFiles += entry.is_regular_file();
  EXPECT_EQ(cachedFiles, 1u);
  const CliRun second = voxhap({"scene", "info", "landing-gear", "--json", "-v"});
  ASSERT_EQ(second.exitCode, 0) << second.err;
  EXPECT_EQ(second.err.find("generated"), std::string::npos) << "the second run must use the cache";
  EXPECT_EQ(nlohmann::json::parse(second.out)["objects"], j["objects"]);
}

}  // namespace

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "haptics/coherence/pair_coherence.h"
#include "haptics/collide/tangent_plane_force.h"
#include "haptics/geometry/mesh_builder.h"
#include "haptics/scene/gltf_writer.h"
#include "support/cli_runner.h"
#include "support/contact_scenes.h"
#include "support/gltf_fixtures.h"
#include "support/helper_thread.h"

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

// --frame-helper: the same frames, bit for bit (the trace's every column but compute time).
TEST_F(SimulateCommand, AFrameHelperGivesTheSameTrace) {
  if (const char* why = noSpareCore()) GTEST_SKIP() << why;
  const std::string script = writeScript("0 1 0 0 0 0 0 0\n0.1 0.995 0.0998 0 0 0 0 0\n");
  auto traceOf = [&](const std::string& file, std::initializer_list<std::string> extra) {
    std::vector<std::string> args = {"simulate",
                                     asset("ball-and-socket.glb"),
                                     "--move",
                                     "ball",
                                     "--script",
                                     script,
                                     "--voxel-size",
                                     "1mm",
                                     "--point-offset=-0.5mm",  // pressed: forces in every frame
                                     "--capacity=5000",
                                     "--trace",
                                     file};
    args.insert(args.end(), extra);
    const CliRun r = voxhap(args);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    std::ifstream in(dir_ / file);
    std::vector<std::string> rows;
    for (std::string line; std::getline(in, line);) rows.push_back(line.substr(0, line.rfind(',')));
    return rows;
  };
  const std::vector<std::string> alone = traceOf("alone.csv", {});
  const std::vector<std::string> helped = traceOf("helped.csv", {"--frame-helper"});
  ASSERT_EQ(alone.size(), 101u);
  EXPECT_EQ(alone, helped);
  int shared = 0;  // frames whose tests and contact forces the helper shared
  for (std::size_t row = 1; row < alone.size(); ++row) {
    std::stringstream line(alone[row]);
    std::vector<std::string> fields;
    for (std::string field; std::getline(line, field, ',');) fields.push_back(field);
    ASSERT_GE(fields.size(), 18u);
    const bool pushed =
        std::stod(fields[10]) != 0.0 || std::stod(fields[11]) != 0.0 || std::stod(fields[12]) != 0.0;
    shared += pushed && std::stoul(fields[16]) >= kHalvedContacts &&
                      std::stoul(fields[17]) >= PairCoherence::kHelpedTests
                  ? 1
                  : 0;
  }
  EXPECT_GT(shared, 50);
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

TEST_F(SimulateCommand, CheckExactSeesAnEdgeCuttingIntoAFaceBetweenVertices) {
  // the plate (top face z = 0) and a 120 mm rod of square section turned 45° about its
  // axis, placed so that its lowest edge runs 0.3 mm below the top face across the whole
  // plate while its vertices are beyond the plate's sides: nothing a vertex check sees
  Scene scene;
  scene.sourceName = "edge";
  scene.objects.push_back(plate());
  scene.objects.push_back(meshObject("rod", ObjectRole::Dynamic, [](TriangleMesh& m) {
    appendBox(m,
              glm::translate(glm::dmat4(1.0), glm::dvec3(0.0013, 0.0021, 0.005 * std::sqrt(2.0) - 0.0003)) *
                  glm::rotate(glm::dmat4(1.0), glm::radians(45.0), glm::dvec3(1, 0, 0)),
              {0.06, 0.005, 0.005});
  }));
  writeGlbFile(scene, dir_ / "edge.glb");
  const std::string script = writeScript("0 1 0 0 0 0 0 0\n0.02 1 0 0 0 0 0 0\n");
  const CliRun r = voxhap({"simulate", (dir_ / "edge.glb").string(), "--move", "rod", "--script", script,
                           "--voxel-size", "1mm", "--capacity", "100000", "--check-exact", "--json"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& exact = j.at("exact_penetration");
  EXPECT_EQ(exact.at("checks"), 21);  // frame 0 and after each of the 20
  EXPECT_EQ(exact.at("every_frames"), 1);
  EXPECT_DOUBLE_EQ(exact.at("probe_spacing_m").get<double>(), 0.00025);
  // as placed, frame 0: the edge's depth exactly (the engine then pushes the rod out)
  EXPECT_NEAR(exact.at("max_depth_m").get<double>(), 0.0003, 1e-6) << exact.dump(2);
  EXPECT_NEAR(exact.at("max_depth_voxels").get<double>(), 0.3, 1e-3);
  EXPECT_EQ(exact.at("max_depth_frame"), 0);
  EXPECT_EQ(exact.at("max_depth_into"), "rod into static");
  EXPECT_NEAR(exact.at("max_depth_world_m")[2].get<double>(), -0.0003, 1e-6);
  EXPECT_GE(exact.at("frames_with_penetration").get<int>(), 1);
  EXPECT_GT(exact.at("exact_tests").get<double>(), 0.0);

  const CliRun text = voxhap({"simulate", (dir_ / "edge.glb").string(), "--move", "rod", "--script", script,
                              "--voxel-size", "1mm", "--capacity", "100000", "--check-exact-every", "5"});
  ASSERT_EQ(text.exitCode, 0) << text.err;
  EXPECT_NE(text.out.find("exact depth     0.300 mm (0.30 voxels of 1.000 mm) after frame 0"),
            std::string::npos)
      << text.out;
  EXPECT_NE(text.out.find("rod into static"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("exact checks    5 (frames 0, 5, 10, … and the last)"), std::string::npos)
      << text.out;
}

TEST_F(SimulateCommand, CheckExactMeasuresEveryPairOfMovingObjects) {
  // two moving objects over the plate, clear of it: a 20 mm cube and a post turned 45°
  // about z whose vertical edge is 0.4 mm into the cube's +x face, its ends above and
  // below the cube
  Scene scene;
  scene.sourceName = "pair";
  scene.objects.push_back(plate());
  const glm::dvec3 cubeCentre(0.0, 0.0, 0.030);
  scene.objects.push_back(meshObject("cube", ObjectRole::Dynamic, [&](TriangleMesh& m) {
    appendBox(m, glm::translate(glm::dmat4(1.0), cubeCentre), {0.01, 0.01, 0.01});
  }));
  scene.objects.push_back(meshObject("post", ObjectRole::Dynamic, [&](TriangleMesh& m) {
    appendBox(m,
              glm::translate(glm::dmat4(1.0),
                             cubeCentre + glm::dvec3(0.01 - 0.0004 + 0.01 * std::sqrt(2.0), 0.0017, 0.0009)) *
                  glm::rotate(glm::dmat4(1.0), glm::radians(45.0), glm::dvec3(0, 0, 1)),
              {0.01, 0.01, 0.02});
  }));
  writeGlbFile(scene, dir_ / "pair.glb");
  const std::string script = writeScript("0 1 0 0 0 0 0 0\n0.005 1 0 0 0 0 0 0\n");
  const CliRun r =
      voxhap({"simulate", (dir_ / "pair.glb").string(), "--move", "cube", "--move", "post", "--script",
              script, "--voxel-size", "1mm", "--capacity", "100000", "--check-exact", "--json"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto exact = nlohmann::json::parse(r.out).at("exact_penetration");
  EXPECT_EQ(exact.at("checks"), 6);
  EXPECT_NEAR(exact.at("max_depth_m").get<double>(), 0.0004, 1e-6) << exact.dump(2);
  EXPECT_EQ(exact.at("max_depth_frame"), 0);
  EXPECT_EQ(exact.at("max_depth_into"), "post into cube");
  EXPECT_NEAR(exact.at("max_depth_world_m")[0].get<double>(), 0.0096, 1e-6);
}

TEST_F(SimulateCommand, CheckExactEveryNFramesAndTheClearanceOfTheLiftedPeg) {
  // the peg starts 1 mm above the mouth of its hole and goes up: no penetration, the
  // clearance about that gap
  const std::string script = writeScript("0 1 0 0 0 0 0 0\n0.2 1 0 0 0 0 0 0.020\n");
  const CliRun r = voxhap({"simulate", asset("peg-in-hole.glb"), "--move", "peg", "--script", script,
                           "--voxel-size", "1mm", "--duration", "0.05", "--check-exact-every", "20",
                           "--probe-spacing", "0.5mm", "--json"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto exact = nlohmann::json::parse(r.out).at("exact_penetration");
  EXPECT_EQ(exact.at("checks"), 4);  // frames 0, 20, 40 and the last, 50
  EXPECT_EQ(exact.at("every_frames"), 20);
  EXPECT_DOUBLE_EQ(exact.at("probe_spacing_m").get<double>(), 0.0005);
  EXPECT_EQ(exact.at("max_depth_m").get<double>(), 0.0);
  EXPECT_TRUE(exact.at("max_depth_frame").is_null());
  EXPECT_TRUE(exact.at("max_depth_into").is_null());
  ASSERT_TRUE(exact.at("min_clearance_m").is_number()) << exact.dump(2);
  EXPECT_GT(exact.at("min_clearance_m").get<double>(), 0.0005);
  EXPECT_LT(exact.at("min_clearance_m").get<double>(), 0.0015);
  for (const char* key : {"probes", "near_probes", "exact_tests", "wall_s", "frames_with_penetration"}) {
    EXPECT_TRUE(exact.at(key).is_number()) << key;
  }
  // without the option there is no such object
  const CliRun plain = voxhap({"simulate", asset("peg-in-hole.glb"), "--move", "peg", "--script", script,
                               "--voxel-size", "1mm", "--duration", "0.01", "--json"});
  ASSERT_EQ(plain.exitCode, 0) << plain.err;
  EXPECT_FALSE(nlohmann::json::parse(plain.out).contains("exact_penetration"));
}

TEST_F(SimulateCommand, SurfaceContactLetsThePegComeCloserWithoutPenetration) {
  // the peg, 1 mm above the mouth of its hole (0.2 mm clearance a side, finer than these
  // voxels can seat), is pressed 3 mm down onto the mouth
  const std::string script = writeScript("0 1 0 0 0 0 0 0\n0.2 1 0 0 0 0 0 -0.003\n");
  auto run = [&](bool surface) {
    std::vector<std::string> args = {"simulate",
                                     asset("peg-in-hole.glb"),
                                     "--move",
                                     "peg",
                                     "--script",
                                     script,
                                     "--voxel-size",
                                     "1mm",
                                     "--point-spacing",
                                     "0.5mm",
                                     "--duration",
                                     "0.4",
                                     "--check-exact-every",
                                     "40",
                                     "--probe-spacing",
                                     "0.25mm",
                                     "--json"};
    args.push_back(surface ? "--surface-contact" : "--paper-contact");
    const CliRun r = voxhap(args);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return nlohmann::json::parse(r.out).at("exact_penetration");
  };
  const auto voxelPlanes = run(false);
  const auto surfacePlanes = run(true);
  EXPECT_EQ(surfacePlanes.at("max_depth_m").get<double>(), 0.0) << surfacePlanes.dump(2);
  EXPECT_EQ(voxelPlanes.at("max_depth_m").get<double>(), 0.0) << voxelPlanes.dump(2);
  // on the mouth's edge: within half a voxel (0.40 mm measured; L/2 = 0.19 mm on a face,
  // more at an edge, whose planes lie inside its rounded distance), where the voxel planes
  // hold it more than a voxel off
  EXPECT_LT(surfacePlanes.at("min_clearance_m").get<double>(), 0.0005) << surfacePlanes.dump(2);
  EXPECT_GT(voxelPlanes.at("min_clearance_m").get<double>(), 0.001) << voxelPlanes.dump(2);
}

TEST_F(SimulateCommand, PointsInAFreeLayerAreRefusedWithSurfaceContactTheDefault) {
  const std::string script = writeScript("0 1 0 0 0 0 0 0\n");
  for (const std::vector<std::string>& contact : {std::vector<std::string>{}, {"--surface-contact"}}) {
    std::vector<std::string> args = {"simulate", asset("peg-in-hole.glb"), "--move", "peg", "--script",
                                     script,     "--point-layer",          "1"};
    args.insert(args.end(), contact.begin(), contact.end());
    const CliRun r = voxhap(args);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("--paper-contact"), std::string::npos) << r.err;  // names the way out
  }
  const CliRun paper = voxhap({"simulate", asset("peg-in-hole.glb"), "--move", "peg", "--script", script,
                               "--point-layer", "1", "--paper-contact", "--duration", "0.01"});
  EXPECT_EQ(paper.exitCode, 0) << paper.err;
}

TEST_F(SimulateCommand, ForceLayerOfAMovingObjectIsCheckedAndTaken) {
  const std::string script = writeScript("0 1 0 0 0 0 0 0\n");
  const auto run = [&](const std::string& value) {
    return voxhap({"simulate", asset("peg-in-hole.glb"), "--move", "peg", "--script", script, "--duration",
                   "0.01", "--force-layer-of", value});
  };
  for (const char* bad : {"peg", "=3", "peg=0", "peg=256", "peg=three"}) {
    const CliRun r = run(bad);
    EXPECT_EQ(r.exitCode, 2) << bad;
    EXPECT_NE(r.err.find("force-layer-of"), std::string::npos) << r.err;
  }
  const CliRun still = run("block=4");
  EXPECT_NE(still.exitCode, 0);
  EXPECT_NE(still.err.find("block, which is not a moving object"), std::string::npos) << still.err;
  const CliRun shallow = run("peg=2");  // surface contact (the default) pushes points up to layer 3
  EXPECT_NE(shallow.exitCode, 0);
  EXPECT_NE(shallow.err.find("peg against the static scene: its own force layer 2"), std::string::npos)
      << shallow.err;
  EXPECT_EQ(run("peg=5").exitCode, 0);
}

TEST_F(SimulateCommand, CheckExactOptionsAreChecked) {
  const std::string script = writeScript("0 1 0 0 0 0 0 0\n");
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--check-exact-every", "0"},
        std::vector<std::string>{"--probe-spacing", "1mm"},
        std::vector<std::string>{"--check-exact", "--probe-spacing", "0mm"}}) {
    std::vector<std::string> args = {"simulate", asset("peg-in-hole.glb"), "--move", "peg", "--script",
                                     script};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliRun r = voxhap(args);
    EXPECT_EQ(r.exitCode, 2) << extra[0];
    EXPECT_NE(r.err.find(extra.back() == "0" ? "check-exact-every" : "probe-spacing"), std::string::npos)
        << r.err;
  }
}

}  // namespace
}  // namespace voxhap::test

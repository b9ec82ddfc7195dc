// `voxhap voxelize`, run as the real executable: exit codes, the JSON figures, the
// cache across runs and the slice picture.

#include <array>
#include <cmath>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/png_decode.h"

namespace {

namespace fs = std::filesystem;
using voxhap::test::CliRun;
using voxhap::test::decodePng;
using voxhap::test::lineCount;
using voxhap::test::slurp;

constexpr double kBallRadiusM = 0.025;
constexpr double kVoxelM = 0.35e-3;

class VoxelizeCommand : public voxhap::test::CliTest {
protected:
  /// Runs voxhap voxelize on the ball-and-socket asset with `extra` arguments and --json.
  nlohmann::json voxelizeJson(const std::vector<std::string>& extra) const {
    std::vector<std::string> args = {"voxelize", asset("ball-and-socket.glb"), "--json"};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliRun r = voxhap(args);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return nlohmann::json::parse(r.out);  // throws unless stdout is exactly one document
  }
};

std::uint32_t bigEndian32(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
  return v;
}

TEST_F(VoxelizeCommand, IsListedByTheTopLevelHelp) {
  const CliRun r = voxhap({"--help"});
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_NE(r.out.find("voxelize"), std::string::npos) << r.out;
}

TEST_F(VoxelizeCommand, BallReportsTheTableFiguresAsOneJsonDocument) {
  const nlohmann::json j = voxelizeJson({"--object", "ball", "--voxel-size", "0.35mm"});
  for (const char* key :
       {"object", "voxel_size_m", "bits", "triangles", "polygons_after_merge", "points", "points_by_feature",
        "voxels", "voxelize_s", "load_s", "memory_bytes", "cache", "peak_rss_bytes"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["object"], "ball");
  EXPECT_DOUBLE_EQ(j["voxel_size_m"].get<double>(), kVoxelM);
  EXPECT_EQ(j["bits"], 4);
  EXPECT_EQ(j["triangles"], 2048);
  EXPECT_EQ(j["cache"], "miss");
  EXPECT_GT(j["voxelize_s"].get<double>(), 0.0);
  EXPECT_EQ(j["load_s"].get<double>(), 0.0);
  EXPECT_GT(j["memory_bytes"].get<std::uint64_t>(), 0u);
  EXPECT_GT(j["peak_rss_bytes"].get<std::uint64_t>(), j["memory_bytes"].get<std::uint64_t>());
  const auto& byFeature = j["points_by_feature"];
  const auto& voxels = j["voxels"];
  EXPECT_EQ(j["points"], voxels["surface"]);
  EXPECT_EQ(j["points"].get<std::uint64_t>(), byFeature["vertex"].get<std::uint64_t>() +
                                                  byFeature["edge"].get<std::uint64_t>() +
                                                  byFeature["surface"].get<std::uint64_t>());
  EXPECT_EQ(voxels["total"].get<std::uint64_t>(), voxels["interior"].get<std::uint64_t>() +
                                                      voxels["surface"].get<std::uint64_t>() +
                                                      voxels["distance"].get<std::uint64_t>());
  // against the sphere: interior plus half the surface layer is the ball's volume; the
  // surface layer is between one and two voxels thick across the sphere's area
  const double voxelVolume = kVoxelM * kVoxelM * kVoxelM;
  const double volume = 4.0 / 3.0 * M_PI * std::pow(kBallRadiusM, 3);
  const double solid = voxels["interior"].get<double>() + 0.5 * voxels["surface"].get<double>();
  EXPECT_NEAR(solid * voxelVolume, volume, 0.02 * volume);
  const double areaVoxels = 4.0 * M_PI * kBallRadiusM * kBallRadiusM / (kVoxelM * kVoxelM);
  EXPECT_GT(j["points"].get<double>(), areaVoxels);
  EXPECT_LT(j["points"].get<double>(), 2.0 * areaVoxels);
}

TEST_F(VoxelizeCommand, SecondRunIsACacheHitWithTheSameFigures) {
  const nlohmann::json first = voxelizeJson({"--object", "ball", "--voxel-size", "0.35mm"});
  const nlohmann::json second = voxelizeJson({"--object", "ball", "--voxel-size", "0.00035"});
  EXPECT_EQ(first["cache"], "miss");
  EXPECT_EQ(second["cache"], "hit");
  EXPECT_EQ(second["voxelize_s"].get<double>(), 0.0);
  EXPECT_GT(second["load_s"].get<double>(), 0.0);
  for (const char* key : {"points", "points_by_feature", "voxels", "memory_bytes", "polygons_after_merge"}) {
    EXPECT_EQ(first[key], second[key]) << key;
  }
  // a different voxel size is a different cache entry
  EXPECT_EQ(voxelizeJson({"--object", "ball", "--voxel-size", "0.4mm"})["cache"], "miss");
}

TEST_F(VoxelizeCommand, NoCacheAlwaysVoxelizesAndCacheDirChoosesTheFolder) {
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(voxelizeJson({"--object", "ball", "--voxel-size", "1mm", "--no-cache"})["cache"], "miss");
  }
  EXPECT_FALSE(fs::exists(dir_ / "cache" / "voxels"));
  voxelizeJson({"--object", "ball", "--voxel-size", "1mm", "--cache-dir", "mine"});
  EXPECT_FALSE(fs::is_empty(dir_ / "mine"));
  EXPECT_FALSE(fs::exists(dir_ / "cache" / "voxels"));
}

TEST_F(VoxelizeCommand, WithoutObjectTheStaticObjectsAreVoxelizedAsOne) {
  const nlohmann::json j = voxelizeJson({"--voxel-size", "1mm"});
  EXPECT_EQ(j["object"], "static");
  const nlohmann::json info =
      nlohmann::json::parse(voxhap({"scene", "info", asset("ball-and-socket.glb"), "--json"}).out);
  EXPECT_EQ(j["triangles"], info["static_triangles"]);
}

TEST_F(VoxelizeCommand, BadVoxelSizesExitTwoWithOneLineNamingTheOption) {
  for (const char* size : {"0", "-0.35mm", "nan", "inf", "0.35cm", "mm", "big", ""}) {
    const CliRun r = voxhap({"voxelize", asset("ball-and-socket.glb"), "--voxel-size", size});
    EXPECT_EQ(r.exitCode, 2) << size;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("--voxel-size"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  const CliRun missing = voxhap({"voxelize", asset("ball-and-socket.glb")});
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.err.find("--voxel-size"), std::string::npos) << missing.err;
  const CliRun bits =
      voxhap({"voxelize", asset("ball-and-socket.glb"), "--voxel-size", "1mm", "--bits", "3"});
  EXPECT_EQ(bits.exitCode, 2);
  EXPECT_NE(bits.err.find("--bits"), std::string::npos) << bits.err;
}

TEST_F(VoxelizeCommand, UnknownObjectIsNamedWithTheKnownOnes) {
  const CliRun r =
      voxhap({"voxelize", asset("ball-and-socket.glb"), "--object", "cube", "--voxel-size", "1mm"});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("'cube'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("ball"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("socket"), std::string::npos) << r.err;
}

TEST_F(VoxelizeCommand, SliceIsAPngOfThreePanelsOfTheGridsLayer) {
  const nlohmann::json j =
      voxelizeJson({"--object", "ball", "--voxel-size", "0.35mm", "--slice", "z=0.012", "--png", "ball.png"});
  const std::string png = slurp(dir_ / "ball.png");
  ASSERT_GT(png.size(), 33u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(png[24], 8);  // bit depth
  EXPECT_EQ(png[25], 2);  // RGB
  EXPECT_EQ(png.substr(png.size() - 8, 4), "IEND");
  // the grid: the ball's ±25 mm at 0.35 mm spans voxels -72 … 71 (or a voxel fewer), padded
  // by 9 voxels (the range plus one) to about 162, rounded up to 3 hyperchunks = 192 voxels;
  // 600 px / 192 gives 3 px per voxel; three 576 px panels with two 8 px gaps
  const std::uint32_t width = bigEndian32(png, 16);
  const std::uint32_t height = bigEndian32(png, 20);
  EXPECT_EQ(height, 576u);
  EXPECT_EQ(width, 3u * 576u + 2u * 8u);
  EXPECT_EQ(j["slice"]["width_px"], width);
  EXPECT_EQ(j["slice"]["height_px"], height);
  // the grid starts 9 voxels below the voxel of the ball's lowest point; z = 12 mm lies in
  // voxel floor(12 / 0.35) = 34 of the frame's lattice
  const nlohmann::json info =
      nlohmann::json::parse(voxhap({"scene", "info", asset("ball-and-socket.glb"), "--json"}).out);
  ASSERT_EQ(info["objects"][0]["name"], "ball");
  const double lowestM = info["objects"][0]["bounds_m"]["min"][2].get<double>();
  const int gridStart = static_cast<int>(std::floor(lowestM / kVoxelM)) - 9;
  EXPECT_EQ(j["slice"]["layer"], 34 - gridStart);

  // decoded: far in the corner, interior at the ball's axis in both the surface and the
  // edge panel, a white surface voxel where the sphere (21.93 mm across at z = 12 mm)
  // cuts the x axis, in voxel floor(21.93 / 0.35) = 62
  const voxhap::test::DecodedPng image = decodePng(dir_ / "ball.png");
  ASSERT_EQ(image.width, width);
  ASSERT_EQ(image.height, height);
  const auto pixelX = [&](int voxel, int panel) {
    return static_cast<std::uint32_t>((voxel - gridStart) * 3 + 1 + panel * (576 + 8));
  };
  const auto pixelY = static_cast<std::uint32_t>((191 - (0 - gridStart)) * 3 + 1);  // y = 0, up is up
  EXPECT_EQ(image.at(0, 0), (std::array<int, 3>{28, 28, 32}));
  EXPECT_EQ(image.at(pixelX(0, 0), pixelY), (std::array<int, 3>{45, 80, 170}));
  EXPECT_EQ(image.at(pixelX(0, 1), pixelY), (std::array<int, 3>{45, 80, 170}));
  EXPECT_EQ(image.at(pixelX(62, 0), pixelY), (std::array<int, 3>{255, 255, 255}));
}

TEST_F(VoxelizeCommand, UnwritablePngExitsOneNamingTheFile) {
  const CliRun r = voxhap({"voxelize", asset("ball-and-socket.glb"), "--object", "ball", "--voxel-size",
                           "1mm", "--slice", "z=0", "--png", "no-such-folder/ball.png"});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("no-such-folder/ball.png"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "no-such-folder"));
}

TEST_F(VoxelizeCommand, SliceMistakesExitTwo) {
  for (const auto& extra : std::vector<std::vector<std::string>>{{"--slice", "z=0"},
                                                                 {"--png", "a.png"},
                                                                 {"--slice", "w=0", "--png", "a.png"},
                                                                 {"--slice", "z=1", "--png", "a.png"}}) {
    std::vector<std::string> args = {
        "voxelize", asset("ball-and-socket.glb"), "--object", "ball", "--voxel-size", "1mm"};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliRun r = voxhap(args);
    EXPECT_EQ(r.exitCode, 2) << extra[0] << " " << r.err;
    EXPECT_NE(r.err.find("--slice"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "a.png"));
  }
}

}  // namespace

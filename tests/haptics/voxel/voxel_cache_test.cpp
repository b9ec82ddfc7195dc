#include "haptics/voxel/voxel_cache.h"

#include <filesystem>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "haptics/geometry/mesh_builder.h"
#include "support/gltf_fixtures.h"

namespace voxhap {
namespace {

namespace fs = std::filesystem;

/// A ball and a box as two objects, merged by the cache functions like a static environment.
struct Objects {
  SceneObject ball;
  SceneObject box;
  std::vector<const SceneObject*> both{&ball, &box};

  Objects() {
    TriangleMesh sphere;
    appendGeodesicSphere(sphere, glm::dmat4(1.0), 0.01, 3);
    ball.name = "ball";
    ball.parts.push_back(makePart("ball", glm::vec4(1.0f), sphere));
    TriangleMesh cube;
    appendBox(cube, glm::translate(glm::dmat4(1.0), glm::dvec3(0.021, 0.003, 0.0)), glm::dvec3(0.004));
    box.name = "box";
    box.parts.push_back(makePart("box", glm::vec4(1.0f), cube));
  }
};

VoxelizeOptions voxelOptions(double voxelSizeM = 0.001) {
  VoxelizeOptions options;
  options.voxelSizeM = voxelSizeM;
  return options;
}

PointshellOptions shellOptions(double displacementM = 0.0) {
  PointshellOptions options;
  options.pointSpacingM = 0.001;
  options.displacementM = displacementM;
  return options;
}

std::vector<char> readBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& file, const std::vector<char>& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void expectSameStats(const VoxelizeStats& a, const VoxelizeStats& b) {
  EXPECT_EQ(a.interiorVoxels, b.interiorVoxels);
  EXPECT_EQ(a.surfaceVoxels, b.surfaceVoxels);
  EXPECT_EQ(a.distanceVoxels, b.distanceVoxels);
  EXPECT_EQ(a.edgeVoxels, b.edgeVoxels);
  EXPECT_EQ(a.vertexVoxels, b.vertexVoxels);
  EXPECT_EQ(a.vertexPoints, b.vertexPoints);
  EXPECT_EQ(a.edgePoints, b.edgePoints);
  EXPECT_EQ(a.surfacePoints, b.surfacePoints);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.polygonsAfterMerge, b.polygonsAfterMerge);
  EXPECT_EQ(a.voteDisagreements, b.voteDisagreements);
  EXPECT_EQ(a.firstDisagreementLocal, b.firstDisagreementLocal);
}

/// Every voxel word and chunk distance of the grid, and the grid itself, agree.
void expectSameVoxmap(const Voxmap& a, const Voxmap& b) {
  ASSERT_EQ(a.grid().dimsHyper, b.grid().dimsHyper);
  EXPECT_EQ(a.grid().originLocal, b.grid().originLocal);
  EXPECT_EQ(a.grid().voxelSizeM, b.grid().voxelSizeM);
  EXPECT_EQ(a.memoryBytes(), b.memoryBytes());
  const glm::ivec3 d = a.grid().dimsVoxels();
  for (int z = 0; z < d.z; ++z) {
    for (int y = 0; y < d.y; ++y) {
      for (int x = 0; x < d.x; ++x)
        ASSERT_EQ(a.word({x, y, z}), b.word({x, y, z})) << x << " " << y << " " << z;
    }
  }
  EXPECT_TRUE(a.surfacePlanes() == b.surfacePlanes());
  const glm::ivec3 c = a.grid().dimsChunks();
  for (int z = 0; z < c.z; ++z) {
    for (int y = 0; y < c.y; ++y) {
      for (int x = 0; x < c.x; ++x) ASSERT_EQ(a.chunkDistance({x, y, z}), b.chunkDistance({x, y, z}));
    }
  }
}

void expectSamePointshell(const Pointshell& a, const Pointshell& b) {
  EXPECT_EQ(a.pointSpacingM, b.pointSpacingM);
  EXPECT_EQ(a.positionsLocal, b.positionsLocal);
  EXPECT_EQ(a.normalsLocal, b.normalsLocal);
  EXPECT_EQ(a.features, b.features);
  EXPECT_EQ(a.chunkBegin, b.chunkBegin);
  EXPECT_EQ(a.chunkCentroidsLocal, b.chunkCentroidsLocal);
}

class VoxelCache : public ::testing::Test {
protected:
  CacheOptions cache() const { return {dir_.path() / "voxels", true}; }

  /// A fresh build, then a corrupted copy of its file, then a run that must rebuild it.
  void expectRebuiltAfter(const std::function<void(std::vector<char>&)>& corrupt, const std::string& warning,
                          const VoxelizeOptions& options = voxelOptions()) {
    const CachedVoxelization first = voxelizeCached(objects_.both, options, cache());
    std::vector<char> bytes = readBytes(first.cacheFile);
    corrupt(bytes);
    writeBytes(first.cacheFile, bytes);
    const CachedVoxelization again = voxelizeCached(objects_.both, options, cache());
    EXPECT_FALSE(again.cacheHit);
    ASSERT_EQ(again.warnings.size(), 1u);
    EXPECT_NE(again.warnings[0].find(first.cacheFile.string()), std::string::npos) << again.warnings[0];
    EXPECT_NE(again.warnings[0].find(warning), std::string::npos) << again.warnings[0];
    EXPECT_NE(again.warnings[0].find("rebuilt"), std::string::npos) << again.warnings[0];
    expectSameVoxmap(again.voxelized.voxmap, first.voxelized.voxmap);
    // the rebuilt file is good again
    const CachedVoxelization third = voxelizeCached(objects_.both, options, cache());
    EXPECT_TRUE(third.cacheHit);
    EXPECT_TRUE(third.warnings.empty());
  }

  test::TempDir dir_;
  Objects objects_;
};

TEST_F(VoxelCache, MissThenHitGivesTheSameVoxmapAndStats) {
  const CachedVoxelization miss = voxelizeCached(objects_.both, voxelOptions(), cache());
  EXPECT_FALSE(miss.cacheHit);
  EXPECT_GT(miss.voxelizeS, 0.0);
  EXPECT_EQ(miss.loadS, 0.0);
  EXPECT_TRUE(miss.warnings.empty());
  ASSERT_TRUE(fs::exists(miss.cacheFile));
  EXPECT_EQ(miss.cacheFile.parent_path(), cache().directory);

  const CachedVoxelization hit = voxelizeCached(objects_.both, voxelOptions(), cache());
  EXPECT_TRUE(hit.cacheHit);
  EXPECT_EQ(hit.voxelizeS, 0.0);
  EXPECT_GT(hit.loadS, 0.0);
  EXPECT_TRUE(hit.warnings.empty());
  EXPECT_EQ(hit.cacheFile, miss.cacheFile);
  expectSameStats(hit.voxelized.stats, miss.voxelized.stats);
  expectSameVoxmap(hit.voxelized.voxmap, miss.voxelized.voxmap);
  // and both agree with voxelizing without a cache
  const CachedVoxelization fresh = voxelizeCached(objects_.both, voxelOptions(), {{}, false});
  expectSameVoxmap(hit.voxelized.voxmap, fresh.voxelized.voxmap);
  EXPECT_GT(miss.voxelized.stats.surfaceVoxels, 1000u);
}

TEST_F(VoxelCache, FlippedByteIsRebuiltWithAWarning) {
  expectRebuiltAfter(
      [](std::vector<char>& b) { b[b.size() / 2] = static_cast<char>(b[b.size() / 2] ^ 0x10); },
      "checksum mismatch");
}

TEST_F(VoxelCache, TruncatedFileIsRebuiltWithAWarning) {
  expectRebuiltAfter([](std::vector<char>& b) { b.erase(b.end() - 100, b.end()); }, "truncated");
  expectRebuiltAfter([](std::vector<char>& b) { b.resize(20); }, "truncated");
}

TEST_F(VoxelCache, OtherFormatVersionIsRebuiltWithAWarning) {
  expectRebuiltAfter([](std::vector<char>& b) { b[8] = static_cast<char>(b[8] + 1); }, "format version");
}

TEST_F(VoxelCache, FileOfOtherDataIsRebuiltWithAWarning) {
  expectRebuiltAfter([](std::vector<char>& b) { b[20] = static_cast<char>(b[20] ^ 1); }, "key mismatch");
}

TEST_F(VoxelCache, LengthInTheHeaderIsCheckedAgainstTheFile) {
  // a payload length claiming far more than the file holds must not be trusted
  expectRebuiltAfter([](std::vector<char>& b) { b[39] = static_cast<char>(0x7f); }, "truncated");
}

TEST_F(VoxelCache, DisabledCacheAlwaysBuildsAndWritesNothing) {
  const CacheOptions off{dir_.path() / "voxels", false};
  for (int i = 0; i < 2; ++i) {
    const CachedVoxelization v = voxelizeCached(objects_.both, voxelOptions(), off);
    EXPECT_FALSE(v.cacheHit);
    EXPECT_GT(v.voxelizeS, 0.0);
    EXPECT_TRUE(v.cacheFile.empty());
  }
  EXPECT_FALSE(fs::exists(off.directory));
}

TEST_F(VoxelCache, SurfacePlanesAreKeptAndComeBackTheSame) {
  VoxelizeOptions planes = voxelOptions();
  planes.surfacePlanes = true;
  const CachedVoxelization miss = voxelizeCached(objects_.both, planes, cache());
  ASSERT_TRUE(miss.voxelized.voxmap.hasSurfacePlanes());
  const CachedVoxelization hit = voxelizeCached(objects_.both, planes, cache());
  EXPECT_TRUE(hit.cacheHit);
  expectSameVoxmap(hit.voxelized.voxmap, miss.voxelized.voxmap);
  // without planes, another file and none read
  const CachedVoxelization without = voxelizeCached(objects_.both, voxelOptions(), cache());
  EXPECT_NE(without.cacheFile, miss.cacheFile);
  EXPECT_FALSE(without.voxelized.voxmap.hasSurfacePlanes());
}

TEST_F(VoxelCache, SurfacePlanesThatDoNotMatchTheirMasksOrAreEmptyOrHaveSidesBeyondSixAreRebuilt) {
  VoxelizeOptions planes = voxelOptions();
  planes.surfacePlanes = true;
  const std::size_t planeCount =
      voxelizeCached(objects_.both, planes, {{}, false}).voxelized.voxmap.surfacePlanes().planeCount();
  ASSERT_GT(planeCount, 0u);
  // the payload ends with the plane count, the planes and their convex sides; then the checksum,
  // which the loader checks after them
  constexpr std::size_t kChecksumBytes = 16;
  auto sidesAt = [&](const std::vector<char>& b) { return b.size() - kChecksumBytes - planeCount; };
  auto planesAt = [&](const std::vector<char>& b) { return sidesAt(b) - planeCount * sizeof(SurfacePlane); };
  expectRebuiltAfter([&](std::vector<char>& b) { b[sidesAt(b) + planeCount / 2] = 0x40; },
                     "convex sides are not six bits", planes);
  expectRebuiltAfter(
      [&](std::vector<char>& b) {
        // the last plane's distance: SurfacePlane::kNone, little-endian
        b[planesAt(b) + (planeCount - 1) * sizeof(SurfacePlane)] = 0x00;
        b[planesAt(b) + (planeCount - 1) * sizeof(SurfacePlane) + 1] = static_cast<char>(0x80);
      },
      "a stored surface plane is empty", planes);
  expectRebuiltAfter([&](std::vector<char>& b) { ++b[planesAt(b) - sizeof(std::uint64_t)]; },
                     "surface planes do not match their masks", planes);
}

TEST_F(VoxelCache, KeyCoversVoxelSizeBitsAwarenessAndGeometry) {
  const fs::path base = voxelizeCached(objects_.both, voxelOptions(), cache()).cacheFile;
  EXPECT_NE(voxelizeCached(objects_.both, voxelOptions(0.0011), cache()).cacheFile, base);
  VoxelizeOptions eight = voxelOptions();
  eight.encoding = VoxelEncoding::forBits(8);
  EXPECT_NE(voxelizeCached(objects_.both, eight, cache()).cacheFile, base);
  VoxelizeOptions unaware = voxelOptions();
  unaware.buildFeatureFields = false;
  EXPECT_NE(voxelizeCached(objects_.both, unaware, cache()).cacheFile, base);
  const SceneObject* ballOnly[] = {&objects_.ball};
  EXPECT_NE(voxelizeCached(ballOnly, voxelOptions(), cache()).cacheFile, base);
  objects_.box.parts[0].mesh.positionsWorld[0].x += 1e-6f;
  EXPECT_NE(voxelizeCached(objects_.both, voxelOptions(), cache()).cacheFile, base);
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(cache().directory)) ++files;
  EXPECT_EQ(files, 6u);  // and no temporary file left behind
}

TEST_F(VoxelCache, UnwritableFolderOnlyWarns) {
  std::ofstream(dir_.path() / "blocker") << "a file where the folder should be";
  const CachedVoxelization v =
      voxelizeCached(objects_.both, voxelOptions(), {dir_.path() / "blocker" / "voxels"});
  EXPECT_FALSE(v.cacheHit);
  ASSERT_EQ(v.warnings.size(), 1u);
  EXPECT_NE(v.warnings[0].find("blocker"), std::string::npos) << v.warnings[0];
  EXPECT_GT(v.voxelized.stats.surfaceVoxels, 0u);
}

TEST_F(VoxelCache, PointshellMissThenHitIsTheSame) {
  const SceneObject* ball[] = {&objects_.ball};
  const CachedPointshell miss = pointshellCached(ball, shellOptions(), cache());
  EXPECT_FALSE(miss.cacheHit);
  EXPECT_GT(miss.buildS, 0.0);
  const CachedPointshell hit = pointshellCached(ball, shellOptions(), cache());
  EXPECT_TRUE(hit.cacheHit);
  EXPECT_EQ(hit.buildS, 0.0);
  EXPECT_GT(hit.loadS, 0.0);
  expectSamePointshell(hit.pointshell, miss.pointshell);
  EXPECT_GT(hit.pointshell.size(), 500u);
  // the displacement is part of the key
  const CachedPointshell moved = pointshellCached(ball, shellOptions(-0.0005), cache());
  EXPECT_FALSE(moved.cacheHit);
  EXPECT_NE(moved.cacheFile, miss.cacheFile);
}

TEST_F(VoxelCache, PointCountsOfTheVoxmapAreThePointshellsAtThatSpacing) {
  // the same lattice: one point per surface voxel, labelled by the same feature priority
  const CachedVoxelization v = voxelizeCached(objects_.both, voxelOptions(), {{}, false});
  const CachedPointshell p = pointshellCached(objects_.both, shellOptions(), {{}, false});
  EXPECT_EQ(v.voxelized.stats.surfaceVoxels, p.pointshell.size());
  EXPECT_EQ(v.voxelized.stats.vertexPoints, p.pointshell.count(PointFeature::Vertex));
  EXPECT_EQ(v.voxelized.stats.edgePoints, p.pointshell.count(PointFeature::Edge));
  EXPECT_EQ(v.voxelized.stats.surfacePoints, p.pointshell.count(PointFeature::Surface));
}

TEST_F(VoxelCache, CorruptPointshellFileIsRebuilt) {
  const SceneObject* ball[] = {&objects_.ball};
  const CachedPointshell first = pointshellCached(ball, shellOptions(), cache());
  std::vector<char> bytes = readBytes(first.cacheFile);
  bytes[bytes.size() - 30] = static_cast<char>(bytes[bytes.size() - 30] ^ 0x01);
  writeBytes(first.cacheFile, bytes);
  const CachedPointshell again = pointshellCached(ball, shellOptions(), cache());
  EXPECT_FALSE(again.cacheHit);
  ASSERT_EQ(again.warnings.size(), 1u);
  EXPECT_NE(again.warnings[0].find("checksum mismatch"), std::string::npos) << again.warnings[0];
  expectSamePointshell(again.pointshell, first.pointshell);
}

}  // namespace
}  // namespace voxhap

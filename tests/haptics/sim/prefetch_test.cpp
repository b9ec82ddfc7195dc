// Pre-fetching (paper §5.3, DESIGN §4.6): a static voxmap paged within a memory budget
// reads what the whole voxmap reads wherever its words are resident, and the frame is
// suspended, never wrong, where they are not. Ground truth: the whole voxmap.
#include <random>
#include <thread>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "haptics/device/scripted_device.h"
#include "haptics/voxel/voxel_cache.h"
#include "support/allocation_counter.h"
#include "support/contact_scenes.h"
#include "support/gltf_fixtures.h"

namespace voxhap {
namespace {

namespace fs = std::filesystem;

constexpr double kVoxel = 0.0005;  // m

/// A plate with a post on it, and a ball over the plate.
Scene plateAndBall() {
  Scene scene;
  scene.objects.push_back(test::plate());
  scene.objects.push_back(test::meshObject("post", ObjectRole::Static, [](TriangleMesh& m) {
    appendBox(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.02, 0.02, 0.01)),
              glm::dvec3(0.004, 0.004, 0.01));
  }));
  scene.objects.push_back(test::meshObject("ball", ObjectRole::Dynamic, [](TriangleMesh& m) {
    appendGeodesicSphere(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 0.012)), 0.01, 4);
  }));
  return scene;
}

std::vector<const SceneObject*> staticObjects(const Scene& scene) {
  return {&scene.objects[0], &scene.objects[1]};
}

VoxelizeOptions voxelOptions() {
  VoxelizeOptions options;
  options.voxelSizeM = kVoxel;
  return options;
}

/// Every voxel of `paged` (every third along each axis) that is resident reads what `whole`
/// reads; returns how many are missing.
std::size_t expectResidentWordsMatch(const Voxmap& paged, const Voxmap& whole) {
  std::size_t missing = 0;
  const glm::ivec3 dims = whole.grid().dimsVoxels();
  for (int z = 0; z < dims.z; z += 3) {
    for (int y = 0; y < dims.y; y += 3) {
      for (int x = 0; x < dims.x; x += 3) {
        const VoxelWord word = paged.word({x, y, z});
        if (word == Voxmap::kMissingWord) {
          ++missing;
        } else if (word != whole.word({x, y, z})) {
          ADD_FAILURE() << "voxel " << x << "," << y << "," << z << " reads " << word << ", whole "
                        << whole.word({x, y, z});
          return missing;
        }
      }
    }
  }
  return missing;
}

/// A budget for `whole`'s tables (as voxel_cache.cpp counts them) and `slots` chunks of words,
/// each with its padding and use mark.
std::uint64_t budgetFor(const Voxmap& whole, std::uint64_t slots) {
  const std::uint64_t tables = (whole.hyperEntries().size() + 2 * whole.chunkEntries().size()) * 4 +
                               whole.hyperEntries().size() * kChunksPerHyper;
  return tables + slots * (kVoxelsPerChunk * static_cast<std::uint64_t>(whole.encoding().bytesPerWord()) +
                           Voxmap::kSlotOverheadBytes);
}

class Prefetch : public ::testing::Test {
protected:
  CacheOptions cache() const { return {dir_.path() / "voxels", true}; }
  test::TempDir dir_;
  Scene scene_ = plateAndBall();
};

TEST_F(Prefetch, AVoxmapThatFitsItsBudgetIsWholeAndHasNoPager) {
  const BudgetedVoxmap whole =
      voxelizeWithinBudget(staticObjects(scene_), voxelOptions(), cache(), 1ull << 34);
  EXPECT_FALSE(whole.pager);
  EXPECT_GT(whole.wordBytes, 0u);
  EXPECT_TRUE(whole.warnings.empty());
}

TEST_F(Prefetch, PagedWordsAreTheWholeVoxmapsAndEvictedOnesReadMissing) {
  const Voxmap whole = voxelizeCached(staticObjects(scene_), voxelOptions(), cache()).voxelized.voxmap;
  BudgetedVoxmap paged =
      voxelizeWithinBudget(staticObjects(scene_), voxelOptions(), cache(), budgetFor(whole, 64));
  ASSERT_TRUE(paged.pager);
  EXPECT_EQ(paged.pager->slotCount(), 64u);
  const std::size_t missingAtFirst = expectResidentWordsMatch(paged.voxmap, whole);  // uniform chunks only
  EXPECT_GT(missingAtFirst, 0u);
  // walk boxes of chunks over the grid: each is read, earlier ones are evicted
  const glm::ivec3 chunks = whole.grid().dimsChunks();
  std::size_t boxes = 0;
  for (int x = 0; x + 1 < chunks.x; x += 3) {
    const glm::ivec3 lo(x, chunks.y / 2 - 1, 0);
    const glm::ivec3 hi(x + 1, chunks.y / 2, chunks.z - 1);
    paged.pager->makeResident(lo, hi);
    ++boxes;
    for (int cz = lo.z; cz <= hi.z; ++cz) {
      for (int cy = lo.y; cy <= hi.y; ++cy) {
        for (int cx = lo.x; cx <= hi.x; ++cx) {
          const glm::ivec3 v = glm::ivec3(cx, cy, cz) * kChunkEdgeVoxels + 3;
          if (paged.voxmap.word(v) == Voxmap::kMissingWord) {
            // only when the box alone holds more mixed chunks than the pool
            EXPECT_GT(2 * 2 * chunks.z, 64) << "chunk " << cx << "," << cy << "," << cz;
          } else {
            ASSERT_EQ(paged.voxmap.word(v), whole.word(v));
          }
        }
      }
    }
    EXPECT_LT(expectResidentWordsMatch(paged.voxmap, whole), missingAtFirst);
  }
  EXPECT_GT(boxes, 3u);
  EXPECT_GT(paged.pager->blocksRead(), 64u);  // slots were reused
}

TEST_F(Prefetch, BudgetTooSmallForTheTablesIsAClearError) {
  try {
    voxelizeWithinBudget(staticObjects(scene_), voxelOptions(), cache(), 1024);
    FAIL() << "accepted a 1 KiB budget";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot hold the voxmap's tables"), std::string::npos) << e.what();
  }
  try {
    voxelizeWithinBudget(staticObjects(scene_), voxelOptions(), CacheOptions{{}, false}, 1 << 20);
    FAIL() << "paged without a cache";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--no-cache"), std::string::npos) << e.what();
  }
}

/// Models of the ball over the plate: the static voxmap whole, and paged in `budgetBytes`.
struct Models {
  SimModel whole;
  BuiltScene paged;
};

Models models(const Scene& scene, const CacheOptions& cache, double capacity) {
  SceneModelOptions options;
  options.staticVoxelSizeM = kVoxel;
  options.pointSpacingM = kVoxel;
  options.sim.coherence.capacityTests = capacity;
  options.voxelizeFn = [cache](std::span<const SceneObject* const> objects, const VoxelizeOptions& o,
                               const ProgressFn&) {
    return voxelizeCached(objects, o, cache).voxelized.voxmap;
  };
  SimModel whole = buildSceneModel(scene, {"ball"}, options);
  const std::uint64_t budget = budgetFor(*whole.staticVoxmap, 192);
  options.budgetedVoxelizeFn = [cache, budget](std::span<const SceneObject* const> objects,
                                               const VoxelizeOptions& o, const ProgressFn&) {
    return voxelizeWithinBudget(objects, o, cache, budget);
  };
  return {std::move(whole), buildScene(scene, {"ball"}, options)};
}

TEST_F(Prefetch, FramesAreSuspendedNeverWrongWhileVoxelsArePagedIn) {
  const Models m = models(scene_, cache(), 1e6);
  ASSERT_TRUE(m.paged.staticPager);
  ASSERT_TRUE(m.paged.model.staticVoxmap->isPaged());
  ASSERT_FALSE(m.whole.staticVoxmap->isPaged());
  // the ball swept over the plate and pressed onto it, faster than the pager may keep up
  std::vector<MotionKeyframe> keys;
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int k = 0; k <= 30; ++k) {
    keys.push_back(
        {0.1 * k, Pose{glm::dvec3(0.02 * unit(random), 0.02 * unit(random), -0.003), identityQuat()}});
  }
  ScriptedDevice device(MotionScript(keys, "sweep"));
  HapticDevice* devices[] = {&device};
  LocalSimulation sim(m.paged.model, m.paged.staticPager);
  SimState& state = sim.state;
  std::uint64_t contactFrames = 0;
  std::uint64_t frameAllocations = 0;  // by the thread that steps
  for (int frame = 0; frame < 3000; ++frame) {
    // what the whole voxmap finds at this pose
    const Pointshell& shell = m.whole.objects[0].shell;
    std::vector<PointContact> contacts(shell.size());
    const std::uint32_t expected =
        samplePoints(shell, *m.whole.staticVoxmap,
                     VoxelTransform::make(objectPose(m.paged.model, state, 0), m.whole.staticVoxmap->grid()),
                     m.whole.pairs[0].fieldShifts, state.forceLayer, 0,
                     static_cast<std::uint32_t>(shell.size()), contacts.data());
    const Pose before = objectPose(m.paged.model, state, 0);
    const test::AllocationCounter allocations;
    sim.stepWithDevices(devices);
    frameAllocations += allocations.count();
    ASSERT_FALSE(sim.workspace.stopped);
    if (sim.workspace.suspensions.active) {
      // a haptic loop waits for its next period; this one runs unpaced otherwise
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      // nothing moves, the device feels nothing
      EXPECT_EQ(objectPose(m.paged.model, state, 0).position, before.position);
      EXPECT_EQ(sim.object(0).feedback.forceWorld, glm::dvec3(0.0));
      EXPECT_EQ(sim.object(0).contactForceWorld, glm::dvec3(0.0));
    } else {
      // every contact tested in its frame (it is in the contact queue now), but a surface
      // point sunk through the plate's face, which awareness leaves to its next test
      // (coherence_test.cpp)
      const PointQueues& queues = sim.workspace.coherence[0].queues();
      for (std::uint32_t i = 0; i < expected; ++i) {
        const PointContact& c = contacts[i];
        const bool throughAFace =
            c.value == kValueInterior && shell.features[c.point] != PointFeature::Vertex;
        ASSERT_TRUE(queues.queueOf(c.point) == 0 || throughAFace)
            << "frame " << frame << ", point " << c.point;
      }
      contactFrames += expected > 0 ? 1 : 0;
    }
  }
  EXPECT_GT(sim.workspace.suspensions.count, 0u);
  EXPECT_GT(contactFrames, 300u);
  EXPECT_EQ(frameAllocations, 0u) << "suspended or paging frames allocated";
  EXPECT_GT(m.paged.staticPager->blocksRead(), m.paged.staticPager->slotCount());  // it evicted
}

TEST_F(Prefetch, APagedModelNeedsItsPagerAndAWholeOneNone) {
  const Models m = models(scene_, cache(), 1e6);
  EXPECT_THROW(makeSimWorkspace(m.paged.model, makeSimState(m.paged.model)), Error);
  EXPECT_THROW(makeSimWorkspace(m.whole, makeSimState(m.whole), m.paged.staticPager), Error);
  SceneModelOptions options;
  options.staticVoxelSizeM = kVoxel;
  options.pointSpacingM = kVoxel;
  const std::uint64_t budget = budgetFor(*m.whole.staticVoxmap, 192);
  options.budgetedVoxelizeFn = [this, budget](std::span<const SceneObject* const> objects,
                                              const VoxelizeOptions& o, const ProgressFn&) {
    return voxelizeWithinBudget(objects, o, cache(), budget);
  };
  try {
    buildSceneModel(scene_, {"ball"}, options);
    FAIL() << "a paged scene built as a bare model";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("buildScene"), std::string::npos) << e.what();
  }
}

TEST_F(Prefetch, ASuspensionLongerThanTwoSecondsStopsTheRun) {
  const Models m = models(scene_, cache(), 1e6);
  ASSERT_TRUE(m.paged.staticPager);
  LocalSimulation sim(m.paged.model, m.paged.staticPager);
  SimState& state = sim.state;
  // the cache file loses its words: nothing more can be read
  for (const auto& entry : fs::directory_iterator(cache().directory)) {
    if (entry.path().filename().string().rfind("voxmap-", 0) == 0) fs::resize_file(entry.path(), 4096);
  }
  // the ball sweeps sideways over the plate, into chunks never read
  HandleInput handles[1] = {{Pose{glm::dvec3(0.04, 0.0, -0.002), identityQuat()}, {}}};
  const auto start = std::chrono::steady_clock::now();
  while (!sim.workspace.stopped && std::chrono::steady_clock::now() - start < std::chrono::seconds(10)) {
    sim.step(handles);
  }
  EXPECT_TRUE(sim.workspace.stopped);
  EXPECT_GT(sim.workspace.suspensions.longestS, kMaxSuspensionS);
  EXPECT_GT(m.paged.staticPager->readFailures(), 0u);  // each failed read gave its slot back
  const std::uint64_t frame = state.frame;
  EXPECT_EQ(sim.step(handles), kFrameStopped);
  EXPECT_EQ(state.frame, frame);  // a stopped run stays stopped
}

}  // namespace
}  // namespace voxhap

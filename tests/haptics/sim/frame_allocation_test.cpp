// The 1 kHz frame never allocates (CONVENTIONS): global operator new is replaced in this
// test binary by one that counts calls while `countingAllocations` is set.
#include <atomic>
#include <cstdlib>
#include <new>

#include <gtest/gtest.h>

#include "support/contact_scenes.h"

namespace {
std::atomic<bool> countingAllocations{false};
std::atomic<long> allocations{0};

void* allocate(std::size_t bytes) {
  if (countingAllocations) ++allocations;
  if (void* p = std::malloc(bytes ? bytes : 1)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t bytes) {
  return allocate(bytes);
}
void* operator new[](std::size_t bytes) {
  return allocate(bytes);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}
void* operator new(std::size_t bytes, const std::nothrow_t&) noexcept {
  if (countingAllocations) ++allocations;
  return std::malloc(bytes ? bytes : 1);
}
void* operator new[](std::size_t bytes, const std::nothrow_t& tag) noexcept {
  return operator new(bytes, tag);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}

namespace voxhap {
namespace {

TEST(FrameAllocation, SteppingTwoCoupledObjectsInContactAllocatesNothing) {
  Scene scene;
  scene.objects.push_back(test::plate());
  for (int i = 0; i < 2; ++i) {
    scene.objects.push_back(test::meshObject(i == 0 ? "a" : "b", ObjectRole::Dynamic, [&](TriangleMesh& m) {
      appendBox(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0111 * i, 0.0, 0.0056)), glm::dvec3(0.005));
    }));
  }
  SceneModelOptions options = test::ampleCapacityOptions();
  options.staticVoxelSizeM = 0.0005;
  options.pointSpacingM = 0.0005;
  options.sim.gravityWorld = glm::dvec3(0.0, 0.0, -9.81);
  const SimModel model = buildSceneModel(scene, {"a", "b"}, options);
  const MotionScript script({{0.0, Pose{}}, {0.2, Pose{glm::dvec3(0.002, 0.0, -0.001), identityQuat()}}},
                            "push");
  ScriptedDevice da(script);
  ScriptedDevice db(script);
  HapticDevice* devices[] = {&da, &db};
  LocalSimulation sim(model);
  // the counter sees allocations
  countingAllocations = true;
  delete new int(1);
  countingAllocations = false;
  ASSERT_EQ(allocations.exchange(0), 1);
  countingAllocations = true;
  for (int i = 0; i < 200; ++i) sim.stepWithDevices(devices);
  countingAllocations = false;
  EXPECT_EQ(allocations.load(), 0);
  EXPECT_GT(sim.object(0).contacts + sim.object(1).contacts, 0u) << "the frames tested no contact";
}

}  // namespace
}  // namespace voxhap

#include "haptics/collide/probe_cells.h"

#include <algorithm>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "haptics/geometry/embree_scene.h"
#include "haptics/geometry/mesh_builder.h"

namespace voxhap {
namespace {

bool lexLess(const glm::vec3& p, const glm::vec3& q) {
  return std::tie(p.x, p.y, p.z) < std::tie(q.x, q.y, q.z);
}

TEST(ProbeCells, OnDemandBlocksHoldTheSameProbesAsTheWholeSurface) {
  TriangleMesh mesh;
  appendCylinder(mesh, frameAlongAxis({0.003, -0.002, 0.001}, glm::normalize(glm::dvec3(1.0, 0.3, 0.2))),
                 0.01, 0.05, 24);
  const TriangleMesh* meshes[] = {&mesh};
  const EmbreeScene scene(meshes);
  ProbeCells whole(meshes, scene, 0.0008, 0.004, true);
  ProbeCells onDemand(meshes, scene, 0.0008, 0.004, false);
  EXPECT_TRUE(whole.whole());
  EXPECT_EQ(onDemand.probeCount(), 0u);

  auto probesOf = [](ProbeCells& cells, std::span<const ProbeBlock> blocks) {
    std::vector<glm::vec3> points;
    for (const ProbeBlock& block : blocks) {
      for (std::uint32_t c = block.firstCell; c < block.firstCell + block.cellCount; ++c) {
        const ProbeCell& cell = cells.cell(c);
        for (std::uint32_t i = cell.first; i < cell.first + cell.count; ++i) {
          points.push_back(cells.probeLocal(i));
          // every probe within its cell's and its block's sphere
          EXPECT_LE(glm::length(glm::dvec3(cells.probeLocal(i)) - cell.centreLocal), cell.radiusM + 1e-12);
          EXPECT_LE(glm::length(glm::dvec3(cells.probeLocal(i)) - block.centreLocal), block.radiusM + 1e-12);
        }
      }
    }
    std::sort(points.begin(), points.end(), lexLess);
    return points;
  };
  const std::vector<glm::vec3> expected = probesOf(whole, whole.blocks());
  // no duplicates in the whole surface: shared edges and vertices are kept once
  EXPECT_EQ(std::adjacent_find(expected.begin(), expected.end()), expected.end());

  std::vector<std::uint64_t> keys;
  onDemand.blockKeysIn({-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1}, keys);
  std::vector<ProbeBlock> blocks;
  for (const std::uint64_t key : keys) {
    if (const auto block = onDemand.block(key)) blocks.push_back(*block);
  }
  EXPECT_EQ(probesOf(onDemand, blocks), expected);
  EXPECT_EQ(onDemand.probeCount(), expected.size());
  onDemand.clear();
  EXPECT_EQ(onDemand.probeCount(), 0u);
}

}  // namespace
}  // namespace voxhap

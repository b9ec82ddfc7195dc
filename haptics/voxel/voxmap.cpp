#include "haptics/voxel/voxmap.h"

#include <cassert>

namespace voxhap {

Voxmap::Voxmap(VoxelGrid grid, VoxelEncoding encoding, std::vector<std::uint32_t> hyper,
               std::vector<std::uint32_t> chunks, std::vector<std::uint8_t> voxelBytes)
    : grid_(grid),
      encoding_(encoding),
      bytesPerWord_(static_cast<std::size_t>(encoding.bytesPerWord())),
      wordMask_(encoding.bytesPerWord() == 4 ? 0xFFFFFFFFu : (1u << (8 * encoding.bytesPerWord())) - 1u),
      hyper_(std::move(hyper)),
      chunks_(std::move(chunks)),
      voxelBytes_(std::move(voxelBytes)) {
  assert(encoding_.valid());
  assert(hyper_.size() == static_cast<std::size_t>(grid_.dimsHyper.x) * static_cast<std::size_t>(grid_.dimsHyper.y) *
                              static_cast<std::size_t>(grid_.dimsHyper.z));
  assert(chunks_.size() % kChunksPerHyper == 0);
  voxelBytes_.resize(voxelBytes_.size() + kPadBytes, 0);
}

}  // namespace voxhap

#include "haptics/voxel/voxel_pager.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>

#include <glm/common.hpp>

#include "haptics/core/error.h"

namespace voxhap {
namespace {

/// How long the pager sleeps when it has nothing to do.
constexpr auto kIdle = std::chrono::microseconds(200);
/// A slot asked for within this many frames is not taken back.
constexpr std::uint64_t kRecentFrames = 50;

}  // namespace

VoxelPager::VoxelPager(const Voxmap::PagedArrays& arrays, const std::filesystem::path& file,
                       std::uint64_t wordsOffset, std::vector<std::uint32_t> fileBlockOfEntry, std::size_t slotCount)
    : arrays_(arrays),
      wordsOffset_(wordsOffset),
      blockBytes_(arrays.blockBytes),
      fileBlockOfEntry_(std::move(fileBlockOfEntry)),
      slotOfEntry_(fileBlockOfEntry_.size(), kNone),
      slotEntry_(slotCount, kNone),
      slotAskedFrame_(slotCount, 0) {
  if (slotCount == 0) throw Error("the voxel memory budget holds no chunk of voxel words");
  fd_ = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw Error(file.string() + ": cannot open for paging: " + std::strerror(errno));
  freeSlots_.reserve(slotCount);
  for (std::size_t s = slotCount; s-- > 0;) freeSlots_.push_back(static_cast<std::uint32_t>(s));
  thread_ = std::thread([this] { run(); });
}

VoxelPager::~VoxelPager() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
  if (fd_ >= 0) ::close(fd_);
}

void VoxelPager::request(const glm::ivec3& loChunk, const glm::ivec3& hiChunk) noexcept {
  const std::uint64_t head = ringHead_.load(std::memory_order_relaxed);
  if (head - ringTail_.load(std::memory_order_acquire) >= kRingSize) {
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  ring_[head % kRingSize] = {loChunk, hiChunk};
  ringHead_.store(head + 1, std::memory_order_release);
}

void VoxelPager::makeResident(const glm::ivec3& loChunk, const glm::ivec3& hiChunk) {
  // through the ring, as the haptic thread asks, then wait until the pager has served it
  while (ringHead_.load() - ringTail_.load() >= kRingSize) std::this_thread::sleep_for(kIdle);
  request(loChunk, hiChunk);
  const std::uint64_t asked = ringHead_.load();
  while (ringTail_.load(std::memory_order_acquire) < asked) {
    beginFrame();  // no frame reads the voxmap yet: slots taken back need no grace
    std::this_thread::sleep_for(kIdle);
  }
}

void VoxelPager::run() {
  while (!stop_.load(std::memory_order_relaxed)) {
    const std::uint64_t tail = ringTail_.load(std::memory_order_relaxed);
    if (tail == ringHead_.load(std::memory_order_acquire)) {
      std::this_thread::sleep_for(kIdle);
      continue;
    }
    if (!serve(ring_[tail % kRingSize])) return;
    ringTail_.store(tail + 1, std::memory_order_release);
  }
}

bool VoxelPager::serve(const Box& box) {
  const glm::ivec3 lo = glm::max(box.lo, glm::ivec3(0));
  const glm::ivec3 hi = glm::min(box.hi, arrays_.grid.dimsChunks() - 1);
  const std::uint64_t now = frame_.load(std::memory_order_relaxed);
  for (int z = lo.z; z <= hi.z; ++z) {
    for (int y = lo.y; y <= hi.y; ++y) {
      for (int x = lo.x; x <= hi.x; ++x) {
        const std::int64_t index = arrays_.chunkEntryIndex({x, y, z});
        if (index < 0) continue;
        const auto entry = static_cast<std::size_t>(index);
        const std::uint32_t block = fileBlockOfEntry_[entry];
        if (block == kNone) continue;  // a uniform chunk: always resident
        std::uint32_t slot = slotOfEntry_[entry];
        if (slot == kNone) {
          slot = freeSlot();
          if (slot == kNone) return false;
          std::uint8_t* into = arrays_.pool + std::size_t{slot} * blockBytes_;
          const auto at = static_cast<off_t>(wordsOffset_ + std::uint64_t{block} * blockBytes_);
          if (::pread(fd_, into, blockBytes_, at) != static_cast<ssize_t>(blockBytes_)) continue;  // stays missing
          slotEntry_[slot] = static_cast<std::uint32_t>(entry);
          slotOfEntry_[entry] = slot;
          arrays_.publish(entry, slot);
          blocksRead_.fetch_add(1, std::memory_order_relaxed);
        }
        slotAskedFrame_[slot] = now;
      }
    }
  }
  return true;
}

std::uint32_t VoxelPager::freeSlot() {
  if (!freeSlots_.empty()) {
    const std::uint32_t slot = freeSlots_.back();
    freeSlots_.pop_back();
    return slot;
  }
  // take back a batch of the slots least recently asked for (clock), unpublish them, and
  // wait two frames so that no lookup still reads them
  const std::size_t batch = std::max<std::size_t>(1, slotEntry_.size() / 64);
  const std::uint64_t now = frame_.load();
  std::vector<std::uint32_t> taken;
  taken.reserve(batch);
  for (std::size_t looked = 0; looked < 2 * slotEntry_.size() && taken.size() < batch; ++looked) {
    const auto slot = static_cast<std::uint32_t>(clockHand_);
    clockHand_ = (clockHand_ + 1) % slotEntry_.size();
    const bool recent = slotAskedFrame_[slot] + kRecentFrames > now && looked < slotEntry_.size();
    if (slotEntry_[slot] == kNone || recent) continue;
    arrays_.publish(slotEntry_[slot], Voxmap::kUniform | Voxmap::kMissingWord);
    slotOfEntry_[slotEntry_[slot]] = kNone;
    slotEntry_[slot] = kNone;
    taken.push_back(slot);
  }
  const std::uint64_t unpublishedAt = frame_.load(std::memory_order_seq_cst);
  while (frame_.load(std::memory_order_seq_cst) < unpublishedAt + 2) {
    if (stop_.load(std::memory_order_relaxed)) return kNone;
    std::this_thread::sleep_for(kIdle);
  }
  freeSlots_.insert(freeSlots_.end(), taken.begin(), taken.end());
  if (freeSlots_.empty()) return kNone;
  const std::uint32_t slot = freeSlots_.back();
  freeSlots_.pop_back();
  return slot;
}

}  // namespace voxhap

#include "haptics/voxel/voxel_pager.h"

#include <algorithm>
#include <cassert>

#include <glm/common.hpp>

#include "haptics/core/error.h"

namespace voxhap {
namespace {

/// How long the pager sleeps when it has nothing to do, or waits.
constexpr auto kIdle = std::chrono::microseconds(200);
/// At most one slot in this many is taken back at once (at least one).
constexpr std::size_t kTakeBackShare = 64;

}  // namespace

VoxelPager::Reader& VoxelPager::Reader::operator=(Reader&& other) noexcept {
  if (this != &other) {
    release();
    pager_ = std::exchange(other.pager_, nullptr);
    index_ = other.index_;
  }
  return *this;
}

VoxelPager::Reader::~Reader() {
  release();
}

void VoxelPager::Reader::release() noexcept {
  if (!pager_) return;
  ReaderEpoch& r = pager_->readers_[index_];
  assert(r.epoch.load(std::memory_order_relaxed) == 0 && "a Reader given back inside a read section");
  r.epoch.store(0, std::memory_order_release);
  r.taken.store(false, std::memory_order_release);
  pager_ = nullptr;
}

void VoxelPager::Reader::enter() noexcept {
  pager_->enter(index_);
}
void VoxelPager::Reader::leave() noexcept {
  pager_->leave(index_);
}
void VoxelPager::Reader::quiescent() noexcept {
  pager_->enter(index_);
}

VoxelPager::VoxelPager(const Voxmap::PagedArrays& arrays, std::unique_ptr<BlockReader> reader,
                       std::vector<std::uint32_t> fileBlockOfEntry, std::size_t slotCount)
    : arrays_(arrays),
      reader_(std::move(reader)),
      blockBytes_(arrays.blockBytes),
      fileBlockOfEntry_(std::move(fileBlockOfEntry)),
      slotOfEntry_(fileBlockOfEntry_.size(), kNone),
      slotEntry_(slotCount, kNone) {
  if (slotCount == 0) throw Error("the voxel memory budget holds no chunk of voxel words");
  assert(arrays_.slotLastUse && arrays_.useClock && arrays_.slotCount == slotCount && "not a Voxmap::paged");
  assert(reader_);
  freeSlots_.reserve(slotCount);
  for (std::size_t s = slotCount; s-- > 0;) freeSlots_.push_back(static_cast<std::uint32_t>(s));
  byAge_.reserve(slotCount);
  readers_[kFrameReader].taken.store(true, std::memory_order_relaxed);
  lastSeenClock_ = arrays_.clockNow();
  lastClockChange_ = std::chrono::steady_clock::now();
  thread_ = std::thread([this] { run(); });
}

VoxelPager::VoxelPager(const Voxmap::PagedArrays& arrays, const std::filesystem::path& file,
                       std::uint64_t wordsOffset, std::vector<std::uint32_t> fileBlockOfEntry,
                       std::size_t slotCount)
    : VoxelPager(arrays, std::make_unique<FileBlockReader>(file, wordsOffset), std::move(fileBlockOfEntry),
                 slotCount) {}

VoxelPager::~VoxelPager() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

void VoxelPager::enter(std::size_t reader) noexcept {
  // seq_cst store: ordered before this section's (seq_cst) entry loads, see the header
  readers_[reader].epoch.store(epoch_.load(std::memory_order_seq_cst), std::memory_order_seq_cst);
}

void VoxelPager::leave(std::size_t reader) noexcept {
  // release: every word this section read happens before the pager sees it outside
  readers_[reader].epoch.store(0, std::memory_order_release);
}

void VoxelPager::beginFrame() noexcept {
  enter(kFrameReader);  // over the previous frame's epoch: leave and enter in one store
  arrays_.tick();
}

VoxelPager::Reader VoxelPager::addReader() {
  for (std::size_t i = kFrameReader + 1; i < kMaxReaders; ++i) {
    bool expected = false;
    if (readers_[i].taken.compare_exchange_strong(expected, true, std::memory_order_acq_rel))
      return {this, i};
  }
  throw Error("a paged voxmap takes at most " + std::to_string(kMaxReaders - 1) +
              " reader threads beside the haptic thread");
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
  // through the ring, as the haptic thread asks, then wait until the pager has served it;
  // while waiting, frames begin: the pager may be taking back a slot, which waits for the
  // frame reader's quiescent point (no frame reads the voxmap yet)
  const auto waitWhile = [this](auto pending) {
    while (pending()) {
      beginFrame();
      std::this_thread::sleep_for(kIdle);
    }
  };
  waitWhile([this] { return ringHead_.load() - ringTail_.load(std::memory_order_acquire) >= kRingSize; });
  request(loChunk, hiChunk);
  const std::uint64_t asked = ringHead_.load();
  waitWhile([this, asked] { return ringTail_.load(std::memory_order_acquire) < asked; });
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
  for (int z = lo.z; z <= hi.z; ++z) {
    for (int y = lo.y; y <= hi.y; ++y) {
      for (int x = lo.x; x <= hi.x; ++x) {
        const std::int64_t index = arrays_.chunkEntryIndex({x, y, z});
        if (index < 0) continue;
        const auto entry = static_cast<std::size_t>(index);
        const std::uint32_t block = fileBlockOfEntry_[entry];
        if (block == kNone) continue;  // a uniform chunk: always resident
        std::uint32_t slot = slotOfEntry_[entry];
        if (slot != kNone) {
          arrays_.markUse(slot, arrays_.clockNow());  // asked for: about to be read
          continue;
        }
        slot = freeSlot();
        if (slot == kNone) return false;
        // nothing reaches the slot now: it is free, or taken back after a grace period
        if (!reader_->read(block,
                           {arrays_.pool + std::size_t{slot} * arrays_.slotStrideBytes, blockBytes_})) {
          freeSlots_.push_back(slot);  // the chunk stays missing; a later request tries again
          readFailures_.fetch_add(1, std::memory_order_relaxed);
          continue;
        }
        slotEntry_[slot] = static_cast<std::uint32_t>(entry);
        slotOfEntry_[entry] = slot;
        arrays_.markUse(slot, arrays_.clockNow());
        arrays_.publish(entry, slot);  // release: after the words
        blocksRead_.fetch_add(1, std::memory_order_relaxed);
      }
    }
  }
  return true;
}

std::uint32_t VoxelPager::freeSlot() {
  if (freeSlots_.empty()) {
    std::vector<std::uint32_t> taken;
    for (;;) {
      if (stop_.load(std::memory_order_relaxed)) return kNone;
      takeBackLeastRecentlyUsed(taken);
      if (!taken.empty()) break;
      idleWhileWaiting();  // every slot in use: wait until some age
    }
    if (!waitForReaders()) return kNone;
    takenBack_.fetch_add(taken.size(), std::memory_order_relaxed);
    freeSlots_.insert(freeSlots_.end(), taken.begin(), taken.end());
  }
  const std::uint32_t slot = freeSlots_.back();
  freeSlots_.pop_back();
  return slot;
}

void VoxelPager::takeBackLeastRecentlyUsed(std::vector<std::uint32_t>& taken) {
  taken.clear();
  byAge_.clear();
  const std::uint32_t now = arrays_.clockNow();
  for (std::uint32_t slot = 0; slot < slotEntry_.size(); ++slot) {
    if (slotEntry_[slot] == kNone) continue;
    // a mark read ahead of this thread's view of the clock counts as now
    const auto age = static_cast<std::int32_t>(now - arrays_.lastUse(slot));
    if (age >= static_cast<std::int32_t>(kInUseTicks))
      byAge_.emplace_back(static_cast<std::uint32_t>(age), slot);
  }
  const std::size_t batch =
      std::min(byAge_.size(), std::max<std::size_t>(1, slotEntry_.size() / kTakeBackShare));
  if (batch == 0) return;
  // oldest first; equal ages by slot, so that runs repeat
  const auto older = [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  };
  std::partial_sort(byAge_.begin(), byAge_.begin() + static_cast<std::ptrdiff_t>(batch), byAge_.end(), older);
  for (std::size_t k = 0; k < batch; ++k) {
    const std::uint32_t slot = byAge_[k].second;
    arrays_.unpublish(slotEntry_[slot]);  // seq_cst: before the epoch bump and the loads
    slotOfEntry_[slotEntry_[slot]] = kNone;
    slotEntry_[slot] = kNone;
    taken.push_back(slot);
  }
}

bool VoxelPager::waitForReaders() {
  const std::uint64_t target = epoch_.fetch_add(1, std::memory_order_seq_cst) + 1;
  for (ReaderEpoch& reader : readers_) {
    for (;;) {
      // seq_cst: after the unpublish in the single total order (the header's case 3)
      const std::uint64_t epoch = reader.epoch.load(std::memory_order_seq_cst);
      if (epoch == 0 || epoch >= target) break;
      if (stop_.load(std::memory_order_relaxed)) return false;
      idleWhileWaiting();
    }
  }
  return true;
}

void VoxelPager::idleWhileWaiting() {
  std::this_thread::sleep_for(kIdle);
  const std::uint32_t now = arrays_.clockNow();
  const auto t = std::chrono::steady_clock::now();
  if (now != lastSeenClock_) {
    lastSeenClock_ = now;
    lastClockChange_ = t;
  } else if (t - lastClockChange_ >= kSelfTickInterval) {
    arrays_.tick();
    lastSeenClock_ = now + 1;
    lastClockChange_ = t;
  }
}

}  // namespace voxhap

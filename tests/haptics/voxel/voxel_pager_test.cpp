// The pager (paper §5.3): slots taken back by last use, failed reads that keep their
// slot, reader epochs that hold a slot until every reader is done with it, and readers
// racing the pager (run under the tsan preset too). Ground truth: the whole voxmap.
#include "haptics/voxel/voxel_pager.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <future>
#include <random>
#include <thread>

#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "haptics/sim/scene_model.h"
#include "haptics/voxel/voxel_cache.h"
#include "support/contact_scenes.h"
#include "support/gltf_fixtures.h"

namespace voxhap {
namespace {

namespace fs = std::filesystem;

constexpr double kVoxel = 0.0005;  // m
constexpr std::uint32_t kNotMixed = 0xFFFFFFFFu;

/// A plate with a post on it: a few hundred mixed chunks at 0.5 mm.
std::vector<SceneObject> plateAndPost() {
  std::vector<SceneObject> objects;
  objects.push_back(test::plate());
  objects.push_back(test::meshObject("post", ObjectRole::Static, [](TriangleMesh& m) {
    appendBox(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.02, 0.02, 0.01)),
              glm::dvec3(0.004, 0.004, 0.01));
  }));
  return objects;
}

VoxelizeOptions voxelOptions() {
  VoxelizeOptions options;
  options.voxelSizeM = kVoxel;
  return options;
}

Voxmap wholeVoxmap(const std::vector<SceneObject>& objects) {
  std::vector<const SceneObject*> pointers;
  for (const SceneObject& o : objects) pointers.push_back(&o);
  return voxelizeObjects(pointers, voxelOptions(), {});
}

/// Blocks of a whole voxmap's words, from memory: fails while `failuresLeft` > 0 (one
/// a read), and yields halfway through a block when `slow`, to widen any race window.
class MemoryBlocks final : public BlockReader {
public:
  explicit MemoryBlocks(const Voxmap& whole)
      : words_(whole.voxelBytes()),
        blockBytes_(std::size_t{kVoxelsPerChunk} * whole.encoding().bytesPerWord()) {}

  bool read(std::uint32_t block, std::span<std::uint8_t> into) noexcept override {
    reads.fetch_add(1, std::memory_order_relaxed);
    if (failuresLeft.load() > 0) {
      failuresLeft.fetch_sub(1);
      std::memset(into.data(), 0xAB, into.size() / 2);  // a short read leaves garbage behind
      return false;
    }
    const std::uint8_t* from = words_.data() + std::size_t{block} * blockBytes_;
    const std::size_t half = into.size() / 2;
    std::memcpy(into.data(), from, half);
    if (slow) std::this_thread::yield();
    std::memcpy(into.data() + half, from + half, into.size() - half);
    return true;
  }

  std::atomic<int> failuresLeft{0};
  std::atomic<std::uint64_t> reads{0};
  bool slow = false;

private:
  std::span<const std::uint8_t> words_;
  std::size_t blockBytes_;
};

/// A paged copy of a whole voxmap, its words read from memory through `blocks`.
struct PagedCopy {
  Voxmap voxmap;
  MemoryBlocks* blocks = nullptr;  // owned by the pager
  std::unique_ptr<VoxelPager> pager;
};

PagedCopy pagedCopy(const Voxmap& whole, std::size_t slots) {
  std::vector<std::uint32_t> hyper(whole.hyperEntries().begin(), whole.hyperEntries().end());
  std::vector<std::uint32_t> chunks(whole.chunkEntries().begin(), whole.chunkEntries().end());
  std::vector<std::uint8_t> distances(whole.chunkDistances().begin(), whole.chunkDistances().end());
  std::vector<std::uint32_t> blockOfEntry(chunks.size(), kNotMixed);
  for (std::size_t i = 0; i < chunks.size(); ++i) {
    if (chunks[i] & Voxmap::kUniform) continue;
    blockOfEntry[i] = chunks[i];
    chunks[i] = Voxmap::kUniform | Voxmap::kMissingWord;
  }
  PagedCopy copy;
  copy.voxmap = Voxmap::paged(whole.grid(), whole.encoding(), std::move(hyper), std::move(chunks), slots,
                              std::move(distances));
  auto blocks = std::make_unique<MemoryBlocks>(whole);
  copy.blocks = blocks.get();
  copy.pager = std::make_unique<VoxelPager>(copy.voxmap.pagedArrays(), std::move(blocks),
                                            std::move(blockOfEntry), slots);
  return copy;
}

/// The chunks of `whole` stored voxel by voxel, in grid order.
std::vector<glm::ivec3> mixedChunks(const Voxmap& whole) {
  std::vector<glm::ivec3> mixed;
  const glm::ivec3 dims = whole.grid().dimsChunks();
  const Voxmap::PagedArrays arrays = const_cast<Voxmap&>(whole).pagedArrays();
  for (int z = 0; z < dims.z; ++z) {
    for (int y = 0; y < dims.y; ++y) {
      for (int x = 0; x < dims.x; ++x) {
        const std::int64_t entry = arrays.chunkEntryIndex({x, y, z});
        if (entry >= 0 && !(whole.chunkEntries()[static_cast<std::size_t>(entry)] & Voxmap::kUniform)) {
          mixed.emplace_back(x, y, z);
        }
      }
    }
  }
  return mixed;
}

/// A voxel of chunk `chunk`, `k` (0 … 511) along its voxels.
glm::ivec3 voxelOf(const glm::ivec3& chunk, int k) {
  return chunk * kChunkEdgeVoxels + glm::ivec3(k % 8, (k / 8) % 8, k / 64);
}

/// Whether chunk `chunk` of `paged` is resident; when it is, its words must be `whole`'s.
bool resident(const Voxmap& paged, const Voxmap& whole, const glm::ivec3& chunk) {
  bool any = false;
  for (int k = 0; k < kVoxelsPerChunk; k += 37) {
    const VoxelWord w = paged.word(voxelOf(chunk, k));
    if (w == Voxmap::kMissingWord) return false;
    EXPECT_EQ(w, whole.word(voxelOf(chunk, k)));
    any = true;
  }
  return any;
}

class VoxelPagerTest : public ::testing::Test {
protected:
  std::vector<SceneObject> objects_ = plateAndPost();
  Voxmap whole_ = wholeVoxmap(objects_);
  std::vector<glm::ivec3> mixed_ = mixedChunks(whole_);
};

TEST_F(VoxelPagerTest, AChunkInUseStaysWhileUnusedOnesAreTakenBackLeastRecentlyUsedFirst) {
  constexpr std::size_t kSlots = 8;
  ASSERT_GE(mixed_.size(), 24u);
  PagedCopy p = pagedCopy(whole_, kSlots);
  // fill the pool: the chunk in use (read every frame from now on, never asked for
  // again) was asked for first, so a clock over requests would take it back first
  const glm::ivec3 inUse = mixed_[0];
  for (std::size_t k = 0; k < kSlots; ++k) p.pager->makeResident(mixed_[k], mixed_[k]);
  for (std::size_t k = 0; k < kSlots; ++k) ASSERT_TRUE(resident(p.voxmap, whole_, mixed_[k])) << k;

  for (std::size_t k = kSlots; k < 24; ++k) {
    p.pager->request(mixed_[k], mixed_[k]);
    bool arrived = false;
    for (int frame = 0; frame < 5000 && !arrived; ++frame) {
      p.pager->beginFrame();
      ASSERT_TRUE(resident(p.voxmap, whole_, inUse)) << "chunk " << k << ", frame " << frame;
      arrived = resident(p.voxmap, whole_, mixed_[k]);
      std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
    ASSERT_TRUE(arrived) << "chunk " << k;
    if (k == kSlots) {
      // the least recently used: the first filled after the one in use
      EXPECT_FALSE(resident(p.voxmap, whole_, mixed_[1]));
      for (std::size_t j = 2; j < kSlots; ++j) EXPECT_TRUE(resident(p.voxmap, whole_, mixed_[j])) << j;
    }
  }
  EXPECT_EQ(p.pager->slotsTakenBack(), 24u - kSlots);
  EXPECT_EQ(p.pager->readFailures(), 0u);
}

TEST_F(VoxelPagerTest, AFailedReadGivesItsSlotBackAndALaterRequestRetries) {
  constexpr std::size_t kSlots = 4;
  PagedCopy p = pagedCopy(whole_, kSlots);
  p.blocks->failuresLeft = 10;
  for (int k = 0; k < 10; ++k) p.pager->makeResident(mixed_[0], mixed_[0]);  // once slots leaked for good
  EXPECT_EQ(p.pager->readFailures(), 10u);
  EXPECT_FALSE(resident(p.voxmap, whole_, mixed_[0]));
  // every slot is still free: four chunks fit without taking any back
  for (std::size_t k = 1; k <= kSlots; ++k) p.pager->makeResident(mixed_[k], mixed_[k]);
  for (std::size_t k = 1; k <= kSlots; ++k) EXPECT_TRUE(resident(p.voxmap, whole_, mixed_[k])) << k;
  EXPECT_EQ(p.pager->slotsTakenBack(), 0u);
  // the failing chunk is asked for again and now reads
  p.pager->makeResident(mixed_[0], mixed_[0]);
  EXPECT_TRUE(resident(p.voxmap, whole_, mixed_[0]));
  EXPECT_EQ(p.pager->slotsTakenBack(), 1u);
  EXPECT_EQ(p.pager->readFailures(), 10u);
  EXPECT_EQ(p.pager->blocksRead(), kSlots + 1);
}

TEST_F(VoxelPagerTest, ATruncatedCacheFileFailsTheReadAndKeepsTheSlot) {
  test::TempDir dir;
  const CacheOptions cache{dir.path() / "voxels", true};
  std::vector<const SceneObject*> pointers;
  for (const SceneObject& o : objects_) pointers.push_back(&o);
  const std::uint64_t words = whole_.voxelBytes().size();
  BudgetedVoxmap paged =
      voxelizeWithinBudget(pointers, voxelOptions(), cache, whole_.memoryBytes() - words / 2);
  ASSERT_TRUE(paged.pager);
  fs::path file;
  for (const auto& entry : fs::directory_iterator(cache.directory)) {
    if (entry.path().filename().string().rfind("voxmap-", 0) == 0) file = entry.path();
  }
  ASSERT_FALSE(file.empty());
  const std::vector<unsigned char> bytes = test::readBytes(file);
  fs::resize_file(file, 4096);  // the same file, short: the pager's descriptor reads it
  const glm::ivec3 chunk = mixed_.back();
  for (int k = 0; k < 3; ++k) paged.pager->makeResident(chunk, chunk);
  EXPECT_EQ(paged.pager->readFailures(), 3u);
  EXPECT_FALSE(resident(paged.voxmap, whole_, chunk));
  {
    std::ofstream out(file, std::ios::binary | std::ios::in | std::ios::out);  // same inode
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }
  paged.pager->makeResident(chunk, chunk);
  EXPECT_TRUE(resident(paged.voxmap, whole_, chunk));
  EXPECT_EQ(paged.pager->slotsTakenBack(), 0u);
}

TEST_F(VoxelPagerTest, ASlotIsRewrittenOnlyAfterEveryRegisteredReaderLeft) {
  constexpr std::size_t kSlots = 4;
  PagedCopy p = pagedCopy(whole_, kSlots);
  for (std::size_t k = 0; k < kSlots; ++k) p.pager->makeResident(mixed_[k], mixed_[k]);
  VoxelPager::Reader reader = p.pager->addReader();
  reader.enter();  // a reader inside a section, on any thread, holds every slot it might read
  p.pager->request(mixed_[kSlots], mixed_[kSlots]);
  for (int frame = 0; frame < 200; ++frame) {
    p.pager->beginFrame();
    std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
  EXPECT_FALSE(resident(p.voxmap, whole_, mixed_[kSlots]));  // the pager waits for the reader
  EXPECT_EQ(p.pager->slotsTakenBack(), 0u);
  reader.leave();
  bool arrived = false;
  for (int frame = 0; frame < 5000 && !arrived; ++frame) {
    p.pager->beginFrame();
    arrived = resident(p.voxmap, whole_, mixed_[kSlots]);
    std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
  EXPECT_TRUE(arrived);
  EXPECT_EQ(p.pager->slotsTakenBack(), 1u);
}

TEST_F(VoxelPagerTest, ReadersAreBoundedAndTheirPlacesComeBack) {
  PagedCopy p = pagedCopy(whole_, 4);
  std::vector<VoxelPager::Reader> readers;
  for (std::size_t k = 1; k < VoxelPager::kMaxReaders; ++k) readers.push_back(p.pager->addReader());
  EXPECT_THROW(p.pager->addReader(), Error);
  readers.pop_back();
  VoxelPager::Reader again = p.pager->addReader();
  {
    VoxelPager::ReadSection section(again);
    EXPECT_EQ(p.voxmap.word(voxelOf(mixed_[0], 0)), Voxmap::kMissingWord);  // nothing asked for yet
  }
}

TEST_F(VoxelPagerTest, MakeResidentBehindAFullRingLetsThePagerTakeASlotBack) {
  // a CI run once hung here: the ring full, the pager taking a slot back and waiting for
  // the frame reader's quiescent point, makeResident waiting for room in the ring
  constexpr std::size_t kSlots = 4;
  PagedCopy p = pagedCopy(whole_, kSlots);
  for (std::size_t k = 0; k < kSlots; ++k) p.pager->makeResident(mixed_[k], mixed_[k]);
  for (std::uint32_t tick = 0; tick <= VoxelPager::kInUseTicks; ++tick) p.pager->beginFrame();
  // the first request takes a slot back, which waits for the next beginFrame(): the rest fill the ring
  while (p.pager->requestsDropped() == 0) p.pager->request(mixed_[kSlots], mixed_[kSlots]);
  auto served =
      std::async(std::launch::async, [&] { p.pager->makeResident(mixed_[kSlots + 1], mixed_[kSlots + 1]); });
  if (served.wait_for(std::chrono::seconds(60)) != std::future_status::ready) {
    std::fputs("makeResident still waits after 60 s: the pager and the frame thread wait for each other\n",
               stderr);
    std::abort();  // a test that waits for ever would take ctest's whole timeout
  }
  EXPECT_TRUE(resident(p.voxmap, whole_, mixed_[kSlots]));
  EXPECT_TRUE(resident(p.voxmap, whole_, mixed_[kSlots + 1]));
  EXPECT_EQ(p.pager->slotsTakenBack(), 2u);
}

TEST_F(VoxelPagerTest, ReadersRacingThePagerReadTheWholeVoxmapsWordsOrMissing) {
  constexpr std::size_t kSlots = 12;
  constexpr std::size_t kWindow = 3;  // chunks in use at once, fewer than the slots
  constexpr int kReaders = 3;
  constexpr int kFrames = 3000;
  ASSERT_GT(mixed_.size(), 4 * kSlots);
  PagedCopy p = pagedCopy(whole_, kSlots);
  p.blocks->slow = true;
  // a window of chunks slides over the mixed chunks, as a moving object's reach does: the
  // frame thread asks for it, every reader reads in it; slots change hands behind it
  std::atomic<std::size_t> window{0};
  std::atomic<bool> stop{false};
  std::atomic<std::uint64_t> mismatches{0};
  std::vector<std::uint64_t> matched(kReaders + 1, 0);
  // false when the voxel's chunk is missing
  auto check = [&](const glm::ivec3& v, int who) {
    const VoxelWord w = p.voxmap.word(v);
    if (w == Voxmap::kMissingWord) return false;
    if (w == whole_.word(v)) {
      ++matched[static_cast<std::size_t>(who)];
    } else {
      mismatches.fetch_add(1, std::memory_order_relaxed);
    }
    return true;
  };
  std::vector<std::thread> threads;
  for (int r = 0; r < kReaders; ++r) {
    threads.emplace_back([&, r, reader = p.pager->addReader()]() mutable {
      std::mt19937 random(static_cast<std::uint32_t>(100 + r));
      std::uniform_int_distribution<std::size_t> inWindow(0, kWindow - 1);
      std::uniform_int_distribution<int> voxel(0, kVoxelsPerChunk - 1);
      while (!stop.load(std::memory_order_relaxed)) {
        {
          VoxelPager::ReadSection section(reader);
          for (int k = 0; k < 64; ++k) {
            check(voxelOf(mixed_[window.load(std::memory_order_relaxed) + inWindow(random)], voxel(random)),
                  r);
          }
        }
        std::this_thread::sleep_for(std::chrono::microseconds(20));  // the machine has two cores
      }
    });
  }
  // the frame thread reads in the window and asks for what it misses, as the haptic
  // thread does; the window moves on every fourth frame
  const std::size_t positions = mixed_.size() - kWindow;
  for (int frame = 0; frame < kFrames; ++frame) {
    p.pager->beginFrame();
    const std::size_t w = static_cast<std::size_t>(frame / 4) % positions;
    window.store(w, std::memory_order_relaxed);
    for (std::size_t k = 0; k < kWindow; ++k) {
      bool missing = false;
      for (int v = 0; v < kVoxelsPerChunk; v += 61) missing |= !check(voxelOf(mixed_[w + k], v), kReaders);
      if (missing) p.pager->request(mixed_[w + k], mixed_[w + k]);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
  const glm::ivec3 last = mixed_[window.load() + kWindow - 1];
  p.pager->makeResident(last, last);  // behind every request still queued
  for (int v = 0; v < kVoxelsPerChunk; v += 7) EXPECT_TRUE(check(voxelOf(last, v), kReaders)) << v;
  stop = true;
  for (std::thread& t : threads) t.join();

  EXPECT_EQ(mismatches.load(), 0u);
  for (int r = 0; r <= kReaders; ++r) EXPECT_GT(matched[static_cast<std::size_t>(r)], 0u) << "reader " << r;
  EXPECT_GT(p.pager->slotsTakenBack(), kSlots);  // slots changed hands under the readers
  EXPECT_EQ(p.pager->readFailures(), 0u);
}

}  // namespace
}  // namespace voxhap

#include "haptics/coherence/pair_coherence.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "haptics/coherence/max_travel.h"
#include "haptics/collide/point_sampler_avx2.h"
#include "haptics/runtime/frame_helper.h"

namespace voxhap {
namespace {

/// Chunk queues: 0 in range (points queued), 1 must test now, j ≥ 2 collapsed with a gap
/// of at least j chunks.
constexpr int kChunkQueues = 16;
constexpr int kChunkInRange = 0;
constexpr int kChunkTestNow = 1;
/// A chunk in range collapses at a gap of this many chunks; a collapsed one is disgorged
/// under kCollapsedMin (the difference keeps chunks from flapping).
constexpr int kCollapseAt = 3;
constexpr int kCollapsedMin = 2;
/// Points whose voxel words testShare reads before it looks at any of them.
constexpr std::uint32_t kTestBatch = 16;

}  // namespace

// Room for the queues of the lowest force layer, so that setForceLayer never allocates.
PairCoherence::PairCoherence(const Pointshell& shell, double voxelSizeM, std::uint8_t forceLayer,
                             std::uint8_t maxValue, bool drifting)
    : points_(static_cast<std::uint32_t>(shell.size()), queueCountFor(1, maxValue)),
      chunks_(static_cast<std::uint32_t>(shell.chunkCount()), kChunkQueues),
      chunkBegin_(shell.chunkBegin),
      voxelSizeM_(voxelSizeM),
      forceLayer_(forceLayer),
      maxValue_(maxValue),
      dueEndByQueue_(static_cast<std::size_t>(queueCountFor(1, maxValue)), 0),
      drifting_(drifting),
      lookupVoxel_(drifting ? shell.size() : 0),
      lookupQueue_(drifting ? shell.size() : 0, 0),
      moves_(shell.size()) {
  for (std::size_t c = 0; c < shell.chunkCount(); ++c) {
    float radiusM = 0.0f;
    for (std::uint32_t p = chunkBegin_[c]; p < chunkBegin_[c + 1]; ++p) {
      radiusM = std::max(radiusM, glm::length(shell.positionsLocal[p] - shell.chunkCentroidsLocal[c]));
    }
    chunkRadiusVoxels_.push_back(static_cast<float>(radiusM / voxelSizeM));
  }
  chunks_.queues().assignAll(kChunkTestNow);
}

double PairCoherence::pointDistanceM(int q) const noexcept {
  return q < kMandatoryQueues ? 0.0 : voxelsToContact(q) * voxelSizeM_;
}

double PairCoherence::chunkDistanceM(int q) const noexcept {
  const double chunkM = kChunkEdgeVoxels * voxelSizeM_;
  if (q == kChunkInRange) return chunkM;  // not for safety: how soon it may collapse
  return q == kChunkTestNow ? 0.0 : (q - 1) * chunkM;
}

int PairCoherence::chunkClass(const Voxmap& voxmap, const glm::vec3& voxelOfCentroid,
                              std::uint32_t chunk) const noexcept {
  const glm::ivec3 ijkChunk(static_cast<int>(std::floor(voxelOfCentroid.x / kChunkEdgeVoxels)),
                            static_cast<int>(std::floor(voxelOfCentroid.y / kChunkEdgeVoxels)),
                            static_cast<int>(std::floor(voxelOfCentroid.z / kChunkEdgeVoxels)));
  const int d = voxmap.chunkDistance(ijkChunk);
  const double gapVoxels = double((d - 1) * kChunkEdgeVoxels) - double(chunkRadiusVoxels_[chunk]);
  if (gapVoxels < 0.0) return kChunkInRange;
  return std::min(kChunkQueues - 1, static_cast<int>(gapVoxels / kChunkEdgeVoxels));
}

void PairCoherence::askAround(VoxelPager* pager, const glm::vec3& voxel, float radiusVoxels) noexcept {
  if (!pager) return;
  const auto chunkOf = [](float v) { return static_cast<int>(std::floor(v / kChunkEdgeVoxels)); };
  const glm::vec3 lo = voxel - radiusVoxels;
  const glm::vec3 hi = voxel + radiusVoxels;
  pager->request({chunkOf(lo.x), chunkOf(lo.y), chunkOf(lo.z)},
                 {chunkOf(hi.x), chunkOf(hi.y), chunkOf(hi.z)});
}

void PairCoherence::testChunk(std::uint32_t chunk, int from, int to, const glm::vec3& voxelOfCentroid,
                              VoxelPager* pager) noexcept {
  PointQueues& chunks = chunks_.queues();
  const std::uint32_t first = chunkBegin_[chunk];
  const std::uint32_t last = chunkBegin_[chunk + 1];
  if (from == kChunkInRange) {
    if (to < kCollapseAt) return;
    points_.queues().removeRange(first, last);
    chunks.move(chunk, from, to);
  } else if (to >= kCollapsedMin) {
    chunks.move(chunk, from, to);
  } else {  // disgorged: every point still reads far; its voxels are wanted soon
    points_.queues().insertRange(first, last, queueForValue(kValueFar, forceLayer_, maxValue_));
    askAround(pager, voxelOfCentroid, chunkRadiusVoxels_[chunk] + kChunkEdgeVoxels);
    if (drifting_) std::fill(lookupQueue_.begin() + first, lookupQueue_.begin() + last, std::uint8_t{0});
    chunks.move(chunk, from, kChunkInRange);
  }
}

void PairCoherence::sortAll(const Pointshell& shell, const Voxmap& voxmap, const VoxelTransform& transform,
                            const std::array<std::uint8_t, 3>& fieldShifts, VoxelPager* pager) {
  points_.queues().clear();
  chunks_.queues().assignAll(kChunkTestNow);
  for (std::uint32_t c = 0; c < shell.chunkCount(); ++c) {
    const glm::vec3 centroid = transform.apply(shell.chunkCentroidsLocal[c]);
    const int to = chunkClass(voxmap, centroid, c);
    if (to >= kCollapsedMin) {
      chunks_.queues().move(c, kChunkTestNow, to);
      continue;
    }
    if (pager) {
      const glm::vec3 reach(chunkRadiusVoxels_[c] + kChunkEdgeVoxels);
      const auto chunkOf = [](const glm::vec3& v) {
        return glm::ivec3(glm::floor(v / float(kChunkEdgeVoxels)));
      };
      pager->makeResident(chunkOf(centroid - reach), chunkOf(centroid + reach));
    }
    chunks_.queues().move(c, kChunkTestNow, kChunkInRange);
    for (std::uint32_t p = chunkBegin_[c]; p < chunkBegin_[c + 1]; ++p) {
      const PointSample sample = samplePointAt(shell, voxmap, transform, fieldShifts, p);
      // a chunk the pool could not keep: the point is tested again in the first frame
      points_.queues().insert(p, sample.missing ? 1 : queueForValue(sample.value, forceLayer_, maxValue_));
      if (drifting_) lookupQueue_[p] = 0;  // tested at load, but start every point afresh
    }
  }
  points_.clearOwed();
  chunks_.clearOwed();
  lastTravelM_ = 0.0;
}

void PairCoherence::skipFrame(double relativeTravelM) noexcept {
  if (chunks_.queues().count(kChunkTestNow) != chunks_.queues().pointCount()) {
    points_.queues().clear();
    chunks_.queues().assignAll(kChunkTestNow);
  }
  points_.clearOwed();
  chunks_.clearOwed();
  lastTravelM_ = relativeTravelM;
}

void PairCoherence::setForceLayer(std::uint8_t forceLayer) noexcept {
  PointQueues& queues = points_.queues();
  for (int q = 0; q < queues.queueCount(); ++q) queues.mergeInto(q, 1);
  std::fill(lookupQueue_.begin(), lookupQueue_.end(), std::uint8_t{0});
  forceLayer_ = forceLayer;
}

bool PairCoherence::onlyCollapsed() const noexcept {
  const PointQueues& chunks = chunks_.queues();
  return chunks.count(kChunkInRange) == 0 && chunks.count(kChunkTestNow) == 0;
}

CoherenceLoad PairCoherence::load(double fullTravelM) const noexcept {
  CoherenceLoad load;
  const PointQueues& points = points_.queues();
  for (int q = 0; q < queueCountFor(forceLayer_, maxValue_); ++q) {
    const double d = pointDistanceM(q);
    if (d > 0.0) {
      points_.addTestsByTravel(q, d, fullTravelM, lastTravelM_, load.tests);
    } else {
      load.mandatory += points.count(q);
    }
  }
  for (int q = 0; q < kChunkQueues; ++q) {
    const double d = chunkDistanceM(q);
    if (d > 0.0) {
      chunks_.addTestsByTravel(q, d, fullTravelM, lastTravelM_, load.tests);
    } else {
      load.mandatory += chunks_.queues().count(q);
    }
  }
  return load;
}

std::uint32_t PairCoherence::updateChunks(const Pointshell& shell, const Voxmap& voxmap,
                                          const VoxelTransform& transform, std::span<std::uint32_t> scratch,
                                          VoxelPager* pager) noexcept {
  std::uint32_t tests = 0;
  for (int q = 0; q < kChunkQueues; ++q) {
    const std::uint32_t n = chunks_.collect(q, chunkDistanceM(q), lastTravelM_, scratch);
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t c = scratch[i];
      const glm::vec3 centroid = transform.apply(shell.chunkCentroidsLocal[c]);
      testChunk(c, q, chunkClass(voxmap, centroid, c), centroid, pager);
    }
    tests += n;
  }
  return tests;
}

std::uint32_t PairCoherence::collectDue(std::span<std::uint32_t> due) noexcept {
  std::uint32_t n = 0;
  const int queueCount = queueCountFor(forceLayer_, maxValue_);
  for (int q = 0; q < queueCount; ++q) {
    n += points_.collect(q, pointDistanceM(q), lastTravelM_, due.subspan(n));
    dueEndByQueue_[static_cast<std::size_t>(q)] = n;
  }
  return n;
}

PairCoherence::Tested PairCoherence::testDue(const Pointshell& shell, const Voxmap& voxmap,
                                             const VoxelTransform& transform,
                                             const std::array<std::uint8_t, 3>& fieldShifts,
                                             std::uint8_t sampledLayer, std::span<const std::uint32_t> due,
                                             PointContact* contacts, VoxelPager* pager,
                                             FrameHelper* helper) noexcept {
  const auto n = static_cast<std::uint32_t>(due.size());
  // the helper takes the last half; a paged voxmap is read by the haptic thread alone
  const std::uint32_t mine = helper && !pager && n >= kHelpedTests ? n / 2 : n;
  Share theirs;
  auto helperShare = [&] {
    theirs = testShare(shell, voxmap, transform, fieldShifts, sampledLayer, due, mine, n, contacts + mine);
  };
  if (mine < n) helper->run(helperShare);
  const Share first = testShare(shell, voxmap, transform, fieldShifts, sampledLayer, due, 0, mine, contacts);
  Tested tested;
  moveTested(shell, transform, first, 0, pager, tested);
  tested.contacts = first.contacts;
  if (mine < n) {
    helper->finish();
    if (first.contacts < mine)
      std::copy(contacts + mine, contacts + mine + theirs.contacts, contacts + first.contacts);
    moveTested(shell, transform, theirs, mine, pager, tested);
    tested.contacts += theirs.contacts;
  }
  return tested;
}

PairCoherence::Share PairCoherence::testShare(const Pointshell& shell, const Voxmap& voxmap,
                                              const VoxelTransform& transform,
                                              const std::array<std::uint8_t, 3>& fieldShifts,
                                              std::uint8_t sampledLayer, std::span<const std::uint32_t> due,
                                              std::uint32_t begin, std::uint32_t end,
                                              PointContact* contacts) noexcept {
  Share share;
  Move* moves = moves_.data() + begin;
  const VoxelWord fieldMask = voxmap.encoding().fieldMask();
  std::uint32_t at = begin;
  const int queueCount = queueCountFor(forceLayer_, maxValue_);
  const bool avx2 = pointTestPathFor(voxmap) == PointTestPath::Avx2;
  for (int q = 0; q < queueCount && at < end; ++q) {
    const std::uint32_t queueEnd = std::min(dueEndByQueue_[static_cast<std::size_t>(q)], end);
    const bool mayDrift = drifting_ && q >= kMandatoryQueues;
    const auto from = static_cast<std::uint8_t>(q);
    while (at < queueEnd) {
      // Each batch reads its voxel words first, all independent loads (eight at a time
      // with AVX2), so that their cache misses overlap; then classifies the points in
      // order, as one at a time would. Points that drifted no nearer than two voxels from
      // their last lookup read nothing.
      const std::uint32_t batch = std::min<std::uint32_t>(kTestBatch, queueEnd - at);
      std::array<glm::vec3, kTestBatch> voxels;
      std::array<float, kTestBatch> guaranteedVoxels;  // by the last lookup, drifting; else 0
      std::array<glm::ivec3, kTestBatch> ijks;         // of the points that read, in order
      std::array<VoxelWord, kTestBatch> words;
      std::uint32_t reads = 0;
      for (std::uint32_t k = 0; k < batch; ++k) {
        const std::uint32_t point = due[at + k];
        voxels[k] = transform.apply(shell.positionsLocal[point]);
        guaranteedVoxels[k] = mayDrift && lookupQueue_[point] >= kMandatoryQueues
                                  ? static_cast<float>(voxelsToContact(lookupQueue_[point])) -
                                        glm::length(voxels[k] - lookupVoxel_[point])
                                  : 0.0f;
        if (guaranteedVoxels[k] < 2.0f) ijks[reads++] = voxelOf(voxels[k]);
      }
      const std::uint32_t vectorReads = avx2 ? reads & ~7u : 0;
      if (vectorReads > 0) voxelWordsAvx2(voxmap, ijks.data(), vectorReads, words.data());
      for (std::uint32_t r = vectorReads; r < reads; ++r) words[r] = voxmap.word(ijks[r]);
      std::uint32_t read = 0;
      for (std::uint32_t k = 0; k < batch; ++k, ++at) {
        const std::uint32_t point = due[at];
        if (guaranteedVoxels[k] >= 2.0f) {
          ++share.drifted;
          const int to = std::min(q, static_cast<int>(guaranteedVoxels[k]) + 1);
          if (to != q) moves[share.moves++] = {point, from, static_cast<std::uint8_t>(to), false};
          continue;
        }
        const glm::ivec3 ijk = ijks[read];
        const VoxelWord word = words[read++];
        if (word == Voxmap::kMissingWord) {  // tested again once its chunk is (asked to be) resident
          moves[share.moves++] = {point, from, 1, true};
          if (drifting_) lookupQueue_[point] = 0;
          continue;
        }
        const std::uint8_t value =
            fieldValue(word, fieldShifts[static_cast<std::size_t>(shell.features[point])], fieldMask);
        // value − 1 wraps far (0) to 255, so one compare keeps [1, sampledLayer]
        if (static_cast<std::uint8_t>(value - 1u) < sampledLayer) {
          PointContact& contact = contacts[share.contacts++];  // field by field, as samplePoints
          contact.point = point;
          contact.ijkVoxel = ijk;
          contact.value = value;
        }
        const auto to = static_cast<std::uint8_t>(queueForValue(value, forceLayer_, maxValue_));
        if (to != from) moves[share.moves++] = {point, from, to, false};
        if (drifting_) {
          lookupVoxel_[point] = voxels[k];
          lookupQueue_[point] = to;
        }
      }
    }
  }
  return share;
}

void PairCoherence::moveTested(const Pointshell& shell, const VoxelTransform& transform, const Share& share,
                               std::uint32_t begin, VoxelPager* pager, Tested& tested) noexcept {
  PointQueues& queues = points_.queues();
  tested.drifted += share.drifted;
  for (const Move& m : std::span(moves_).subspan(begin, share.moves)) {
    queues.move(m.point, m.from, m.to);
    if (!m.missing) continue;
    ++tested.missing;
    const glm::vec3 voxel = transform.apply(shell.positionsLocal[m.point]);
    const glm::ivec3 chunk = glm::ivec3(glm::floor(voxel / float(kChunkEdgeVoxels)));
    if (chunk != tested.lastAskedChunk) askAround(pager, voxel, kChunkEdgeVoxels);
    tested.lastAskedChunk = chunk;  // neighbours miss together: one request for a run of them
  }
}

}  // namespace voxhap

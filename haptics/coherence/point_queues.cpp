#include "haptics/coherence/point_queues.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <numeric>

namespace voxhap {

namespace {

/// Sweep blocks wanted in a round, where there are as many words.
constexpr std::uint32_t kMinSweepBlocks = 512;

std::uint32_t blockWordsFor(std::uint32_t wordCount) {
  std::uint32_t words = 32;
  while (words > 1 && wordCount / words < kMinSweepBlocks) words /= 2;
  return words;
}

/// The order in which sweeps visit `blockCount` blocks: block b at step b · G mod
/// blockCount, G near its golden section and prime to it, so that the steps of any run
/// of neighbouring blocks are spread evenly over the round.
std::vector<std::uint32_t> sweepOrderFor(std::uint32_t blockCount) {
  auto g = std::max<std::uint32_t>(1, static_cast<std::uint32_t>(std::lround(0.618034 * blockCount)));
  while (std::gcd(g, blockCount) != 1) ++g;
  std::vector<std::uint32_t> order(blockCount);
  for (std::uint32_t b = 0; b < blockCount; ++b) order[std::uint64_t{b} * g % blockCount] = b;
  return order;
}

}  // namespace

PointQueues::PointQueues(std::uint32_t pointCount, int queueCount)
    : pointCount_(pointCount),
      wordCount_((pointCount + kWordBits - 1) / kWordBits),
      summaryCount_((wordCount_ + kWordBits - 1) / kWordBits),
      blockWords_(blockWordsFor(wordCount_)),
      blockCount_(std::max<std::uint32_t>(1, (wordCount_ + blockWords_ - 1) / blockWords_)),
      sweepOrder_(sweepOrderFor(blockCount_)),
      bits_(static_cast<std::size_t>(queueCount) * wordCount_, 0),
      summary_(static_cast<std::size_t>(queueCount) * summaryCount_, 0),
      counts_(static_cast<std::size_t>(queueCount), 0),
      cursors_(static_cast<std::size_t>(queueCount), 0) {
  assert(queueCount >= 1);
}

int PointQueues::queueOf(std::uint32_t point) const noexcept {
  const std::uint32_t w = point / kWordBits;
  const std::uint32_t bit = 1u << (point % kWordBits);
  for (int q = 0; q < queueCount(); ++q) {
    if (words(q)[w] & bit) return q;
  }
  return -1;
}

void PointQueues::insert(std::uint32_t point, int q) noexcept {
  const std::uint32_t w = point / kWordBits;
  assert(!(words(q)[w] & (1u << (point % kWordBits))));
  words(q)[w] |= 1u << (point % kWordBits);
  summary(q)[w / kWordBits] |= 1u << (w % kWordBits);
  ++counts_[static_cast<std::size_t>(q)];
}

void PointQueues::remove(std::uint32_t point, int q) noexcept {
  const std::uint32_t w = point / kWordBits;
  std::uint32_t& word = words(q)[w];
  assert(word & (1u << (point % kWordBits)));
  word &= ~(1u << (point % kWordBits));
  if (word == 0) summary(q)[w / kWordBits] &= ~(1u << (w % kWordBits));
  --counts_[static_cast<std::size_t>(q)];
}

void PointQueues::move(std::uint32_t point, int from, int to) noexcept {
  if (from == to) return;
  remove(point, from);
  insert(point, to);
}

void PointQueues::insertRange(std::uint32_t first, std::uint32_t last, int q) noexcept {
  for (std::uint32_t p = first; p < last; ++p) insert(p, q);
}

void PointQueues::clear() noexcept {
  std::fill(bits_.begin(), bits_.end(), 0u);
  std::fill(summary_.begin(), summary_.end(), 0u);
  std::fill(counts_.begin(), counts_.end(), 0u);
}

void PointQueues::mergeInto(int from, int to) noexcept {
  if (from == to) return;
  std::uint32_t* source = words(from);
  std::uint32_t* target = words(to);
  for (std::uint32_t w = 0; w < wordCount_; ++w) {
    target[w] |= source[w];
    source[w] = 0;
  }
  std::uint32_t* sourceSummary = summary(from);
  std::uint32_t* targetSummary = summary(to);
  for (std::uint32_t w = 0; w < summaryCount_; ++w) {
    targetSummary[w] |= sourceSummary[w];
    sourceSummary[w] = 0;
  }
  counts_[static_cast<std::size_t>(to)] += counts_[static_cast<std::size_t>(from)];
  counts_[static_cast<std::size_t>(from)] = 0;
}

void PointQueues::removeRange(std::uint32_t first, std::uint32_t last) noexcept {
  for (int q = 0; q < queueCount(); ++q) {
    if (counts_[static_cast<std::size_t>(q)] == 0) continue;
    for (std::uint32_t p = first; p < last; ++p) {
      if (words(q)[p / kWordBits] & (1u << (p % kWordBits))) remove(p, q);
    }
  }
}

void PointQueues::assignAll(int q) noexcept {
  clear();
  if (pointCount_ == 0) return;
  std::uint32_t* w = words(q);
  std::fill(w, w + wordCount_, ~0u);
  if (pointCount_ % kWordBits) w[wordCount_ - 1] = (1u << (pointCount_ % kWordBits)) - 1u;
  std::uint32_t* s = summary(q);
  std::fill(s, s + summaryCount_, ~0u);
  if (wordCount_ % kWordBits) s[summaryCount_ - 1] = (1u << (wordCount_ % kWordBits)) - 1u;
  counts_[static_cast<std::size_t>(q)] = pointCount_;
}

std::uint32_t PointQueues::nonEmptyWords(int q, std::uint32_t block) const noexcept {
  const std::uint32_t firstWord = block * blockWords_;
  if (firstWord >= wordCount_) return 0;
  // the block's words lie within one summary word
  const std::uint32_t bits = summary(q)[firstWord / kWordBits] >> (firstWord % kWordBits);
  return blockWords_ < kWordBits ? bits & ((1u << blockWords_) - 1u) : bits;
}

std::uint32_t PointQueues::blockPoints(int q, std::uint32_t block) const noexcept {
  const std::uint32_t* w = words(q) + block * blockWords_;
  std::uint32_t points = 0;
  for (std::uint32_t bits = nonEmptyWords(q, block); bits; bits &= bits - 1) {
    points += static_cast<std::uint32_t>(std::popcount(w[std::countr_zero(bits)]));
  }
  return points;
}

std::uint32_t PointQueues::takeBlock(int q, std::uint32_t block, std::span<std::uint32_t> out,
                                     std::uint32_t at) const noexcept {
  const std::uint32_t points = blockPoints(q, block);
  if (points > out.size() - at) return kNoRoom;
  for (std::uint32_t bits = nonEmptyWords(q, block); bits; bits &= bits - 1) {
    const std::uint32_t wi = block * blockWords_ + static_cast<std::uint32_t>(std::countr_zero(bits));
    for (std::uint32_t word = words(q)[wi]; word; word &= word - 1) {
      out[at++] = wi * kWordBits + static_cast<std::uint32_t>(std::countr_zero(word));
    }
  }
  return points;
}

void PointQueues::pointsAhead(int q, std::span<const std::uint32_t> blockMarks,
                              std::span<std::uint32_t> points) const noexcept {
  std::uint32_t step = cursors_[static_cast<std::size_t>(q)];
  std::uint32_t passed = 0;
  std::uint32_t sum = 0;
  for (std::size_t k = 0; k < blockMarks.size(); ++k) {
    for (; passed < std::min(blockMarks[k], blockCount_); ++passed) {
      sum += blockPoints(q, sweepOrder_[step]);
      step = step + 1 == blockCount_ ? 0 : step + 1;
    }
    points[k] = sum;
  }
}

PointQueues::Sweep PointQueues::takeSweep(int q, std::uint32_t minBlocks,
                                          std::span<std::uint32_t> out) noexcept {
  Sweep sweep;
  const auto qi = static_cast<std::size_t>(q);
  const std::uint32_t count = counts_[qi];
  const std::uint32_t mustCover = std::min(minBlocks, blockCount_);
  std::uint32_t& step = cursors_[qi];
  while (sweep.coveredBlocks < mustCover && sweep.taken < count) {
    const std::uint32_t taken = takeBlock(q, sweepOrder_[step], out, sweep.taken);
    if (taken == kNoRoom) break;
    sweep.taken += taken;
    ++sweep.coveredBlocks;
    step = step + 1 == blockCount_ ? 0 : step + 1;
  }
  if (sweep.taken == count && sweep.coveredBlocks < mustCover) {  // nobody left to pass over
    step = static_cast<std::uint32_t>((std::uint64_t{step} + mustCover - sweep.coveredBlocks) % blockCount_);
    sweep.coveredBlocks = mustCover;
  }
  return sweep;
}

std::uint32_t PointQueues::takeAll(int q, std::span<std::uint32_t> out) const noexcept {
  const std::uint32_t* w = words(q);
  const std::uint32_t* s = summary(q);
  std::uint32_t written = 0;
  for (std::uint32_t si = 0; si < summaryCount_; ++si) {
    for (std::uint32_t nonEmpty = s[si]; nonEmpty; nonEmpty &= nonEmpty - 1) {
      const std::uint32_t wi = si * kWordBits + static_cast<std::uint32_t>(std::countr_zero(nonEmpty));
      for (std::uint32_t word = w[wi]; word; word &= word - 1) {
        if (written == out.size()) return written;
        out[written++] = wi * kWordBits + static_cast<std::uint32_t>(std::countr_zero(word));
      }
    }
  }
  return written;
}

}  // namespace voxhap

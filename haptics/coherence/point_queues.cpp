#include "haptics/coherence/point_queues.h"

#include <algorithm>
#include <bit>
#include <cassert>

namespace voxhap {

PointQueues::PointQueues(std::uint32_t pointCount, int queueCount)
    : pointCount_(pointCount),
      wordCount_((pointCount + kWordBits - 1) / kWordBits),
      summaryCount_((wordCount_ + kWordBits - 1) / kWordBits),
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

std::uint32_t PointQueues::nextAtOrAfter(int q, std::uint32_t from) const noexcept {
  if (from >= pointCount_) return pointCount_;
  const std::uint32_t* w = words(q);
  const std::uint32_t* s = summary(q);
  std::uint32_t wi = from / kWordBits;
  // the rest of the first word
  const std::uint32_t head = w[wi] & (~0u << (from % kWordBits));
  if (head) return wi * kWordBits + static_cast<std::uint32_t>(std::countr_zero(head));
  ++wi;
  // then whole words, skipping runs of empty ones through the summary
  while (wi < wordCount_) {
    const std::uint32_t si = wi / kWordBits;
    const std::uint32_t nonEmpty = s[si] & (~0u << (wi % kWordBits));
    if (!nonEmpty) {
      wi = (si + 1) * kWordBits;
      continue;
    }
    wi = si * kWordBits + static_cast<std::uint32_t>(std::countr_zero(nonEmpty));
    return wi * kWordBits + static_cast<std::uint32_t>(std::countr_zero(w[wi]));
  }
  return pointCount_;
}

PointQueues::Sweep PointQueues::takeSweep(int q, std::uint32_t minPoints, std::uint64_t minIndices,
                                          std::span<std::uint32_t> out) noexcept {
  Sweep sweep;
  if (pointCount_ == 0) return sweep;
  const auto qi = static_cast<std::size_t>(q);
  const std::uint64_t n = pointCount_;
  const std::uint64_t mustCover = std::min<std::uint64_t>(minIndices, n);
  const std::uint32_t cap = std::min(counts_[qi], static_cast<std::uint32_t>(out.size()));
  // positions are unwrapped: start … start + n covers every index once
  const std::uint64_t start = cursors_[qi];
  std::uint64_t at = start;
  while (sweep.taken < cap) {
    const auto index = static_cast<std::uint32_t>(at % n);
    std::uint32_t next = nextAtOrAfter(q, index);
    std::uint64_t position = at - index + next;
    if (next == pointCount_) position = at - index + n + nextAtOrAfter(q, 0);  // wrap round
    if (position >= start + n) break;                                          // a full circle
    if (sweep.taken >= minPoints && position >= start + mustCover) break;
    out[sweep.taken++] = static_cast<std::uint32_t>(position % n);
    at = position + 1;
  }
  at = std::max(at, start + mustCover);
  sweep.coveredIndices = at - start;
  cursors_[qi] = static_cast<std::uint32_t>(at % n);
  return sweep;
}

std::uint32_t PointQueues::takeAll(int q, std::span<std::uint32_t> out) const noexcept {
  std::uint32_t written = 0;
  for (std::uint32_t p = nextAtOrAfter(q, 0); p < pointCount_ && written < out.size();
       p = nextAtOrAfter(q, p + 1)) {
    out[written++] = p;
  }
  return written;
}

}  // namespace voxhap

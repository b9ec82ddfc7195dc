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

std::uint32_t PointQueues::takeRoundRobin(int q, std::uint32_t m, std::span<std::uint32_t> out) noexcept {
  const auto qi = static_cast<std::size_t>(q);
  const std::uint32_t wanted = std::min({m, counts_[qi], static_cast<std::uint32_t>(out.size())});
  std::uint32_t written = 0;
  std::uint32_t at = cursors_[qi];
  while (written < wanted) {
    std::uint32_t p = nextAtOrAfter(q, at);
    if (p == pointCount_) p = nextAtOrAfter(q, 0);  // wrap round
    out[written++] = p;
    at = p + 1;
  }
  if (written > 0) cursors_[qi] = at >= pointCount_ ? 0 : at;
  return written;
}

std::uint32_t PointQueues::takeAll(int q, std::span<std::uint32_t> out) const noexcept {
  std::uint32_t written = 0;
  for (std::uint32_t p = nextAtOrAfter(q, 0); p < pointCount_ && written < out.size(); p = nextAtOrAfter(q, p + 1)) {
    out[written++] = p;
  }
  return written;
}

}  // namespace voxhap

#pragma once
/// A sliding anti-replay window over one sender's datagram sequence numbers (DESIGN §8),
/// as IPsec keeps one (RFC 4303 §3.4.3): the highest number accepted so far and a bitmap
/// of which of the kSize numbers below it have been seen. A number above the highest is
/// new; one inside the window is new once; one below the window is too old to tell and
/// is refused. check() only looks, so that a caller can drop a stale datagram before it
/// pays for authentication; accept() records a number once the datagram has proved
/// authentic, so that forged datagrams never move the window. Fixed size, no allocation.

#include <array>
#include <cstdint>

namespace voxhap::net {

class ReplayWindow {
public:
  /// How many sequence numbers below the highest are remembered: at 1 kHz, a datagram
  /// overtaken by up to 1 s of later ones is still taken.
  static constexpr std::uint64_t kSize = 1024;

  enum class Verdict {
    New,       ///< not seen: take it (after authentication, accept() it)
    Replayed,  ///< seen already
    TooOld     ///< kSize or more below the highest seen: cannot be told from a replay
  };

  Verdict check(std::uint64_t sequence) const noexcept {
    if (!any_ || sequence > highest_) return Verdict::New;
    if (highest_ - sequence >= kSize) return Verdict::TooOld;
    return seen(sequence) ? Verdict::Replayed : Verdict::New;
  }

  /// Records `sequence`, which check() found New.
  void accept(std::uint64_t sequence) noexcept {
    if (!any_ || sequence > highest_) {
      // numbers between the old highest and the new one have not been seen
      if (!any_ || sequence - highest_ >= kSize) {
        bits_.fill(0);
      } else {
        for (std::uint64_t s = highest_ + 1; s < sequence; ++s) clear(s);
      }
      highest_ = sequence;
      any_ = true;
    }
    set(sequence);
  }

  /// The highest sequence number accepted (0 before the first).
  std::uint64_t highest() const noexcept { return highest_; }

private:
  static constexpr std::uint64_t kWordBits = 64;
  bool seen(std::uint64_t s) const noexcept { return (bits_[word(s)] >> (s % kWordBits)) & 1u; }
  void set(std::uint64_t s) noexcept { bits_[word(s)] |= std::uint64_t{1} << (s % kWordBits); }
  void clear(std::uint64_t s) noexcept { bits_[word(s)] &= ~(std::uint64_t{1} << (s % kWordBits)); }
  static std::size_t word(std::uint64_t s) noexcept {
    return static_cast<std::size_t>((s % kSize) / kWordBits);
  }

  bool any_ = false;
  std::uint64_t highest_ = 0;
  std::array<std::uint64_t, kSize / kWordBits> bits_{};
};

}  // namespace voxhap::net

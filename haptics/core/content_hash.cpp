#include "haptics/core/content_hash.h"

#include <bit>
#include <cstring>

namespace voxhap {
namespace {

static_assert(std::endian::native == std::endian::little, "cache keys and files assume a little-endian machine");

constexpr std::uint64_t kPrime1 = 0x9E3779B185EBCA87ull;
constexpr std::uint64_t kPrime2 = 0xC2B2AE3D27D4EB4Full;
constexpr std::uint64_t kPrime3 = 0x165667B19E3779F9ull;
constexpr std::uint64_t kPrime4 = 0x85EBCA77C2B2AE63ull;
constexpr std::uint64_t kPrime5 = 0x27D4EB2F165667C5ull;

std::uint64_t round(std::uint64_t acc, std::uint64_t input) {
  return std::rotl(acc + input * kPrime2, 31) * kPrime1;
}

std::uint64_t merge(std::uint64_t h, std::uint64_t acc) { return (h ^ round(0, acc)) * kPrime1 + kPrime4; }

/// Full avalanche of a 64-bit value (every input bit flips each output bit with p ≈ 1/2).
std::uint64_t avalanche(std::uint64_t h) {
  h ^= h >> 33;
  h *= kPrime2;
  h ^= h >> 29;
  h *= kPrime3;
  h ^= h >> 32;
  return h;
}

std::uint64_t load64(const unsigned char* p) {
  std::uint64_t v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

}  // namespace

std::string Digest128::hex() const {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string s(32, '0');
  for (int i = 0; i < 16; ++i) {
    s[static_cast<std::size_t>(15 - i)] = kDigits[(hi >> (4 * i)) & 0xF];
    s[static_cast<std::size_t>(31 - i)] = kDigits[(lo >> (4 * i)) & 0xF];
  }
  return s;
}

ContentHash::ContentHash() : acc_{kPrime1 + kPrime2, kPrime2, 0, 0 - kPrime1} {}

void ContentHash::stripe(const unsigned char* bytes32) {
  for (std::size_t k = 0; k < 4; ++k) acc_[k] = round(acc_[k], load64(bytes32 + 8 * k));
}

void ContentHash::update(const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  if (bytes == 0) return;  // data may be null then
  totalBytes_ += bytes;
  if (pendingBytes_ > 0) {
    const std::size_t take = std::min(bytes, pending_.size() - pendingBytes_);
    std::memcpy(pending_.data() + pendingBytes_, p, take);
    pendingBytes_ += take;
    p += take;
    bytes -= take;
    if (pendingBytes_ < pending_.size()) return;
    stripe(pending_.data());
    pendingBytes_ = 0;
  }
  for (; bytes >= 32; bytes -= 32, p += 32) stripe(p);
  std::memcpy(pending_.data(), p, bytes);
  pendingBytes_ = bytes;
}

void ContentHash::addDouble(double value) { add(std::bit_cast<std::uint64_t>(value)); }

Digest128 ContentHash::digest() const {
  // the tail: whole words, then the remaining bytes, into both folds
  std::uint64_t tail = 0;
  std::uint64_t tailAlt = kPrime5;
  std::size_t i = 0;
  for (; i + 8 <= pendingBytes_; i += 8) {
    const std::uint64_t w = load64(pending_.data() + i);
    tail = std::rotl(tail ^ round(0, w), 27) * kPrime1 + kPrime4;
    tailAlt = std::rotl(tailAlt + w * kPrime3, 23) * kPrime2;
  }
  for (; i < pendingBytes_; ++i) {
    tail = std::rotl(tail ^ (std::uint64_t{pending_[i]} * kPrime5), 11) * kPrime1;
    tailAlt = std::rotl(tailAlt ^ (std::uint64_t{pending_[i]} * kPrime1), 17) * kPrime3;
  }
  const auto& a = acc_;
  std::uint64_t lo = std::rotl(a[0], 1) + std::rotl(a[1], 7) + std::rotl(a[2], 12) + std::rotl(a[3], 18);
  for (std::uint64_t acc : a) lo = merge(lo, acc);
  std::uint64_t hi = std::rotl(a[3], 5) ^ std::rotl(a[2], 23) ^ (a[1] * kPrime3) ^ (a[0] * kPrime4);
  for (std::size_t k = 4; k-- > 0;) hi = merge(hi, a[k] ^ kPrime5);
  return {avalanche(lo + tail + totalBytes_), avalanche(hi ^ tailAlt ^ (totalBytes_ * kPrime2))};
}

}  // namespace voxhap

#include "haptics/core/content_hash.h"

#include <bit>
#include <new>

#include <xxhash.h>

namespace voxhap {

static_assert(std::endian::native == std::endian::little,
              "cache keys and files assume a little-endian machine");

std::string Digest128::hex() const {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string s(32, '0');
  for (int i = 0; i < 16; ++i) {
    s[static_cast<std::size_t>(15 - i)] = kDigits[(hi >> (4 * i)) & 0xF];
    s[static_cast<std::size_t>(31 - i)] = kDigits[(lo >> (4 * i)) & 0xF];
  }
  return s;
}

void ContentHash::FreeState::operator()(XXH3_state_s* state) const noexcept {
  XXH3_freeState(state);
}

ContentHash::ContentHash() : state_(XXH3_createState()) {
  if (!state_) throw std::bad_alloc();
  XXH3_128bits_reset(state_.get());
}

ContentHash::~ContentHash() = default;
ContentHash::ContentHash(ContentHash&&) noexcept = default;
ContentHash& ContentHash::operator=(ContentHash&&) noexcept = default;

void ContentHash::update(const void* data, std::size_t bytes) {
  if (bytes == 0) return;  // data may be null then
  XXH3_128bits_update(state_.get(), data, bytes);
}

void ContentHash::addDouble(double value) {
  add(std::bit_cast<std::uint64_t>(value));
}

Digest128 ContentHash::digest() const {
  const XXH128_hash_t h = XXH3_128bits_digest(state_.get());
  return {h.low64, h.high64};
}

}  // namespace voxhap

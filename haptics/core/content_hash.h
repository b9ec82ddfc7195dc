#pragma once
/// A 128-bit content hash for cache keys and file checksums (not cryptographic): XXH3-128
/// (libxxhash) with seed 0, streamed. The result depends only on the byte sequence (not on
/// how it was split into update() calls), on this machine's byte order (little-endian),
/// and on nothing else. Load time only: the hash state is allocated.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <type_traits>

struct XXH3_state_s;  // xxhash.h

namespace voxhap {

/// A 128-bit digest: two 64-bit lanes.
struct Digest128 {
  std::uint64_t lo = 0;
  std::uint64_t hi = 0;

  /// 32 lowercase hex digits, `hi` first.
  std::string hex() const;
  friend bool operator==(const Digest128&, const Digest128&) = default;
};

class ContentHash {
public:
  ContentHash();
  ~ContentHash();
  /// Takes `other`'s state; `other` may then only be destroyed or assigned to.
  ContentHash(ContentHash&& other) noexcept;
  ContentHash& operator=(ContentHash&&) noexcept;

  /// Appends `bytes` bytes at `data` to the hashed sequence.
  void update(const void* data, std::size_t bytes);

  /// Appends the object representation of a trivially copyable value (no padding bits).
  template <typename T>
  void add(const T& value) {
    static_assert(std::is_trivially_copyable_v<T> && std::has_unique_object_representations_v<T>);
    update(&value, sizeof value);
  }
  /// Appends a double's bits (so 0.35e-3 and 0.35000000000000003e-3 differ).
  void addDouble(double value);
  /// Appends the element count, then the elements' bytes.
  template <typename T>
  void addArray(std::span<const T> values) {
    static_assert(std::is_trivially_copyable_v<T>);
    add(static_cast<std::uint64_t>(values.size()));
    update(values.data(), values.size_bytes());
  }

  /// The digest of everything appended so far; the hash may be updated further.
  Digest128 digest() const;

private:
  struct FreeState {
    void operator()(XXH3_state_s* state) const noexcept;
  };
  std::unique_ptr<XXH3_state_s, FreeState> state_;
};

}  // namespace voxhap

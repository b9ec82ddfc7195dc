#pragma once
/// The key every peer of a session shares (DESIGN §8, issue 12): 32 random bytes that
/// seal and authenticate every datagram. Kept in a file as 64 hexadecimal digits (a
/// final line end allowed), so that a first peer can print one for the others.

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

namespace voxhap::net {

class SessionKey {
public:
  static constexpr std::size_t kBytes = 32;

  /// A new key from libsodium's random generator.
  static SessionKey generate();
  /// The key in 64 hexadecimal digits; throws Error naming what is wrong.
  static SessionKey fromHex(const std::string& hex);
  /// The key in the file at `path`; throws Error naming the file and what is wrong.
  static SessionKey fromFile(const std::filesystem::path& path);

  std::string toHex() const;
  const std::array<std::uint8_t, kBytes>& bytes() const { return bytes_; }

private:
  SessionKey() = default;
  std::array<std::uint8_t, kBytes> bytes_{};
};

/// Calls sodium_init() once; throws Error if libsodium cannot start.
void initSodium();

}  // namespace voxhap::net

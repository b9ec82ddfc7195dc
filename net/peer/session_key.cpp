#include "net/peer/session_key.h"

#include <fstream>
#include <sstream>

#include <sodium.h>

#include "haptics/core/error.h"

namespace voxhap::net {

void initSodium() {
  if (sodium_init() < 0) throw Error("libsodium could not start (sodium_init failed)");
}

SessionKey SessionKey::generate() {
  initSodium();
  SessionKey key;
  randombytes_buf(key.bytes_.data(), key.bytes_.size());
  return key;
}

SessionKey SessionKey::fromHex(const std::string& hex) {
  initSodium();
  std::string digits = hex;
  while (!digits.empty() && (digits.back() == '\n' || digits.back() == '\r')) digits.pop_back();
  if (digits.size() != 2 * kBytes) {
    throw Error("a session key is " + std::to_string(2 * kBytes) + " hexadecimal digits, not " +
                std::to_string(digits.size()) + " characters");
  }
  SessionKey key;
  std::size_t written = 0;
  const char* end = nullptr;
  if (sodium_hex2bin(key.bytes_.data(), key.bytes_.size(), digits.data(), digits.size(), nullptr, &written,
                     &end) != 0 ||
      written != kBytes || end != digits.data() + digits.size()) {
    throw Error("a session key has only the digits 0-9 and a-f");
  }
  return key;
}

SessionKey SessionKey::fromFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string() + ": cannot read the session key file");
  std::ostringstream contents;
  contents << in.rdbuf();
  try {
    return fromHex(contents.str());
  } catch (const Error& e) {
    throw Error(path.string() + ": " + e.what());
  }
}

std::string SessionKey::toHex() const {
  std::string hex(2 * kBytes + 1, '\0');
  sodium_bin2hex(hex.data(), hex.size(), bytes_.data(), bytes_.size());
  hex.pop_back();
  return hex;
}

}  // namespace voxhap::net

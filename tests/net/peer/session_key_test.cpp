#include "net/peer/session_key.h"

#include <fstream>

#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "support/gltf_fixtures.h"

namespace voxhap::net {
namespace {

TEST(SessionKey, GeneratedKeysDifferAndRoundTripThroughHex) {
  const SessionKey a = SessionKey::generate();
  const SessionKey b = SessionKey::generate();
  EXPECT_NE(a.bytes(), b.bytes());
  EXPECT_EQ(a.toHex().size(), 64u);
  EXPECT_EQ(SessionKey::fromHex(a.toHex()).bytes(), a.bytes());
}

TEST(SessionKey, AFileWithALineEndHoldsTheKey) {
  const test::TempDir dir;
  const std::string hex = "000102030405060708090a0b0c0d0e0f101112131415161718191a1b1c1d1e1f";
  std::ofstream(dir.path() / "key") << hex << "\n";
  const SessionKey key = SessionKey::fromFile(dir.path() / "key");
  for (std::size_t i = 0; i < SessionKey::kBytes; ++i) EXPECT_EQ(key.bytes()[i], i);
  EXPECT_EQ(key.toHex(), hex);
}

TEST(SessionKey, BadKeysAndFilesSayWhatIsWrong) {
  const test::TempDir dir;
  auto message = [](auto make) -> std::string {
    try {
      make();
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(message([] { SessionKey::fromHex("abcd"); }).find("64 hexadecimal digits, not 4"),
            std::string::npos);
  EXPECT_NE(message([] { SessionKey::fromHex(std::string(63, '0') + "g"); }).find("0-9 and a-f"),
            std::string::npos);
  const auto missing = dir.path() / "missing";
  EXPECT_NE(message([&] { SessionKey::fromFile(missing); }).find(missing.string() + ": cannot read"),
            std::string::npos);
  std::ofstream(dir.path() / "short") << "0123\n";
  EXPECT_NE(message([&] { SessionKey::fromFile(dir.path() / "short"); }).find("short: a session key is 64"),
            std::string::npos);
}

}  // namespace
}  // namespace voxhap::net

#include "net/frontend/frame_codec.h"

#include <random>

#include <gtest/gtest.h>

namespace voxhap::net {
namespace {

TEST(FrameCodec, LengthIsFourBytesLittleEndian) {
  std::string out;
  appendFrame(out, std::string(0x0102, 'x'));
  ASSERT_EQ(out.size(), 4u + 0x0102u);
  EXPECT_EQ(static_cast<unsigned char>(out[0]), 0x02);
  EXPECT_EQ(static_cast<unsigned char>(out[1]), 0x01);
  EXPECT_EQ(out[2], 0);
  EXPECT_EQ(out[3], 0);
}

TEST(FrameCodec, FramesSurviveAnyChunking) {
  std::mt19937 rng(7);
  std::vector<std::string> sent;
  std::string stream;
  for (int i = 0; i < 200; ++i) {
    std::string payload(rng() % 300, '\0');
    for (char& c : payload) c = static_cast<char>(rng());
    appendFrame(stream, payload);
    sent.push_back(std::move(payload));
  }
  FrameDecoder decoder;
  std::vector<std::string> got;
  std::string payload;
  for (std::size_t at = 0; at < stream.size();) {
    const std::size_t n = std::min<std::size_t>(1 + rng() % 97, stream.size() - at);
    decoder.feed(std::string_view(stream).substr(at, n));
    at += n;
    while (decoder.next(payload) == FrameDecoder::Result::Frame) got.push_back(payload);
  }
  EXPECT_EQ(got, sent);
  EXPECT_EQ(decoder.buffered(), 0u);
}

TEST(FrameCodec, AnOversizedLengthIsRefusedBeforeItsBytesArrive) {
  FrameDecoder decoder(1000);
  decoder.feed(std::string("\xe9\x03\x00\x00", 4));  // 1001
  std::string payload;
  EXPECT_EQ(decoder.next(payload), FrameDecoder::Result::Oversized);
  EXPECT_EQ(decoder.announcedBytes(), 1001u);
}

TEST(FrameCodec, APartialFrameWaits) {
  FrameDecoder decoder;
  std::string frame;
  appendFrame(frame, "hello");
  decoder.feed(std::string_view(frame).substr(0, 6));
  std::string payload;
  EXPECT_EQ(decoder.next(payload), FrameDecoder::Result::NeedMore);
  decoder.feed(std::string_view(frame).substr(6));
  EXPECT_EQ(decoder.next(payload), FrameDecoder::Result::Frame);
  EXPECT_EQ(payload, "hello");
}

// bounded fuzz: random bytes never make the decoder return more than it was fed or
// buffer more than the cap plus one chunk
TEST(FrameCodec, FuzzedStreamsStayWithinTheCap) {
  std::mt19937 rng(11);
  constexpr std::uint32_t kCap = 4096;
  for (int round = 0; round < 2000; ++round) {
    FrameDecoder decoder(kCap);
    std::size_t fed = 0;
    std::size_t returned = 0;
    std::string payload;
    bool broken = false;
    for (int chunk = 0; chunk < 20 && !broken; ++chunk) {
      std::string bytes(rng() % 64, '\0');
      for (char& c : bytes) c = static_cast<char>(rng() % 4 == 0 ? rng() : rng() % 8);
      decoder.feed(bytes);
      fed += bytes.size();
      for (;;) {
        const FrameDecoder::Result r = decoder.next(payload);
        if (r == FrameDecoder::Result::Oversized) {
          EXPECT_GT(decoder.announcedBytes(), kCap);
          broken = true;
          break;
        }
        if (r == FrameDecoder::Result::NeedMore) break;
        ASSERT_LE(payload.size(), kCap);
        returned += kFrameHeaderBytes + payload.size();
      }
      ASSERT_EQ(returned + decoder.buffered(), fed);
      ASSERT_LE(decoder.buffered(), kCap + kFrameHeaderBytes + 64);
    }
  }
}

}  // namespace
}  // namespace voxhap::net

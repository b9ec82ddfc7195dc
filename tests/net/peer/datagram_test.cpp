#include "net/peer/datagram.h"

#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "support/allocation_counter.h"

namespace voxhap::net {
namespace {

using Bytes = std::vector<std::uint8_t>;

class DatagramTest : public ::testing::Test {
protected:
  static constexpr std::uint64_t kSession = 0x1122334455667788ull;
  const SessionKey key_ = SessionKey::generate();
  DatagramSealer sealer_{key_, kSession, 7, 1000};
  DatagramOpener opener_{key_, kSession};
  std::array<std::uint8_t, kMaxDatagramPayloadBytes> payload_{};
  DatagramHeader header_;
  std::size_t payloadBytes_ = 0;

  Bytes seal(const Bytes& payload, DatagramKind kind = DatagramKind::State, std::uint32_t timeUs = 42) {
    Bytes out(kMaxDatagramBytes);
    out.resize(sealer_.seal(kind, timeUs, payload, out));
    return out;
  }
  OpenResult open(const Bytes& datagram) { return opener_.open(datagram, payload_, header_, payloadBytes_); }
  Bytes opened() const {
    return Bytes(payload_.begin(), payload_.begin() + static_cast<long>(payloadBytes_));
  }
};

TEST_F(DatagramTest, APayloadComesOutAsItWentInWithItsHeader) {
  const Bytes payload = {1, 2, 3, 250, 0, 9};
  const Bytes datagram = seal(payload, DatagramKind::Event, 123456);
  ASSERT_EQ(datagram.size(), kDatagramHeaderBytes + payload.size() + kDatagramTagBytes);
  ASSERT_EQ(open(datagram), OpenResult::Opened);
  EXPECT_EQ(opened(), payload);
  EXPECT_EQ(header_.kind, DatagramKind::Event);
  EXPECT_EQ(header_.session, kSession);
  EXPECT_EQ(header_.sender, 7u);
  EXPECT_EQ(header_.sequence, 1000u);
  EXPECT_EQ(header_.sendTimeUs, 123456u);
  EXPECT_EQ(sealer_.nextSequence(), 1001u);
  // an empty payload is a datagram too (a heartbeat)
  ASSERT_EQ(open(seal({})), OpenResult::Opened);
  EXPECT_EQ(payloadBytes_, 0u);
}

TEST_F(DatagramTest, ThePayloadIsNotInTheClear) {
  const Bytes payload(64, 0xAB);
  const Bytes datagram = seal(payload);
  int same = 0;
  for (std::size_t i = 0; i < payload.size(); ++i) same += datagram[kDatagramHeaderBytes + i] == 0xAB;
  EXPECT_LT(same, 8);  // about 64/256 by chance
}

TEST_F(DatagramTest, EveryChangedByteIsCaught) {
  const Bytes datagram = seal({10, 20, 30, 40});
  for (std::size_t i = 0; i < datagram.size(); ++i) {
    Bytes bad = datagram;
    bad[i] ^= 0x01;
    const OpenResult r = open(bad);
    EXPECT_NE(r, OpenResult::Opened) << "byte " << i;
  }
  EXPECT_EQ(opener_.count(OpenResult::Opened), 0u);
  EXPECT_EQ(open(datagram), OpenResult::Opened);  // the forgeries did not spend its number
}

TEST_F(DatagramTest, AnotherKeyOrSessionIsRefused) {
  DatagramOpener otherKey{SessionKey::generate(), kSession};
  const Bytes datagram = seal({1, 2, 3});
  EXPECT_EQ(otherKey.open(datagram, payload_, header_, payloadBytes_), OpenResult::Forged);
  DatagramOpener otherSession{key_, kSession + 1};
  EXPECT_EQ(otherSession.open(datagram, payload_, header_, payloadBytes_), OpenResult::NotOurs);
  // a sender claiming another sender's id does not authenticate (the nonce and the header differ)
  Bytes spoofed = datagram;
  spoofed[16] = 8;
  EXPECT_EQ(open(spoofed), OpenResult::Forged);
}

TEST_F(DatagramTest, ReplaysAndTooOldDatagramsAreDropped) {
  const Bytes first = seal({1});
  std::vector<Bytes> later;
  for (std::uint64_t i = 0; i < ReplayWindow::kSize; ++i) later.push_back(seal({2}));
  EXPECT_EQ(open(later.back()), OpenResult::Opened);
  EXPECT_EQ(open(later.back()), OpenResult::Replayed);
  EXPECT_EQ(open(later.front()), OpenResult::Opened);  // late, but inside the window
  EXPECT_EQ(open(first), OpenResult::TooOld);
  EXPECT_EQ(opener_.count(OpenResult::Replayed), 1u);
  EXPECT_EQ(opener_.count(OpenResult::TooOld), 1u);
  // a sender that joins again with a new sequence is taken after forget()
  DatagramSealer restarted{key_, kSession, 7, 5};
  Bytes again(kMaxDatagramBytes);
  again.resize(restarted.seal(DatagramKind::State, 0, Bytes{3}, again));
  EXPECT_EQ(open(again), OpenResult::TooOld);
  opener_.forget(7);
  EXPECT_EQ(open(again), OpenResult::Opened);
}

TEST_F(DatagramTest, SizesOutsideTheLimitsAreRefusedOnBothSides) {
  Bytes out(kMaxDatagramBytes);
  EXPECT_EQ(sealer_.seal(DatagramKind::State, 0, Bytes(kMaxDatagramPayloadBytes + 1), out), 0u);
  EXPECT_EQ(sealer_.seal(DatagramKind::State, 0, Bytes(10), std::span(out).first(40)), 0u);
  EXPECT_EQ(sealer_.nextSequence(), 1000u) << "nothing sent, no number used";
  EXPECT_EQ(open(seal(Bytes(kMaxDatagramPayloadBytes))), OpenResult::Opened);

  EXPECT_EQ(open(Bytes(kDatagramHeaderBytes + kDatagramTagBytes - 1)), OpenResult::BadSize);
  EXPECT_EQ(open(Bytes(kMaxDatagramBytes + 1)), OpenResult::BadSize);
  std::array<std::uint8_t, 2> tiny{};
  EXPECT_EQ(opener_.open(seal({1, 2, 3}), tiny, header_, payloadBytes_), OpenResult::PayloadTooBig);
}

TEST_F(DatagramTest, SendersBeyondTheTableAreDroppedButKnownOnesGoOn) {
  std::vector<DatagramSealer> sealers;
  for (std::uint32_t id = 100; id < 100 + DatagramOpener::kMaxSenders + 1; ++id)
    sealers.emplace_back(key_, kSession, id);
  Bytes out(kMaxDatagramBytes);
  for (std::size_t i = 0; i < sealers.size(); ++i) {
    out.resize(kMaxDatagramBytes);
    out.resize(sealers[i].seal(DatagramKind::State, 0, Bytes{1}, out));
    EXPECT_EQ(open(out), i < DatagramOpener::kMaxSenders ? OpenResult::Opened : OpenResult::NoWindow) << i;
  }
  out.resize(kMaxDatagramBytes);
  out.resize(sealers.front().seal(DatagramKind::State, 0, Bytes{1}, out));
  EXPECT_EQ(open(out), OpenResult::Opened);
  // forged datagrams from new senders take no window
  opener_.forget(100);
  Bytes forged = out;
  forged[16] = 0xEE;
  EXPECT_EQ(open(forged), OpenResult::Forged);
  out.resize(kMaxDatagramBytes);
  out.resize(sealers.back().seal(DatagramKind::State, 0, Bytes{1}, out));
  EXPECT_EQ(open(out), OpenResult::Opened) << "the freed window went to a real sender";
}

TEST_F(DatagramTest, SealingAndOpeningAllocateNothing) {
  const Bytes payload(200, 5);
  Bytes out(kMaxDatagramBytes);
  const test::AllocationCounter allocations;
  for (int i = 0; i < 100; ++i) {
    const std::size_t n = sealer_.seal(DatagramKind::State, 0, payload, out);
    ASSERT_EQ(opener_.open(std::span(out).first(n), payload_, header_, payloadBytes_), OpenResult::Opened);
  }
  EXPECT_EQ(allocations.count(), 0u);
}

// Bounded fuzz: random bytes, and genuine datagrams with random bytes changed, cut or
// grown. None opens but the genuine ones, and every datagram is counted once.
TEST_F(DatagramTest, RandomAndMutatedDatagramsNeverOpen) {
  std::mt19937_64 rng(20261203);
  std::uniform_int_distribution<int> byte(0, 255);
  const int kRounds = 20000;
  std::uint64_t genuine = 0;
  for (int round = 0; round < kRounds; ++round) {
    Bytes datagram;
    if (round % 2 == 0) {
      datagram.resize(std::uniform_int_distribution<std::size_t>(0, kMaxDatagramBytes + 8)(rng));
      for (auto& b : datagram) b = static_cast<std::uint8_t>(byte(rng));
      if (round % 4 == 0 && datagram.size() >= 8) {  // a header that looks like ours
        const Bytes real = seal({});
        std::copy(real.begin(),
                  real.begin() + static_cast<long>(std::min(datagram.size(), kDatagramHeaderBytes)),
                  datagram.begin());
      }
    } else {
      Bytes payload(std::uniform_int_distribution<std::size_t>(0, 300)(rng));
      for (auto& b : payload) b = static_cast<std::uint8_t>(byte(rng));
      datagram = seal(payload);
      if (round % 10 == 1) {
        ASSERT_EQ(open(datagram), OpenResult::Opened);
        ++genuine;
        continue;
      }
      switch (round % 3) {
        case 0:
          datagram[std::uniform_int_distribution<std::size_t>(0, datagram.size() - 1)(rng)] ^=
              1 + byte(rng) % 255;
          break;
        case 1:
          datagram.resize(std::uniform_int_distribution<std::size_t>(0, datagram.size() - 1)(rng));
          break;
        default:
          datagram.push_back(static_cast<std::uint8_t>(byte(rng)));
          break;
      }
    }
    EXPECT_NE(open(datagram), OpenResult::Opened) << "round " << round;
  }
  std::uint64_t total = 0;
  for (std::uint64_t c : opener_.counts()) total += c;
  EXPECT_EQ(total, static_cast<std::uint64_t>(kRounds));
  EXPECT_EQ(opener_.count(OpenResult::Opened), genuine);
  EXPECT_GT(opener_.count(OpenResult::Forged), 0u);
  EXPECT_GT(opener_.count(OpenResult::NotOurs), 0u);
  EXPECT_GT(opener_.count(OpenResult::BadSize), 0u);
}

}  // namespace
}  // namespace voxhap::net

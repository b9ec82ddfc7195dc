// PeerSession in one process: several peers on one io_context, on loopback, joining,
// owning, handing over, leaving and timing out, and garbage at the socket. Every wait is
// bounded by a count of rounds.

#include "net/peer/peer_session.h"

#include <algorithm>
#include <random>

#include <asio/ip/udp.hpp>
#include <gtest/gtest.h>

#include "haptics/core/error.h"

namespace voxhap::net {
namespace {

using namespace std::chrono_literals;
namespace pb = peer::v1;

constexpr std::uint32_t kObjects = 3;

SessionKey testKey(char digit = 'a') {
  return SessionKey::fromHex(std::string(64, digit));
}

pb::SessionParameters parameters(char sceneByte = 1, double voxelM = 0.001) {
  pb::SessionParameters p;
  p.set_scene_hash(std::string(16, sceneByte));
  p.set_voxel_size_m(voxelM);
  p.set_point_spacing_m(0.001);
  p.set_force_layer(4);
  p.set_moving_objects(kObjects);
  return p;
}

/// One peer with what its callbacks saw.
struct TestPeer {
  TestPeer(asio::io_context& io, const std::string& name, pb::SessionParameters params = parameters(),
           const SessionKey& key = testKey()) {
    PeerSessionOptions o;
    o.name = name;
    o.parameters = std::move(params);
    o.timeout = 300ms;
    session =
        std::make_unique<PeerSession>(io, key, o, [this](const std::string& line) { log.push_back(line); });
  }
  void start(std::vector<PeerId> initialOwners = std::vector<PeerId>(kObjects, kNoPeer)) {
    owners = initialOwners;
    session->start(
        initialOwners,
        [this](std::uint32_t object, PeerId owner, std::int64_t, const RigidBodyState& body, std::int64_t) {
          ++states;
          lastBody[object] = body;
          lastStateOwner[object] = owner;
        },
        [this](std::uint32_t object, PeerId owner) { owners[object] = owner; }, [this] { return snapshot; });
  }
  LocalFrame frame() const {
    LocalFrame f;
    f.endedUs = std::chrono::duration_cast<std::chrono::microseconds>(
                    std::chrono::steady_clock::now().time_since_epoch())
                    .count();
    f.frame = 1;
    for (std::uint32_t o = 0; o < kObjects; ++o) {
      RigidBodyState b;
      b.comWorld = glm::dvec3(o, 0.0, 0.0) + offset;
      f.bodies.push_back(b);
      f.held.push_back(held[o]);
    }
    return f;
  }

  std::unique_ptr<PeerSession> session;
  std::vector<std::string> log;
  std::vector<PeerId> owners;
  std::vector<std::byte> snapshot;
  std::array<bool, kObjects> held{};
  glm::dvec3 offset{0.0};
  std::uint64_t states = 0;
  std::map<std::uint32_t, RigidBodyState> lastBody;
  std::map<std::uint32_t, PeerId> lastStateOwner;
};

/// Ticks every started peer and runs the context, `rounds` times 5 ms.
void run(asio::io_context& io, std::initializer_list<TestPeer*> peers, int rounds = 20) {
  for (int i = 0; i < rounds; ++i) {
    for (TestPeer* p : peers) p->session->tick(p->frame());
    io.restart();
    io.run_for(5ms);
  }
}

/// Starts `first`, then `second` and `third` joined through it.
void startJoinedThroughFirst(TestPeer& first, TestPeer& second, TestPeer& third) {
  first.start();
  for (TestPeer* p : {&second, &third}) {
    p->session->join("127.0.0.1", first.session->port(), 5s);
    p->start();
  }
}

std::vector<std::byte> patternBytes(std::size_t n) {
  std::vector<std::byte> bytes(n);
  for (std::size_t i = 0; i < n; ++i) bytes[i] = static_cast<std::byte>(i * 7 + 3);
  return bytes;
}

TEST(PeerSession, AJoinerGetsTheWholeSnapshotAndEveryMemberLearnsOfEveryOther) {
  asio::io_context io;
  TestPeer a(io, "ann"), b(io, "bob"), c(io, "cyd");
  a.snapshot = patternBytes(3500);  // four chunks
  a.start();
  const std::vector<std::byte> got = b.session->join("127.0.0.1", a.session->port(), 5s);
  EXPECT_EQ(got, a.snapshot);
  b.snapshot = patternBytes(10);
  b.start();
  // the third joins through the second, and hears of the first from its welcome
  EXPECT_EQ(c.session->join("127.0.0.1", b.session->port(), 5s), b.snapshot);
  c.start();
  run(io, {&a, &b, &c});
  for (TestPeer* p : {&a, &b, &c}) {
    const std::vector<MemberView> members = p->session->members();
    ASSERT_EQ(members.size(), 2u) << p->session->self();
    for (const MemberView& m : members) {
      EXPECT_GT(m.rttMs, 0.0);
      EXPECT_GT(m.oneWayMs, 0.0);
      EXPECT_FALSE(m.name.empty());
      EXPECT_GT(m.bytesIn, 0u);
    }
    EXPECT_EQ(p->session->counts().opened[static_cast<std::size_t>(OpenResult::Forged)], 0u);
  }
}

TEST(PeerSession, AnotherSceneIsRefusedAndOtherSizesAreAcceptedWithAWarning) {
  asio::io_context io;
  TestPeer a(io, "ann");
  a.start();
  TestPeer other(io, "oz", parameters(2));
  try {
    other.session->join("127.0.0.1", a.session->port(), 5s);
    ADD_FAILURE() << "joined another scene";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("another scene"), std::string::npos) << e.what();
  }
  TestPeer coarse(io, "cy", parameters(1, 0.002));
  coarse.session->join("127.0.0.1", a.session->port(), 5s);
  ASSERT_EQ(coarse.session->warnings().size(), 1u);
  EXPECT_NE(coarse.session->warnings()[0].find("voxel size"), std::string::npos);
  EXPECT_TRUE(std::any_of(a.log.begin(), a.log.end(),
                          [](const std::string& l) { return l.find("voxel size") != std::string::npos; }));
  pb::SessionParameters surface = parameters();
  surface.set_surface_contact(true);
  TestPeer finer(io, "fi", surface);
  finer.session->join("127.0.0.1", a.session->port(), 5s);
  ASSERT_EQ(finer.session->warnings().size(), 1u);
  EXPECT_NE(finer.session->warnings()[0].find("contact by surface planes here, by voxel planes there"),
            std::string::npos)
      << finer.session->warnings()[0];
}

TEST(PeerSession, WithAnotherKeyNothingAnswers) {
  asio::io_context io;
  TestPeer a(io, "ann");
  a.start();
  TestPeer stranger(io, "eve", parameters(), testKey('b'));
  EXPECT_THROW(stranger.session->join("127.0.0.1", a.session->port(), 300ms), Error);
  run(io, {&a}, 2);
  // another key is another session id: dropped before any cryptography
  EXPECT_GT(a.session->counts().opened[static_cast<std::size_t>(OpenResult::NotOurs)], 0u);
  EXPECT_TRUE(a.session->members().empty());
}

TEST(PeerSession, OwnersStreamTheirObjectsHandOverWhatIsWantedAndTheLowerIdWinsATie) {
  asio::io_context io;
  TestPeer a(io, "ann"), b(io, "bob");
  a.start();
  b.session->join("127.0.0.1", a.session->port(), 5s);
  b.start();
  a.session->want(0);
  a.held[0] = true;
  a.offset = glm::dvec3(0.0, 0.5, 0.0);
  run(io, {&a, &b});
  const PeerId ann = a.session->self(), bob = b.session->self();
  EXPECT_EQ(a.owners[0], ann);
  EXPECT_EQ(b.owners[0], ann);
  // bob gets ann's stream of object 0, and only of it
  EXPECT_GT(b.states, 10u);
  EXPECT_EQ(b.lastBody.count(1), 0u);
  EXPECT_EQ(b.lastBody[0].comWorld, glm::dvec3(0.0, 0.5, 0.0));
  EXPECT_EQ(b.lastStateOwner[0], ann);

  // bob asks for it: ann's user holds it, so it stays; once let go, it is handed over
  b.session->want(0);
  run(io, {&a, &b});
  EXPECT_EQ(b.owners[0], ann);
  a.held[0] = false;
  run(io, {&a, &b});
  EXPECT_EQ(a.owners[0], bob);
  EXPECT_EQ(b.owners[0], bob);

  // both take object 2 in the same round: the lower id keeps it on both
  a.session->want(2);
  b.session->want(2);
  run(io, {&a, &b});
  const PeerId lower = std::min(ann, bob);
  EXPECT_EQ(a.owners[2], lower);
  EXPECT_EQ(b.owners[2], lower);
}

TEST(PeerSession, ALeaverIsGoneAtOnceASilentOneAfterTheTimeoutAndTheirObjectsAreNobodys) {
  asio::io_context io;
  TestPeer a(io, "ann"), b(io, "bob"), c(io, "cyd");
  startJoinedThroughFirst(a, b, c);
  b.session->want(1);
  c.session->want(2);
  run(io, {&a, &b, &c});
  ASSERT_EQ(a.owners[1], b.session->self());
  ASSERT_EQ(a.owners[2], c.session->self());

  b.session->leave(b.frame());
  run(io, {&a, &c}, 2);  // well within the 300 ms time-out
  EXPECT_EQ(a.session->members().size(), 1u);
  EXPECT_EQ(a.owners[1], kNoPeer);
  EXPECT_EQ(c.owners[1], kNoPeer);

  // c goes silent (no more ticks): gone after 300 ms, and not taken back from stale gossip
  run(io, {&a}, 80);
  EXPECT_TRUE(a.session->members().empty());
  EXPECT_EQ(a.owners[2], kNoPeer);
}

// A stall longer than the time-out (a suspended machine, a starved comms thread) makes
// both sides time each other out; they hear each other again when both go on, and the
// objects come back to their owners. A leaver is not taken back.
TEST(PeerSession, PeersThatTimedEachOtherOutInAStallAreMembersAgainWhenItEnds) {
  asio::io_context io;
  TestPeer a(io, "ann"), b(io, "bob"), c(io, "cyd");
  startJoinedThroughFirst(a, b, c);
  b.session->want(1);
  run(io, {&a, &b, &c});
  ASSERT_EQ(a.owners[1], b.session->self());

  c.session->leave(c.frame());
  run(io, {&a, &b}, 2);
  // nobody ticks for 400 ms (more than the 300 ms time-out), then each times the other out
  io.restart();
  io.run_for(400ms);
  run(io, {&a, &b}, 60);  // 300 ms: calls every 100 ms
  const auto logged = [](const TestPeer& p, const std::string& what) {
    return std::any_of(p.log.begin(), p.log.end(),
                       [&](const std::string& line) { return line.find(what) != std::string::npos; });
  };
  for (const TestPeer* p : {&a, &b}) {
    EXPECT_TRUE(logged(*p, "timed out")) << p->session->self();
    EXPECT_TRUE(logged(*p, "is heard again")) << p->session->self();
    ASSERT_EQ(p->session->members().size(), 1u) << p->session->self();
    EXPECT_EQ(p->owners[1], b.session->self());
  }
  EXPECT_EQ(a.session->members()[0].peer, b.session->self());
  // the leaver, ticking again, stays gone
  run(io, {&a, &b, &c}, 40);
  EXPECT_EQ(a.session->members().size(), 1u);
  EXPECT_EQ(b.session->members().size(), 1u);
}

TEST(PeerSession, AStateWhoseClockIsImpossibleIsDroppedAsMalformed) {
  asio::io_context io;
  TestPeer a(io, "ann");
  a.start();
  asio::ip::udp::socket sender(io, asio::ip::udp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  const asio::ip::udp::endpoint target(asio::ip::make_address("127.0.0.1"), a.session->port());
  DatagramSealer sealer(testKey(), a.session->sessionId(), 77, 1);
  std::vector<std::uint8_t> payload, datagram(kMaxDatagramBytes);
  for (const std::int64_t sentUs : {std::int64_t{0}, std::int64_t{-5}, (std::int64_t{1} << 53) + 1}) {
    pb::PeerState state;
    state.set_sent_us(sentUs);
    state.set_name("mallory");
    payload.resize(state.ByteSizeLong());
    ASSERT_TRUE(state.SerializeToArray(payload.data(), static_cast<int>(payload.size())));
    sender.send_to(asio::buffer(datagram.data(), sealer.seal(DatagramKind::State, 0, payload, datagram)),
                   target);
  }
  run(io, {&a}, 4);
  EXPECT_EQ(a.session->counts().opened[static_cast<std::size_t>(OpenResult::Opened)], 3u);
  EXPECT_EQ(a.session->counts().malformed, 3u);
  EXPECT_TRUE(a.session->members().empty());
}

TEST(PeerSession, GarbageAtTheSocketIsCountedAndDropped) {
  asio::io_context io;
  TestPeer a(io, "ann");
  a.start();
  asio::ip::udp::socket attacker(io, asio::ip::udp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  const asio::ip::udp::endpoint target(asio::ip::make_address("127.0.0.1"), a.session->port());
  std::mt19937 random(5);
  std::vector<std::uint8_t> bytes(1300);
  // random sizes and bytes; sealed datagrams with a flipped bit; one authentic datagram,
  // again and again
  DatagramSealer sealer(testKey(), a.session->sessionId(), 77, 1);
  std::vector<std::uint8_t> authentic(kMaxDatagramBytes);
  const std::uint8_t junk[3] = {1, 2, 3};
  const std::size_t authenticBytes = sealer.seal(DatagramKind::State, 0, junk, authentic);
  for (int i = 0; i < 300; ++i) {
    for (auto& byte : bytes) byte = static_cast<std::uint8_t>(random());
    std::size_t n = random() % bytes.size();
    if (i % 3 == 1) {
      n = sealer.seal(DatagramKind::State, 0, junk, bytes);
      bytes[kDatagramHeaderBytes + 1] ^= 0x40;  // a flipped payload bit
    } else if (i % 3 == 2) {
      std::copy(authentic.begin(), authentic.begin() + static_cast<std::ptrdiff_t>(authenticBytes),
                bytes.begin());
      n = authenticBytes;
    }
    attacker.send_to(asio::buffer(bytes.data(), n), target);
    if (i % 30 == 29) run(io, {&a}, 2);  // within the socket's receive buffer
  }
  run(io, {&a}, 10);
  const PeerSessionCounts& c = a.session->counts();
  EXPECT_EQ(c.datagramsIn, 300u);
  std::uint64_t dropped = c.flooded + c.malformed + c.unexpected;
  for (std::size_t r = 1; r < kOpenResults; ++r) dropped += c.opened[r];
  // the one authentic datagram opens (its payload is no PeerState: malformed); the rest
  // are dropped, each counted once
  EXPECT_EQ(c.opened[static_cast<std::size_t>(OpenResult::Opened)], 1u);
  EXPECT_EQ(c.malformed, 1u);
  EXPECT_EQ(dropped + c.opened[0] - c.malformed, 300u);
  EXPECT_GE(c.opened[static_cast<std::size_t>(OpenResult::Forged)], 100u);
  EXPECT_GE(c.opened[static_cast<std::size_t>(OpenResult::Replayed)], 99u);
  EXPECT_TRUE(a.session->members().empty());
}

}  // namespace
}  // namespace voxhap::net

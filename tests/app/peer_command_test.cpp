// `voxhap peer`, run as the real executable: three peers on loopback, each owning one of
// three boxes on a plate, one pushing its box into another's (type-1, issue 12). Front-end
// clients read what every peer shows. Every wait is bounded; no assertion is about how
// long anything took.

#include <array>
#include <cmath>
#include <csignal>
#include <fstream>
#include <map>
#include <random>
#include <thread>

#include <asio/ip/udp.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "net/frontend/frontend_client.h"
#include "net/peer/datagram.h"
#include "net/peer/peer_session.h"
#include "support/newest_update.h"
#include "support/peer_processes.h"
#include "support/sanitizers.h"

namespace voxhap::test {
namespace {

using namespace std::chrono_literals;
namespace pb = net::pb;

class PeerCommand : public PeerProcessTest {};

/// Three peers, each owning one of the three boxes, the second and third holding theirs
/// where they are; once all are up, the first user drags its box 15 mm into the middle one
/// (5 mm away), holds it there 2 s, and takes it back. Checks what every peer shows while
/// they touch and at rest, and what each counted.
void pushScenario(PeerCommand& test, const Path& path) {
  PeerPlacement placement(test, path);
  auto placed = [&](const std::string& name, std::vector<std::string> args) {
    return placement.place(name, std::move(args));
  };
  const auto advertised = &PeerPlacement::advertised;
  PeerCommand::Peer a = test.startPeer("a" + path.delay, placed("a", {"--take", "left", "--name", "ann"}));
  ASSERT_NE(a.udpPort, 0);
  PeerCommand::Peer b =
      test.startPeer("b" + path.delay, placed("b", {"--join", advertised(a), "--take", "middle", "--device",
                                                    "script:hold.txt", "--name", "bob"}));
  ASSERT_NE(b.udpPort, 0);
  // the third joins through the second: it learns of the first from the welcome
  PeerCommand::Peer c =
      test.startPeer("c" + path.delay, placed("c", {"--join", advertised(b), "--take", "right", "--device",
                                                    "script:hold.txt", "--name", "cyd"}));
  ASSERT_NE(c.udpPort, 0);

  std::array<PeerCommand::Peer*, 3> peers = {&a, &b, &c};
  std::vector<std::unique_ptr<net::FrontendClient>> clients;
  for (PeerCommand::Peer* p : peers) {
    clients.push_back(std::make_unique<net::FrontendClient>("127.0.0.1", p->frontendPort, 5000ms));
    clients.back()->hello("peer test");
    subscribe(*clients.back());
  }
  pb::ClientMessage grab;
  grab.mutable_grab()->set_object("left");
  grab.mutable_grab()->set_device("client");
  const pb::ServerMessage grabbed = clients[0]->request(grab);
  ASSERT_TRUE(grabbed.has_done()) << grabbed.DebugString();
  slideHandle(*clients[0], "left", {0.0, 0.0, 0.0}, {0.015, 0.0, 0.0});
  // while the left box is pressed into the middle one: the middle one's owner feels it
  // through its contacts, and on every peer the left box stays out of the middle one
  // (until the middle box's owner has felt it and 2 s more; a sanitizer's build is slower)
  std::array<std::uint32_t, 3> middleContacts{};
  double deepestM = 0.0;
  std::string deepestSeen = "no overlap";
  auto until = std::chrono::steady_clock::now() + 30s;
  for (bool felt = false; std::chrono::steady_clock::now() < until;) {
    for (std::size_t i = 0; i < clients.size(); ++i) {
      const pb::FrameUpdate u = newestUpdate(*clients[i]);
      ASSERT_EQ(u.objects_size(), 3);
      middleContacts[i] = std::max(middleContacts[i], u.objects(1).contacts());
      // left's +x face at −15 mm + its motion, middle's −x face at −10 mm + its motion
      const double overlapM = (positionOf(u.objects(0)).x - 0.015) - (positionOf(u.objects(1)).x - 0.010);
      if (overlapM > deepestM) {
        deepestM = overlapM;
        deepestSeen = "peer " + std::to_string(i) + " showed left at x " +
                      std::to_string(positionOf(u.objects(0)).x * 1e3) + " mm, middle at x " +
                      std::to_string(positionOf(u.objects(1)).x * 1e3) + " mm, middle's contacts " +
                      std::to_string(u.objects(1).contacts());
      }
    }
    if (!felt && middleContacts[1] > 0) {
      felt = true;
      until = std::chrono::steady_clock::now() + 2s;
    }
    std::this_thread::sleep_for(50ms);
  }
  EXPECT_GT(middleContacts[1], 0u) << "the middle box's owner felt no contact";
  EXPECT_LT(deepestM, 0.1 * kBoxesVoxelM) << deepestSeen;
  const double pushedM = positionOf(newestUpdate(*clients[0]).objects(0)).x;
  EXPECT_GT(pushedM, 0.003) << "the left box was not pushed";
  slideHandle(*clients[0], "left", {0.015, 0.0, 0.0}, {0.0, 0.0, 0.0});

  // apart and at rest, every peer shows every box where its owner has it (waiting up to
  // 30 s for them to settle and their states to arrive)
  std::array<pb::FrameUpdate, 3> final;
  std::array<double, 3> disagreementM{};
  for (const auto giveUp = std::chrono::steady_clock::now() + 30s;
       std::chrono::steady_clock::now() < giveUp;) {
    std::this_thread::sleep_for(500ms);
    for (std::size_t i = 0; i < clients.size(); ++i) final[i] = newestUpdate(*clients[i]);
    disagreementM = {};
    for (int object = 0; object < 3; ++object) {
      const auto o = static_cast<std::size_t>(object);
      const glm::dvec3 owners = positionOf(final[o].objects(object));
      for (std::size_t i = 0; i < 3; ++i)
        disagreementM[o] =
            std::max(disagreementM[o], glm::length(positionOf(final[i].objects(object)) - owners));
    }
    if (*std::max_element(disagreementM.begin(), disagreementM.end()) < 1e-6) break;
  }
  // every peer sees the same owners: the first took left, the second middle, the third right
  for (std::size_t i = 0; i < 3; ++i) {
    for (int object = 0; object < 3; ++object)
      EXPECT_EQ(std::to_string(final[i].objects(object).owner_peer()),
                peers[static_cast<std::size_t>(object)]->id);
  }
  std::printf(
      "[ figures  ] %s: left pushed %.2f mm, deepest overlap %.4f mm; disagreement at rest: left %.6f, "
      "middle "
      "%.6f, right %.6f mm\n",
      path.delay.empty() ? "direct" : (path.delay + " ms, " + path.loss + " lost").c_str(), pushedM * 1e3,
      deepestM * 1e3, disagreementM[0] * 1e3, disagreementM[1] * 1e3, disagreementM[2] * 1e3);
  for (const double d : disagreementM) EXPECT_LT(d, 1e-6);
  if (::testing::Test::HasFailure()) {
    for (std::size_t i = 0; i < 3; ++i) {
      for (int object = 0; object < 3; ++object) {
        const glm::dvec3 at = positionOf(final[i].objects(object));
        std::printf("peer %zu sees %s at %.6f %.6f %.6f mm, travel share %.4f, contacts %u\n", i,
                    kBoxes[static_cast<std::size_t>(object)], at.x * 1e3, at.y * 1e3, at.z * 1e3,
                    final[i].objects(object).travel_share(), final[i].objects(object).contacts());
      }
    }
  }

  std::array<nlohmann::json, 3> summaries;
  for (std::size_t i = 0; i < 3; ++i) summaries[i] = PeerCommand::stop(*peers[i]);
  if (::testing::Test::HasFailure()) {
    for (std::size_t i = 0; i < 3; ++i)
      std::printf("---- peer %s\n%s%s\n", peers[i]->id.c_str(), peers[i]->child->err().c_str(),
                  summaries[i].dump().c_str());
  }
  for (std::size_t i = 0; i < 3; ++i) {
    const nlohmann::json& peer = summaries[i].at("peer");
    EXPECT_GE(peer.at("remote_states").get<std::uint64_t>(), 100u);
    EXPECT_EQ(peer.at("open_results").at("forged"), 0);
    EXPECT_EQ(peer.at("malformed"), 0);
    std::printf("[ figures  ] peer %zu: %llu datagrams and %llu bytes out, %llu in, over %.1f s\n", i,
                peer.at("datagrams_out").get<unsigned long long>(),
                peer.at("bytes_out").get<unsigned long long>(), peer.at("bytes_in").get<unsigned long long>(),
                summaries[i].at("wall_s").get<double>());
  }
  // the last to stop saw the others leave (a leave lost on a lossy path times out instead)
  if (path.delay.empty()) {
    EXPECT_TRUE(summaries[2].at("peer").at("members").empty()) << summaries[2].dump();
  }
}

TEST_F(PeerCommand, UsageErrorsExitTwoAndSayWhatIsWrong) {
  for (const auto& [args, says] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"peer"}, "SCENE"},
           {{"peer", "boxes.glb", "--join", "127.0.0.1:7500"}, "--key"},
           {{"peer", "boxes.glb", "--device", "script:hold.txt"}, "--take"},
           {{"peer", "boxes.glb", "--rate", "50"}, "100 to 1000"},
           {{"peer", "boxes.glb", "--passive", "--take", "left"}, "--passive"},
           {{"peer", "boxes.glb", "--join", "127.0.0.1:0", "--key", "session.key"}, "--join"},
       }) {
    const CliRun r = voxhap(args);
    EXPECT_EQ(r.exitCode, 2) << args.back() << "\n" << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
  }
  // a key file that is no key: an error naming the file
  std::ofstream(dir_ / "bad.key") << "not hex\n";
  const CliRun bad =
      voxhap({"peer", "boxes.glb", "--move", "left", "--key", "bad.key", "--headless", "--duration", "1"});
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_NE(bad.err.find("bad.key"), std::string::npos) << bad.err;
}

TEST_F(PeerCommand, PeersJoinLeaveAndDieDuringContactAndTheRestGoOn) {
  Peer a = startPeer("a", {"--take", "middle", "--device", "script:hold.txt", "--name", "ann"});
  ASSERT_NE(a.udpPort, 0);
  const std::string at = "127.0.0.1:" + std::to_string(a.udpPort);
  // b presses its box into a's from the start: a moving join during contact
  std::ofstream(dir_ / "press.txt") << "0 1 0 0 0 0 0 0\n0.5 1 0 0 0 0.012 0 0\n60 1 0 0 0 0.012 0 0\n";
  Peer b = startPeer("b", {"--join", at, "--take", "left", "--device", "script:press.txt", "--name", "bob"});
  ASSERT_NE(b.udpPort, 0);
  net::FrontendClient client("127.0.0.1", a.frontendPort, 5000ms);
  client.hello("peer test");
  subscribe(client);
  // (up to 30 s: a sanitizer's build is slower)
  std::uint32_t contacts = 0;
  for (int i = 0; i < 600 && contacts == 0; ++i) {
    contacts = newestUpdate(client).objects(1).contacts();
    std::this_thread::sleep_for(50ms);
  }
  EXPECT_GT(contacts, 0u) << "a's box felt no push";
  // c joins while they touch, and leaves again
  Peer c = startPeer("c", {"--join", at, "--take", "right", "--device", "script:hold.txt", "--name", "cyd"});
  ASSERT_NE(c.udpPort, 0);
  EXPECT_TRUE(c.child->waitForStderr("'right' is this peer's", 30s)) << c.child->err();
  const nlohmann::json left = stop(c);
  EXPECT_EQ(left.at("peer").at("members").size(), 2u) << left.dump();
  EXPECT_TRUE(a.child->waitForStderr("(cyd) left", 10s)) << a.child->err();
  // b dies while pressing: a times it out (1 s), and b's box stops where it was, nobody's
  b.child->signal(SIGKILL);
  EXPECT_TRUE(a.child->waitForStderr("(bob) timed out", 10s)) << a.child->err();
  pb::FrameUpdate after = newestUpdate(client);
  for (int i = 0; i < 100 && after.objects(0).owner_peer() != 0u; ++i) after = newestUpdate(client);
  EXPECT_EQ(after.objects(0).owner_peer(), 0u);
  EXPECT_EQ(std::to_string(after.objects(1).owner_peer()), a.id);
  std::this_thread::sleep_for(300ms);
  const pb::FrameUpdate later = newestUpdate(client);
  EXPECT_GT(later.frame(), after.frame());                                // a goes on
  EXPECT_EQ(positionOf(later.objects(0)), positionOf(after.objects(0)));  // b's box does not move
  const nlohmann::json summary = stop(a);
  EXPECT_TRUE(summary.at("peer").at("members").empty()) << summary.dump();
  EXPECT_EQ(summary.at("peer").at("open_results").at("forged"), 0);
}

TEST_F(PeerCommand, AMillionRandomAndMutatedDatagramsLeaveAPeerRunningAndCounted) {
  Peer a = startPeer("a", {"--take", "middle", "--device", "script:hold.txt"});
  ASSERT_NE(a.udpPort, 0);
  // the session's id as any key holder derives it, for datagrams that pass the first checks
  asio::io_context io;
  const net::SessionKey key = net::SessionKey::fromFile(dir_ / "session.key");
  const std::uint64_t session = net::PeerSession(io, key, {}, [](const std::string&) {}).sessionId();
  net::DatagramSealer sealer(key, session, 4242, 1);
  asio::ip::udp::socket socket(io, asio::ip::udp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  const asio::ip::udp::endpoint target(asio::ip::make_address("127.0.0.1"), a.udpPort);
  const std::size_t count = test::kSanitizer ? 100'000 : 1'000'000;
  std::mt19937_64 random(31);
  std::vector<std::uint8_t> sealed(net::kMaxDatagramBytes), bytes(1400), authentic;
  const auto started = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < count; ++i) {
    std::size_t n = random() % bytes.size();
    for (std::size_t k = 0; k < n; k += 8) {
      const std::uint64_t r = random();
      std::memcpy(bytes.data() + k, &r, std::min<std::size_t>(8, n - k));
    }
    switch (i % 4) {
      case 1: {  // sealed, then a bit flipped or cut short
        const std::size_t payload = random() % 200;
        const std::size_t m =
            sealer.seal(net::DatagramKind::State, 0, std::span(bytes.data(), payload), sealed);
        std::copy(sealed.begin(), sealed.begin() + static_cast<std::ptrdiff_t>(m), bytes.begin());
        n = random() % 2 ? m : random() % m;
        if (n == m) bytes[random() % m] ^= static_cast<std::uint8_t>(1u << (random() % 8));
        break;
      }
      case 2:  // the right magic and session, the rest random
        std::copy(sealed.begin(), sealed.begin() + 16, bytes.begin());
        n = std::max<std::size_t>(n, 16);
        break;
      case 3:  // authentic, with a payload that is no message (and replayed now and then)
        if (i % 1000 == 3) {
          n = sealer.seal(net::DatagramKind::Event, 0, std::span(bytes.data() + 600, random() % 100), sealed);
          authentic.assign(sealed.begin(), sealed.begin() + static_cast<std::ptrdiff_t>(n));
        }
        if (i % 1000 == 3 || i % 1000 == 7) {  // and again: a replay
          std::copy(authentic.begin(), authentic.end(), bytes.begin());
          n = authentic.size();
        }
        break;
    }
    asio::error_code ec;
    socket.send_to(asio::buffer(bytes.data(), n), target, 0, ec);
  }
  const double sendS = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  // it still runs: its frames go on and a front end is served
  net::FrontendClient client("127.0.0.1", a.frontendPort, 5000ms);
  client.hello("after the flood");
  subscribe(client);
  const std::uint64_t frame = newestUpdate(client).frame();
  std::this_thread::sleep_for(200ms);
  EXPECT_GT(newestUpdate(client).frame(), frame);
  const nlohmann::json summary = stop(a);
  const nlohmann::json& peer = summary.at("peer");
  std::uint64_t outcomes =
      peer.at("flooded").get<std::uint64_t>() + peer.at("unexpected").get<std::uint64_t>();
  for (const auto& [result, n] : peer.at("open_results").items()) outcomes += n.get<std::uint64_t>();
  // every datagram that reached it was counted once (the kernel drops what its buffer cannot hold)
  EXPECT_EQ(outcomes, peer.at("datagrams_in").get<std::uint64_t>()) << peer.dump();
  EXPECT_GT(peer.at("datagrams_in").get<std::uint64_t>(), count / 100);
  EXPECT_EQ(peer.at("members").size(), 0u);
  std::printf(
      "[ figures  ] %zu datagrams sent in %.2f s (%.0f/s); the peer took %llu: %llu flooded, %llu forged, "
      "%llu "
      "not ours, %llu bad size, %llu replayed, %llu opened; haptic period p99 %.0f us, max %.0f us, %llu "
      "overruns\n",
      count, sendS, static_cast<double>(count) / sendS, peer.at("datagrams_in").get<unsigned long long>(),
      peer.at("flooded").get<unsigned long long>(),
      peer.at("open_results").at("forged").get<unsigned long long>(),
      peer.at("open_results").at("not_ours").get<unsigned long long>(),
      peer.at("open_results").at("bad_size").get<unsigned long long>(),
      peer.at("open_results").at("replayed").get<unsigned long long>(),
      peer.at("open_results").at("opened").get<unsigned long long>(),
      summary.at("period").at("p99_us").get<double>(), summary.at("period").at("max_us").get<double>(),
      summary.at("period").at("overruns").get<unsigned long long>());
}

TEST_F(PeerCommand, ThreePeersPushEachOthersBoxesAndAgreeWhereEveryBoxIs) {
  pushScenario(*this, {});
}

TEST_F(PeerCommand, ThroughRelaysOf0And100And300MillisecondsLosingFivePercentTheyStillAgree) {
  for (const char* delay : {"0", "100", "300"}) {
    SCOPED_TRACE(std::string(delay) + " ms");
    pushScenario(*this, {delay, "5%", ""});
  }
}

}  // namespace
}  // namespace voxhap::test

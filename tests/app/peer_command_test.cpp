// `voxhap peer`, run as the real executable: three peers on loopback, each owning one of
// three boxes on a plate, one pushing its box into another's (type-1, issue 12). Front-end
// clients read what every peer shows. Every wait is bounded; no assertion is about how
// long anything took.

#include <array>
#include <cmath>
#include <csignal>
#include <fstream>
#include <map>
#include <thread>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "net/frontend/frontend_client.h"
#include "support/child_process.h"
#include "support/cli_runner.h"
#include "support/gltf_fixtures.h"

namespace voxhap::test {
namespace {

using namespace std::chrono_literals;
namespace pb = net::pb;

constexpr double kVoxelM = 0.001;
constexpr std::array<const char*, 3> kBoxes = {"left", "middle", "right"};

/// An axis-aligned box of half extents `half` about `centre`, m.
MeshData box(const glm::vec3& centre, const glm::vec3& half) {
  MeshData m = unitCube();
  for (glm::vec3& p : m.positions) p = centre + (2.0f * p - 1.0f) * half;
  return m;
}

/// A 200 × 200 × 10 mm plate whose top is z = 0 and three 20 mm boxes 3 mm over it, their
/// centres 25 mm apart along x (5 mm gaps).
void writeBoxesScene(const std::filesystem::path& dir) {
  GltfDoc doc;
  doc.addMeshNode(doc.addMesh(box({0.0f, 0.0f, -0.005f}, {0.1f, 0.1f, 0.005f})), "plate");
  for (int i = 0; i < 3; ++i)
    doc.addMeshNode(doc.addMesh(box({0.025f * static_cast<float>(i - 1), 0.0f, 0.013f}, glm::vec3(0.01f))),
                    kBoxes[static_cast<std::size_t>(i)]);
  writeDoc(doc, dir, "boxes", BufferStorage::Glb);
}

class PeerCommand : public CliTest {
protected:
  struct Peer {
    std::unique_ptr<ChildProcess> child;
    std::uint16_t udpPort = 0;
    std::uint16_t frontendPort = 0;
    std::string id;
  };

  void SetUp() override {
    CliTest::SetUp();
    writeBoxesScene(dir_);
    std::ofstream(dir_ / "session.key") << std::string(64, 'a') << "\n";
    // one holds its box where it is; the other pushes its box 15 mm to +x in 1 s, into the
    // next one (5 mm away), and holds it there
    std::ofstream(dir_ / "hold.txt") << "0 1 0 0 0 0 0 0\n30 1 0 0 0 0 0 0\n";
    std::ofstream(dir_ / "push.txt")
        << "0 1 0 0 0 0 0 0\n0.5 1 0 0 0 0 0 0\n1.5 1 0 0 0 0.015 0 0\n30 1 0 0 0 0.015 0 0\n";
  }

  /// Starts a headless peer of the boxes scene with `extra` arguments; waits until it
  /// listens for peers and front ends.
  Peer startPeer(const std::string& name, std::vector<std::string> extra) {
    std::vector<std::string> args = {
        "peer",       "boxes.glb",     "--move",       "left",      "--move", "middle",
        "--move",     "right",         "--voxel-size", "1mm",       "--key",  "session.key",
        "--headless", "--no-realtime", "--json",       "--timeout", "1"};
    args.insert(args.end(), extra.begin(), extra.end());
    Peer p;
    p.child = std::make_unique<ChildProcess>(VOXHAP_EXE, args, dir_, name);
    const auto id = p.child->waitForStderr("voxhap: peer ", 120s);
    const auto udp = p.child->waitForStderr("listening for peers on 127.0.0.1:", 120s);
    const auto tcp = p.child->waitForStderr("listening on 127.0.0.1:", 120s);
    EXPECT_TRUE(id && udp && tcp) << p.child->err();
    if (!id || !udp || !tcp) return p;
    p.id = id->substr(0, id->find(' '));
    p.udpPort = static_cast<std::uint16_t>(std::stoi(*udp));
    p.frontendPort = static_cast<std::uint16_t>(std::stoi(*tcp));
    return p;
  }

  /// Peer `p`'s JSON summary once it has stopped after SIGTERM.
  static nlohmann::json stop(Peer& p) {
    p.child->signal(SIGTERM);
    const auto status = p.child->wait(30s);
    EXPECT_EQ(status.value_or(-2), 0) << p.child->err();
    return nlohmann::json::parse(p.child->out(), nullptr, false);
  }
};

/// The newest frame update a subscribed client has, waiting up to 10 s for one.
pb::FrameUpdate newestUpdate(net::FrontendClient& client) {
  std::optional<pb::FrameUpdate> last;
  for (auto until = std::chrono::steady_clock::now() + 10s; std::chrono::steady_clock::now() < until;) {
    const auto event = client.nextEvent(last ? 1ms : 1000ms);
    if (!event) {
      if (last) break;
      continue;
    }
    if (event->has_frame_update()) last = event->frame_update();
  }
  EXPECT_TRUE(last) << "no frame update";
  return last.value_or(pb::FrameUpdate{});
}

glm::dvec3 positionOf(const pb::ObjectState& o) {
  return {o.pose().position_m().x(), o.pose().position_m().y(), o.pose().position_m().z()};
}

TEST_F(PeerCommand, ThreePeersPushEachOthersBoxesAndAgreeWhereEveryBoxIs) {
  Peer a = startPeer("a", {"--take", "left", "--device", "script:push.txt", "--name", "ann"});
  ASSERT_NE(a.udpPort, 0);
  Peer b = startPeer("b", {"--join", "127.0.0.1:" + std::to_string(a.udpPort), "--take", "middle", "--device",
                           "script:hold.txt", "--name", "bob"});
  ASSERT_NE(b.udpPort, 0);
  // the third joins through the second: it learns of the first from the welcome
  Peer c = startPeer("c", {"--join", "127.0.0.1:" + std::to_string(b.udpPort), "--take", "right", "--device",
                           "script:hold.txt", "--name", "cyd"});
  ASSERT_NE(c.udpPort, 0);

  std::array<Peer*, 3> peers = {&a, &b, &c};
  std::vector<std::unique_ptr<net::FrontendClient>> clients;
  for (Peer* p : peers) {
    clients.push_back(std::make_unique<net::FrontendClient>("127.0.0.1", p->frontendPort, 5000ms));
    clients.back()->hello("peer test");
    pb::ClientMessage subscribe;
    subscribe.mutable_subscribe()->set_rate_hz(50.0);
    ASSERT_TRUE(clients.back()->request(subscribe).has_done());
  }
  // while the left box is pushed into the middle one: the middle one's owner feels it
  // through its contacts, and on every peer the left box stays out of the middle one
  std::array<std::uint32_t, 3> middleContacts{};
  double deepestM = 0.0;
  for (auto until = std::chrono::steady_clock::now() + 4s; std::chrono::steady_clock::now() < until;) {
    for (std::size_t i = 0; i < clients.size(); ++i) {
      const pb::FrameUpdate u = newestUpdate(*clients[i]);
      ASSERT_EQ(u.objects_size(), 3);
      middleContacts[i] = std::max(middleContacts[i], u.objects(1).contacts());
      // left's +x face at −15 mm + its motion, middle's −x face at −10 mm + its motion
      const double overlapM = (positionOf(u.objects(0)).x - 0.015) - (positionOf(u.objects(1)).x - 0.010);
      deepestM = std::max(deepestM, overlapM);
    }
    std::this_thread::sleep_for(50ms);
  }
  EXPECT_GT(middleContacts[1], 0u) << "the middle box's owner felt no contact";
  EXPECT_LT(deepestM, 0.1 * kVoxelM);

  // at rest, every peer shows every box where its owner has it: the free one exactly (its
  // owner's newest state), the two in contact within half a voxel (where a remote box
  // presses a local one, the local step yields only part of the way: FrameInputs::kinematic)
  std::array<pb::FrameUpdate, 3> final;
  for (std::size_t i = 0; i < clients.size(); ++i) final[i] = newestUpdate(*clients[i]);
  EXPECT_GT(positionOf(final[0].objects(0)).x, 0.003) << "the left box was not pushed";
  std::array<double, 3> disagreementM{};
  for (int object = 0; object < 3; ++object) {
    const auto o = static_cast<std::size_t>(object);
    const glm::dvec3 owners = positionOf(final[o].objects(object));
    for (std::size_t i = 0; i < 3; ++i) {
      disagreementM[o] =
          std::max(disagreementM[o], glm::length(positionOf(final[i].objects(object)) - owners));
      // every peer sees the same owners: the first took left, the second middle, the third right
      EXPECT_EQ(std::to_string(final[i].objects(object).owner_peer()), peers[o]->id) << "peer " << i;
    }
  }
  std::printf(
      "[ figures  ] deepest overlap %.4f mm; disagreement at rest: left %.4f, middle %.4f, right %.6f mm\n",
      deepestM * 1e3, disagreementM[0] * 1e3, disagreementM[1] * 1e3, disagreementM[2] * 1e3);
  EXPECT_LT(disagreementM[0], 0.5 * kVoxelM);
  EXPECT_LT(disagreementM[1], 0.5 * kVoxelM);
  EXPECT_LT(disagreementM[2], 1e-6);

  std::array<nlohmann::json, 3> summaries;
  for (std::size_t i = 0; i < 3; ++i) summaries[i] = stop(*peers[i]);
  for (std::size_t i = 0; i < 3; ++i) {
    const nlohmann::json& peer = summaries[i].at("peer");
    EXPECT_GE(peer.at("remote_states").get<std::uint64_t>(), 100u);
    EXPECT_EQ(peer.at("open_results").at("forged"), 0);
    EXPECT_EQ(peer.at("malformed"), 0);
  }
  // the last to stop saw the others leave
  EXPECT_TRUE(summaries[2].at("peer").at("members").empty()) << summaries[2].dump();
}

}  // namespace
}  // namespace voxhap::test

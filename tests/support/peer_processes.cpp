#include "support/peer_processes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <fstream>
#include <thread>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "net/peer/free_udp_port.h"
#include "support/gltf_fixtures.h"

namespace voxhap::test {
namespace {

using namespace std::chrono_literals;
namespace pb = net::pb;

/// An axis-aligned box of half extents `half` about `centre`, m.
MeshData box(const glm::vec3& centre, const glm::vec3& half) {
  MeshData m = unitCube();
  for (glm::vec3& p : m.positions) p = centre + (2.0f * p - 1.0f) * half;
  return m;
}

}  // namespace

void writeBoxesScene(const std::filesystem::path& dir) {
  GltfDoc doc;
  doc.addMeshNode(doc.addMesh(box({0.0f, 0.0f, -0.005f}, {0.1f, 0.1f, 0.005f})), "plate");
  for (int i = 0; i < 3; ++i)
    doc.addMeshNode(doc.addMesh(box({0.025f * static_cast<float>(i - 1), 0.0f, 0.013f}, glm::vec3(0.01f))),
                    kBoxes[static_cast<std::size_t>(i)]);
  writeDoc(doc, dir, "boxes", BufferStorage::Glb);
}

void PeerProcessTest::SetUp() {
  CliTest::SetUp();
  writeBoxesScene(dir_);
  std::ofstream(dir_ / "session.key") << std::string(64, 'a') << "\n";
  std::ofstream(dir_ / "hold.txt") << "0 1 0 0 0 0 0 0\n60 1 0 0 0 0 0 0\n";
}

PeerProcessTest::Peer PeerProcessTest::startPeer(const std::string& name, std::vector<std::string> extra) {
  std::vector<std::string> args = {"peer",   "boxes.glb",   "--move",     "left",          "--move",
                                   "middle", "--move",      "right",      "--voxel-size",  "1mm",
                                   "--key",  "session.key", "--headless", "--no-realtime", "--json"};
  if (std::find(extra.begin(), extra.end(), "--timeout") == extra.end())
    args.insert(args.end(), {"--timeout", "1"});
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
  p.advertisedPort = p.udpPort;
  for (std::size_t i = 0; i + 1 < extra.size(); ++i) {
    if (extra[i] == "--advertise")
      p.advertisedPort =
          static_cast<std::uint16_t>(std::stoi(extra[i + 1].substr(extra[i + 1].rfind(':') + 1)));
  }
  p.frontendPort = static_cast<std::uint16_t>(std::stoi(*tcp));
  return p;
}

nlohmann::json PeerProcessTest::stop(Peer& p) {
  p.child->signal(SIGTERM);
  const auto status = p.child->wait(30s);
  EXPECT_EQ(status.value_or(-2), 0) << p.child->err();
  return nlohmann::json::parse(p.child->out(), nullptr, false);
}

std::vector<std::string> PeerPlacement::place(const std::string& name, std::vector<std::string> args) {
  if (path_.delay.empty()) return args;
  const std::uint16_t port = net::freeLoopbackUdpPort();
  const std::string jitter =
      path_.jitter.empty() ? std::to_string(std::stod(path_.delay) / 10.0) : path_.jitter;
  relays_.push_back(std::make_unique<ChildProcess>(
      VOXHAP_EXE,
      std::vector<std::string>{"relay", "--to", "127.0.0.1:" + std::to_string(port), "--delay",
                               path_.delay + "ms", "--jitter", jitter + "ms", "--loss", path_.loss, "--seed",
                               std::to_string(relays_.size() + 1)},
      test_.dir(), name + "-relay" + path_.delay));
  const auto relayPort = relays_.back()->waitForStderr("relaying 127.0.0.1:", 30s);
  EXPECT_TRUE(relayPort) << relays_.back()->err();
  if (!relayPort) return args;
  args.insert(args.end(), {"--listen", "127.0.0.1:" + std::to_string(port), "--advertise",
                           "127.0.0.1:" + relayPort->substr(0, relayPort->find(' '))});
  return args;
}

std::string PeerPlacement::advertised(const PeerProcessTest::Peer& p) {
  return "127.0.0.1:" + std::to_string(p.advertisedPort);
}

glm::dvec3 positionOf(const pb::ObjectState& o) {
  return {o.pose().position_m().x(), o.pose().position_m().y(), o.pose().position_m().z()};
}

void subscribe(net::FrontendClient& client) {
  pb::ClientMessage subscribe;
  subscribe.mutable_subscribe()->set_rate_hz(50.0);
  ASSERT_TRUE(client.request(subscribe).has_done());
}

void slideHandle(net::FrontendClient& client, const std::string& object, const glm::dvec3& fromM,
                 const glm::dvec3& toM) {
  const int steps = std::max(1, static_cast<int>(std::lround(glm::length(toM - fromM) / 0.001)));
  for (int i = 1; i <= steps; ++i) {
    pb::ClientMessage move;
    move.mutable_move_handle()->set_object(object);
    const glm::dvec3 at = fromM + (toM - fromM) * (static_cast<double>(i) / steps);
    pb::Vec3& position = *move.mutable_move_handle()->mutable_handle()->mutable_position_m();
    position.set_x(at.x);
    position.set_y(at.y);
    position.set_z(at.z);
    move.mutable_move_handle()->mutable_handle()->mutable_orientation()->set_w(1.0);
    const pb::ServerMessage reply = client.request(move);
    ASSERT_TRUE(reply.has_done()) << reply.DebugString();
    std::this_thread::sleep_for(20ms);
  }
}

}  // namespace voxhap::test

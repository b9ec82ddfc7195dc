#pragma once
/// Test support for sessions of real `voxhap peer` processes on loopback: a scene of three
/// boxes on a plate, peers started headless and stopped for their JSON summaries, each
/// optionally behind its own impairment relay (`voxhap relay`), and front-end helpers.

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "net/frontend/frontend_client.h"
#include "support/child_process.h"
#include "support/cli_runner.h"

namespace voxhap::test {

/// The boxes scene's voxel size, m.
inline constexpr double kBoxesVoxelM = 0.001;
/// Its moving boxes, in the scene's order.
inline constexpr std::array<const char*, 3> kBoxes = {"left", "middle", "right"};

/// A 200 × 200 × 10 mm plate whose top is z = 0 and three 20 mm boxes 3 mm over it, their
/// centres 25 mm apart along x (5 mm gaps), as dir/boxes.glb.
void writeBoxesScene(const std::filesystem::path& dir);

/// A fixture whose folder holds the boxes scene, session.key and hold.txt (a script that
/// holds its object where it is for 60 s).
class PeerProcessTest : public CliTest {
public:
  struct Peer {
    std::unique_ptr<ChildProcess> child;
    std::uint16_t udpPort = 0;
    std::uint16_t advertisedPort = 0;  ///< where the others send to (a relay, or udpPort)
    std::uint16_t frontendPort = 0;
    std::string id;
  };

  const std::filesystem::path& dir() const { return dir_; }

  /// Starts a headless peer of the boxes scene with `extra` arguments (and --timeout 1
  /// unless they say otherwise); waits until it listens for peers and front ends.
  Peer startPeer(const std::string& name, std::vector<std::string> extra);
  /// Peer `p`'s JSON summary once it has stopped after SIGTERM.
  static nlohmann::json stop(Peer& p);

protected:
  void SetUp() override;
};

/// The path between the peers: direct, or each peer behind a relay that delays what comes
/// to it by `delay` ms ± `jitter` ms (a tenth of the delay when empty) and loses `loss` of it.
struct Path {
  std::string delay;  ///< empty: direct
  std::string loss = "5%";
  std::string jitter;
};

/// Puts each peer where `path` says: behind a relay of its own, or directly.
class PeerPlacement {
public:
  PeerPlacement(PeerProcessTest& test, Path path) : test_(test), path_(std::move(path)) {}
  /// `args` of the peer `name`, with --listen and --advertise for its relay when there is one.
  std::vector<std::string> place(const std::string& name, std::vector<std::string> args);
  /// "127.0.0.1:PORT" where the others reach `p`.
  static std::string advertised(const PeerProcessTest::Peer& p);

private:
  PeerProcessTest& test_;
  Path path_;
  std::vector<std::unique_ptr<ChildProcess>> relays_;
};

glm::dvec3 positionOf(const net::pb::ObjectState& o);

/// Subscribes `client` (hello done) to frame updates at 50 Hz.
void subscribe(net::FrontendClient& client);

/// Moves the handle of `object` on `client`'s controller in a straight line from `fromM`
/// to `toM` (offsets from its place in the scene, m) in steps of 1 mm every 20 ms.
void slideHandle(net::FrontendClient& client, const std::string& object, const glm::dvec3& fromM,
                 const glm::dvec3& toM);

}  // namespace voxhap::test

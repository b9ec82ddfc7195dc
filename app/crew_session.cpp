#include "app/crew_session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>

#include <unistd.h>

#include "app/controller/inprocess_controller.h"
#include "haptics/core/error.h"
#include "net/frontend/frontend_client.h"
#include "net/frontend/pose_proto.h"
#include "net/peer/free_udp_port.h"
#include "net/peer/session_key.h"

namespace voxhap::cli {
namespace {

namespace pb = net::pb;
using Clock = std::chrono::steady_clock;

/// One user's peer: its controller, its diagnostics and the front end that watches it.
struct CrewPeer {
  std::ostringstream log;
  std::unique_ptr<Console> console;
  std::unique_ptr<InProcessController> controller;
  std::unique_ptr<net::FrontendClient> client;
};

pb::FrameUpdate newest(CrewPeer& peer, const CrewUser& user) {
  const std::optional<pb::FrameUpdate> u = peer.client->newestUpdate();
  if (!u) throw Error(user.name + "'s peer sends no frames");
  return *u;
}

/// What, as `peers` show it, keeps a user's part from where that user needs it (a shared
/// part shared by all its users, an owned one owned); empty when every part is ready.
std::string partsNotReady(std::vector<std::unique_ptr<CrewPeer>>& peers, const std::vector<CrewUser>& users,
                          const std::vector<std::string>& objects) {
  std::string why;
  for (std::size_t p = 0; p < peers.size(); ++p) {
    const pb::FrameUpdate u = newest(*peers[p], users[p]);
    for (const CrewUser& user : users) {
      const auto index = std::find(objects.begin(), objects.end(), user.object) - objects.begin();
      const pb::ObjectState& o = u.objects(static_cast<int>(index));
      const auto sharers = std::count_if(users.begin(), users.end(), [&](const CrewUser& other) {
        return other.share && other.object == user.object;
      });
      if (user.share && o.sharer_peers_size() != sharers) {
        why += "\n  on " + users[p].name + "'s peer '" + user.object + "' has " +
               std::to_string(o.sharer_peers_size()) + " sharer(s), not " + std::to_string(sharers);
      } else if (!user.share && o.owner_peer() == 0) {
        why += "\n  on " + users[p].name + "'s peer '" + user.object + "' is nobody's";
      }
    }
  }
  return why;
}

/// The last `lines` lines of `text`.
std::string tail(const std::string& text, std::size_t lines) {
  std::size_t from = text.size();
  for (std::size_t n = 0; from > 0 && n <= lines;) {
    if (text[--from] == '\n') ++n;
  }
  return text.substr(from == 0 ? 0 : from + 1);
}

}  // namespace

CrewSessionResult runCrewSession(const CrewSessionOptions& options, Console& console,
                                 const std::function<void(double)>& progress) {
  if (options.users.empty()) throw Error("a session needs a user");
  // the key every peer reads, in a folder of this run's own that only this user can read
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("voxhap-session-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::filesystem::permissions(dir, std::filesystem::perms::owner_all,
                               std::filesystem::perm_options::replace);
  struct RemoveDir {
    std::filesystem::path dir;
    ~RemoveDir() {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  } removeDir{dir};
  const std::filesystem::path keyFile = dir / "session.key";
  std::ofstream(keyFile) << net::SessionKey::generate().toHex() << "\n";

  const std::uint16_t firstPort = net::freeLoopbackUdpPort();
  std::vector<std::unique_ptr<CrewPeer>> peers;
  for (std::size_t k = 0; k < options.users.size(); ++k) {
    const CrewUser& user = options.users[k];
    ControllerOptions o;
    o.scene = options.scene;
    o.model = options.model;
    o.realtime = options.realtime;
    PeerRunOptions peer;
    peer.listenPort = k == 0 ? firstPort : 0;
    if (k > 0) {
      peer.joinHost = "127.0.0.1";
      peer.joinPort = firstPort;
    }
    peer.keyFile = keyFile.string();
    (user.share ? peer.share : peer.take) = user.object;
    peer.name = user.name;
    peer.passivity = options.passivity;
    peer.joinPatienceS = options.patienceS;
    o.peer = peer;
    auto p = std::make_unique<CrewPeer>();
    p->console = std::make_unique<Console>(p->log, false);
    console.info("starting " + user.name + "'s peer (" + (user.share ? "shares " : "takes ") + user.object +
                 ")");
    try {
      p->controller = std::make_unique<InProcessController>(o, *p->console);
    } catch (const std::exception& e) {
      throw Error(user.name + "'s peer did not start: " + e.what() + "\n" + p->log.str());
    }
    p->client = std::make_unique<net::FrontendClient>("127.0.0.1", p->controller->port());
    p->client->hello("voxhap demo");
    pb::ClientMessage subscribe;
    subscribe.mutable_subscribe()->set_rate_hz(options.sampleHz);
    if (!p->client->request(subscribe).has_done()) throw Error(user.name + "'s peer refused a subscription");
    peers.push_back(std::move(p));
  }

  if (options.onStarted) {
    std::vector<std::uint16_t> ports;
    for (const auto& p : peers) ports.push_back(p->controller->port());
    options.onStarted(ports);
  }

  CrewSessionResult result;
  // the moving objects' names, in the frame updates' order
  pb::ClientMessage list;
  list.mutable_list_objects();
  const pb::ServerMessage listed = peers[0]->client->request(list);
  for (const pb::ObjectInfo& o : listed.object_list().objects()) {
    if (o.moving()) result.objects.push_back(o.name());
  }
  for (const CrewUser& user : options.users) {
    if (std::find(result.objects.begin(), result.objects.end(), user.object) == result.objects.end())
      throw Error(user.name + "'s part '" + user.object + "' is no moving object of " + options.scene);
  }

  console.info("waiting until every user's part is theirs");
  const auto settleBy = Clock::now() + std::chrono::duration<double>(options.patienceS);
  for (std::string why; !(why = partsNotReady(peers, options.users, result.objects)).empty();) {
    if (Clock::now() > settleBy) {
      std::string logs;
      for (std::size_t k = 0; k < peers.size(); ++k) {
        peers[k]->client.reset();
        peers[k]->controller.reset();  // its threads end: its log is this thread's to read
        logs += "\n" + options.users[k].name + "'s peer, last lines:\n" + tail(peers[k]->log.str(), 20);
      }
      throw Error("the parts were not every user's within the patience (" +
                  std::to_string(std::lround(options.patienceS)) + " s):" + why + logs);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }

  // every user grabs at the same moment: the scripts are written to be played together
  std::vector<double> grabbedS;
  for (std::size_t k = 0; k < peers.size(); ++k) {
    const CrewUser& user = options.users[k];
    pb::ClientMessage grab;
    grab.mutable_grab()->set_object(user.object);
    grab.mutable_grab()->set_device("script:" + user.script.string());
    const pb::ServerMessage reply = peers[k]->client->request(grab);
    if (!reply.has_done())
      throw Error(user.name + " could not grab " + user.object + ": " + reply.DebugString());
    grabbedS.push_back(newest(*peers[k], user).time_s());
  }
  console.info("playing the users' scripts");

  const auto started = Clock::now();
  const auto giveUp = started + std::chrono::duration<double>(3.0 * options.playS + 60.0);
  const auto period = std::chrono::duration<double>(1.0 / options.sampleHz);
  for (double leastPlayedS = 0.0; leastPlayedS < options.playS;) {
    if (Clock::now() > giveUp) throw Error("the peers simulated too slowly: the scripts did not play out");
    leastPlayedS = options.playS;
    for (std::size_t k = 0; k < peers.size(); ++k) {
      const pb::FrameUpdate u = newest(*peers[k], options.users[k]);
      CrewSample& s = result.samples.emplace_back();
      s.peer = k;
      s.playedS = u.time_s() - grabbedS[k];
      for (const pb::ObjectState& o : u.objects()) {
        s.poses.push_back(net::fromProto(o.pose()));
        s.divergent.push_back(o.divergent());
        s.otherInstance.push_back(net::furthestOtherInstance(o));
        s.contacts.push_back(o.contacts());
      }
      leastPlayedS = std::min(leastPlayedS, s.playedS);
    }
    if (progress) progress(std::clamp(leastPlayedS / options.playS, 0.0, 1.0));
    std::this_thread::sleep_for(period);
  }
  result.wallS = std::chrono::duration<double>(Clock::now() - started).count();

  // the last first: the first's summary then lists who left
  result.summaries.resize(peers.size());
  result.logs.resize(peers.size());
  for (std::size_t k = peers.size(); k-- > 0;) {
    peers[k]->client.reset();
    result.summaries[k] = nlohmann::json::parse(peers[k]->controller->stopAndWait(), nullptr, false);
    result.logs[k] = peers[k]->log.str();
  }
  return result;
}

}  // namespace voxhap::cli

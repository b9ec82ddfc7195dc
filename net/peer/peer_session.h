#pragma once
/// One peer's side of a collaborative session over UDP (DESIGN §8, issue 12): the socket,
/// the sealed datagrams, membership, ownership and the state streams. It runs on the
/// comms thread's io_context and never touches the haptic thread: the caller gives it each
/// local frame (tick) and takes the remote states and ownership changes from callbacks.
///
/// Membership. A peer joins through any member: it sends Join (padded, so that no reply
/// is longer) until a Welcome comes, then pulls the welcoming peer's state snapshot in
/// chunks, then streams. The Welcome lists the members; every heartbeat lists the members
/// its sender hears from, so members learn of each other whoever they joined through.
/// A member not heard from for `timeout` is gone, as is one whose heartbeat says it is
/// leaving; a gone member is not taken back from others' lists for kForgetGoneS. One that
/// timed out still gets a heartbeat every kCallGone until then, and is back as soon as
/// its own heartbeat comes: a stall longer than the timeout on either side (a suspended
/// laptop, a starved comms thread) makes both time each other out, and without these
/// calls neither would send to the other again.
///
/// Ownership, as state in every heartbeat (no reliable channel needed: a lost heartbeat
/// only delays the next): a peer lists what it owns, what it wants and what its users
/// hold. An object's owner is the lowest-numbered live peer that lists it; a peer that
/// sees a lower one list what it claims drops its claim. A peer claims what it wants once
/// nobody owns it; an owner hands over what another wants and none of its users holds;
/// a gone owner's objects are nobody's (each peer holds them where they are).
///
/// Shared objects (type-2): a peer that shares an object lists it, with its own instance,
/// in every heartbeat. Each sharer takes the others' instances (onShared); for the peers
/// that do not share it, its owner is its lowest-numbered sharer, whose instance they
/// follow like any owner's. Sharing outranks a claim: nobody owns what somebody shares.

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <asio/io_context.hpp>
#include <asio/ip/udp.hpp>

#include "haptics/dynamics/rigid_body.h"
#include "haptics/sim/sim_state.h"
#include "net/peer/datagram.h"
#include "net/peer/one_way_delay.h"
#include "net/peer/session_key.h"
#include "net/proto/peer.pb.h"

namespace voxhap::net {

struct PeerSessionOptions {
  std::string listenHost = "127.0.0.1";
  std::uint16_t listenPort = 0;  ///< 0: any free port
  std::string name;              ///< the user, for the others' displays
  /// "HOST:PORT" the others send to (a relay in front of this peer, an address they can
  /// reach); empty: the bound address, or where its datagrams come from when that is 0.0.0.0.
  std::string advertise;
  /// What every member must share: scene hash and object count refuse a joiner that
  /// differs; sizes and force layer are accepted with a warning.
  peer::v1::SessionParameters parameters;
  std::chrono::milliseconds timeout{2000};  ///< a member not heard from this long is gone
  /// Peers arriving from other addresses beyond loopback are refused unless this is set.
  bool allowBeyondLoopback = false;
  /// Datagrams taken per second before any cryptography; beyond, dropped and counted.
  double maxDatagramsPerS = 20000.0;
};

/// One local frame as the caller gives it at each tick.
struct LocalFrame {
  std::int64_t endedUs = 0;  ///< the local monotonic clock when it ended
  std::uint64_t frame = 0;
  std::vector<RigidBodyState> bodies;  ///< every moving object
  std::vector<bool> held;              ///< per object: a local user holds it
  /// Per object this peer shares (else ignored): the energy put in at its coupling port
  /// so far, J, and whether its instance is divergent.
  std::vector<double> sharedInJ;
  std::vector<bool> divergent;
};

/// Another peer's instance of an object this peer shares, as this peer last heard of it.
struct SharerView {
  PeerId peer = kNoPeer;
  double oneWayMs = -1.0;  ///< < 0: not measured yet
  bool divergent = false;
  RigidBodyState instance;  ///< as last heard
};

/// What the session counted, for statistics and tests.
struct PeerSessionCounts {
  std::uint64_t datagramsIn = 0;
  std::uint64_t bytesIn = 0;
  std::uint64_t datagramsOut = 0;
  std::uint64_t bytesOut = 0;
  std::uint64_t flooded = 0;    ///< dropped by the rate limit before any check
  std::uint64_t malformed = 0;  ///< authentic but not a payload we understand
  std::uint64_t unexpected =
      0;  ///< authentic, well formed, not for now (a stranger's heartbeat, a stale reply)
  std::uint64_t sendFailures = 0;
  std::array<std::uint64_t, kOpenResults> opened{};  ///< by OpenResult
};

/// A member as this peer sees it.
struct MemberView {
  PeerId peer = kNoPeer;
  std::string endpoint;
  std::string name;
  double rttMs = -1.0;     ///< filtered round trip, < 0: not measured yet
  double oneWayMs = -1.0;  ///< one-way delay as reported (OneWayDelay), < 0: not measured yet
  double sinceHeardS = 0.0;
  bool heard = false;  ///< a heartbeat has come from it (not only word of it from others)
  std::uint64_t bytesIn = 0;
  std::uint64_t bytesOut = 0;
};

class PeerSession {
public:
  using LogFn = std::function<void(const std::string&)>;
  /// A remote owner's state of `object`, arrived at `arrivalUs` (local monotonic clock).
  using RemoteBodyFn = std::function<void(std::uint32_t object, PeerId owner, std::int64_t sentUs,
                                          const RigidBodyState& body, std::int64_t arrivalUs)>;
  /// `object` is `owner`'s now (kNoPeer: nobody's).
  using OwnerFn = std::function<void(std::uint32_t object, PeerId owner)>;
  /// Another sharer's instance of `object`, which this peer shares too, with the energy put
  /// in at its port so far (J), arrived at `arrivalUs`.
  using SharedBodyFn = std::function<void(std::uint32_t object, PeerId sharer, std::int64_t sentUs,
                                          const RigidBodyState& body, double inJ, std::int64_t arrivalUs)>;
  /// The local state as saveState bytes, for a joiner's snapshot.
  using SnapshotFn = std::function<std::vector<std::byte>()>;

  /// Binds the socket (throws Error naming the address when it cannot) and picks this
  /// peer's id at random. Nothing is sent until join() or start().
  PeerSession(asio::io_context& io, const SessionKey& key, PeerSessionOptions options, LogFn log);

  /// Joins through the member at `host:port`: runs `io` (nothing else may be running it)
  /// until the Welcome and the whole snapshot have come, and returns the snapshot. Throws
  /// Error when the member refuses (its reason), or nothing answers within `patience`.
  std::vector<std::byte> join(const std::string& host, std::uint16_t port,
                              std::chrono::milliseconds patience = std::chrono::seconds(10));

  /// Starts receiving (after join(), or as the first member) with the object owners of the
  /// state the loop starts from.
  void start(const std::vector<PeerId>& owners, RemoteBodyFn onBody, OwnerFn onOwner, SnapshotFn snapshot);

  /// Sends this peer's heartbeat, with `frame`'s bodies of the objects it owns, to every
  /// member; times members out; hands over and claims. Call it at the stream rate.
  void tick(const LocalFrame& frame);
  /// Asks for `object`: claimed at the next tick when nobody owns it, else asked of its owner.
  void want(std::uint32_t object);
  /// Shares `object` from the next tick on: lists it with this peer's instance, and hands
  /// the other sharers' instances to `onShared`. After start(); an object out of range is ignored.
  void share(std::uint32_t object, SharedBodyFn onShared);
  bool sharing(std::uint32_t object) const { return shares_.count(object) > 0; }
  /// The other members that share `object`, lowest-numbered first.
  std::vector<SharerView> sharers(std::uint32_t object) const;
  /// Sends a last heartbeat, marked leaving, three times.
  void leave(const LocalFrame& frame);

  PeerId self() const { return self_; }
  std::uint16_t port() const { return socket_.local_endpoint().port(); }
  std::uint64_t sessionId() const { return sessionId_; }
  /// The owner of every object as this peer sees it.
  const std::vector<PeerId>& owners() const { return owners_; }
  std::vector<MemberView> members() const;
  const PeerSessionCounts& counts() const { return counts_; }
  /// Warnings of the join (parameters that differ), for the user to see.
  const std::vector<std::string>& warnings() const { return warnings_; }

private:
  using Clock = std::chrono::steady_clock;
  struct Member {
    asio::ip::udp::endpoint endpoint;
    std::string name;
    Clock::time_point heard{};
    std::set<std::uint32_t> owns, wants, holding, divergent;
    std::map<std::uint32_t, RigidBodyState> shares;  ///< what it shares: its instance, as last heard
    std::uint32_t theirSentUs = 0;                   ///< header send time of their newest datagram
    Clock::time_point theirSentAt{};
    bool heardDirectly = false;
    OneWayDelay delay;
    std::uint64_t bytesIn = 0, bytesOut = 0;
  };
  struct Gone {
    Clock::time_point since{};
    asio::ip::udp::endpoint endpoint;
    bool left = false;  ///< said so; else timed out
    Clock::time_point nextCall{};
  };
  struct Snapshot {
    std::vector<std::byte> bytes;
    Clock::time_point made{};
  };

  void receive();
  void onDatagram(std::size_t size);
  void onState(PeerId from, const DatagramHeader& header, const peer::v1::PeerState& state);
  void onEvent(PeerId from, const DatagramHeader& header, const peer::v1::Event& event);
  void onJoin(PeerId from, const peer::v1::Join& join);
  void send(const asio::ip::udp::endpoint& to, DatagramKind kind, const google::protobuf::Message& payload);
  void sendEvent(const asio::ip::udp::endpoint& to, const peer::v1::Event& event);
  /// Adds `peer` at `endpoint` when it is not a member and not recently gone; `itself`:
  /// its own heartbeat came (not word of it from others), which takes one that timed out back.
  Member* admit(PeerId peer, const asio::ip::udp::endpoint& endpoint, bool itself);
  void drop(PeerId peer, const std::string& why, bool left);
  /// Recomputes owners_ from the members' claims and mine_, calling onOwner for changes.
  void settleOwners();
  peer::v1::PeerState heartbeat(const LocalFrame& frame, bool leaving) const;
  std::uint32_t nowUs32() const;
  bool withinRate();

  asio::io_context& io_;
  PeerSessionOptions options_;
  LogFn log_;
  asio::ip::udp::socket socket_;
  PeerId self_ = kNoPeer;
  std::uint64_t sessionId_ = 0;
  DatagramSealer sealer_;
  DatagramOpener opener_;
  std::vector<std::uint8_t> inBuffer_, payloadBuffer_, outBuffer_;
  asio::ip::udp::endpoint sender_;
  std::map<PeerId, Member> members_;
  std::map<PeerId, Gone> gone_;
  std::map<PeerId, Snapshot> snapshots_;  ///< one per joiner, served in chunks
  std::set<std::uint32_t> mine_, wants_, shares_;
  std::vector<PeerId> owners_;
  std::vector<std::string> warnings_;
  std::string advertised_;  ///< what heartbeats and Welcomes say this peer's endpoint is
  RemoteBodyFn onBody_;
  OwnerFn onOwner_;
  SharedBodyFn onShared_;
  SnapshotFn snapshotFn_;
  bool started_ = false;
  // joining
  std::optional<peer::v1::Welcome> welcome_;
  PeerId welcomer_ = kNoPeer;
  std::vector<std::byte> joinSnapshot_;
  // the rate limit: a token bucket
  double tokens_ = 0.0;
  Clock::time_point tokensAt_{};
  PeerSessionCounts counts_;
};

}  // namespace voxhap::net

#include "net/peer/peer_session.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <sodium.h>

#include "haptics/core/error.h"

namespace voxhap::net {
namespace {

namespace pb = peer::v1;

/// A gone member is not taken back from others' member lists for this long.
constexpr double kForgetGoneS = 30.0;
/// How often one that timed out gets a heartbeat until then.
constexpr auto kCallGone = std::chrono::milliseconds(100);
/// A joiner's snapshot is kept for its chunk requests this long.
constexpr double kKeepSnapshotS = 30.0;
/// Snapshot bytes a chunk carries (with its framing it stays under the largest payload).
constexpr std::size_t kChunkBytes = 1000;
/// How often a joiner repeats an unanswered request.
constexpr auto kRetry = std::chrono::milliseconds(200);
/// A state's send time past this is no monotonic clock (2⁵³ µs is 285 years of uptime; a
/// double holds every µs up to it).
constexpr std::int64_t kLatestSentUs = std::int64_t{1} << 53;

double secondsBetween(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

std::string text(const asio::ip::udp::endpoint& e) {
  return e.address().to_string() + ":" + std::to_string(e.port());
}

std::optional<asio::ip::udp::endpoint> parseEndpoint(const std::string& hostPort) {
  const auto colon = hostPort.rfind(':');
  if (colon == std::string::npos) return std::nullopt;
  asio::error_code ec;
  const asio::ip::address address = asio::ip::make_address(hostPort.substr(0, colon), ec);
  if (ec) return std::nullopt;
  try {
    const int port = std::stoi(hostPort.substr(colon + 1));
    if (port <= 0 || port > 65535) return std::nullopt;
    return asio::ip::udp::endpoint(address, static_cast<std::uint16_t>(port));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

/// The session id every holder of `key` derives alike (BLAKE2b of the key, keyed by a label).
std::uint64_t sessionIdOf(const SessionKey& key) {
  initSodium();
  static constexpr char kLabel[] = "voxhap peer session id";
  std::uint8_t digest[8];
  crypto_generichash(digest, sizeof digest, reinterpret_cast<const unsigned char*>(kLabel), sizeof kLabel - 1,
                     key.bytes().data(), key.bytes().size());
  std::uint64_t id = 0;
  std::memcpy(&id, digest, sizeof id);
  return id;
}

PeerId randomPeerId() {
  initSodium();
  PeerId id = kNoPeer;
  while (id == kNoPeer) id = randombytes_random();
  return id;
}

void toVec3(const glm::dvec3& v, pb::Vec3& out) {
  out.set_x(v.x);
  out.set_y(v.y);
  out.set_z(v.z);
}

glm::dvec3 fromVec3(const pb::Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

void toBody(std::uint32_t object, const RigidBodyState& b, pb::Body& body) {
  body.set_object(object);
  toVec3(b.comWorld, *body.mutable_com_m());
  body.mutable_orientation()->set_w(b.orientation.w);
  body.mutable_orientation()->set_x(b.orientation.x);
  body.mutable_orientation()->set_y(b.orientation.y);
  body.mutable_orientation()->set_z(b.orientation.z);
  toVec3(b.linearVelocityWorld, *body.mutable_velocity_m_per_s());
  toVec3(b.angularVelocityWorld, *body.mutable_angular_velocity_rad_per_s());
}

RigidBodyState fromBody(const pb::Body& body) {
  RigidBodyState b;
  b.comWorld = fromVec3(body.com_m());
  b.orientation = glm::dquat(body.orientation().w(), body.orientation().x(), body.orientation().y(),
                             body.orientation().z());
  b.linearVelocityWorld = fromVec3(body.velocity_m_per_s());
  b.angularVelocityWorld = fromVec3(body.angular_velocity_rad_per_s());
  return b;
}

std::string differs(const char* what, double mine, double theirs) {
  return std::string(what) + " " + std::to_string(theirs) + " here, " + std::to_string(mine) + " there";
}

/// Why `theirs` may not join a session of `mine`, or what differs in what may (warnings).
std::string refusal(const pb::SessionParameters& mine, const pb::SessionParameters& theirs,
                    std::vector<std::string>& warnings) {
  if (mine.scene_hash() != theirs.scene_hash()) return "another scene (its content hash differs)";
  if (mine.moving_objects() != theirs.moving_objects()) {
    return std::to_string(theirs.moving_objects()) + " moving objects, the session has " +
           std::to_string(mine.moving_objects());
  }
  // paper §6.1: a pair's force depends on its voxel size and force layer
  if (mine.voxel_size_m() != theirs.voxel_size_m())
    warnings.push_back(differs("voxel size (m)", theirs.voxel_size_m(), mine.voxel_size_m()));
  if (mine.point_spacing_m() != theirs.point_spacing_m())
    warnings.push_back(differs("point spacing (m)", theirs.point_spacing_m(), mine.point_spacing_m()));
  if (mine.point_offset_m() != theirs.point_offset_m())
    warnings.push_back(differs("point offset (m)", theirs.point_offset_m(), mine.point_offset_m()));
  if (mine.force_layer() != theirs.force_layer())
    warnings.push_back(differs("force layer", theirs.force_layer(), mine.force_layer()));
  if (mine.surface_contact() != theirs.surface_contact()) {
    auto contact = [](bool surface) { return surface ? "surface planes" : "voxel planes"; };
    warnings.push_back(std::string("contact by ") + contact(theirs.surface_contact()) + " here, by " +
                       contact(mine.surface_contact()) + " there");
  }
  return {};
}

}  // namespace

PeerSession::PeerSession(asio::io_context& io, const SessionKey& key, PeerSessionOptions options, LogFn log)
    : io_(io),
      options_(std::move(options)),
      log_(std::move(log)),
      socket_(io),
      self_(randomPeerId()),
      sessionId_(sessionIdOf(key)),
      sealer_(key, sessionId_, self_),
      opener_(key, sessionId_),
      inBuffer_(kMaxDatagramBytes + 1),
      payloadBuffer_(kMaxDatagramPayloadBytes),
      outBuffer_(kMaxDatagramBytes),
      tokens_(options_.maxDatagramsPerS),
      tokensAt_(Clock::now()) {
  asio::error_code ec;
  const asio::ip::address address = asio::ip::make_address(options_.listenHost, ec);
  if (ec) throw Error("--listen: '" + options_.listenHost + "' is not an IP address");
  const asio::ip::udp::endpoint listen(address, options_.listenPort);
  socket_.open(listen.protocol());
  socket_.bind(listen, ec);
  if (ec) {
    throw Error("cannot listen for peers on " + options_.listenHost + ":" +
                std::to_string(options_.listenPort) + ": " + ec.message());
  }
  advertised_ = options_.advertise.empty() ? text(socket_.local_endpoint()) : options_.advertise;
  if (!parseEndpoint(advertised_)) throw Error("--advertise: '" + advertised_ + "' is not HOST:PORT");
  receive();
}

std::uint32_t PeerSession::nowUs32() const {
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(Clock::now().time_since_epoch());
  return static_cast<std::uint32_t>(us.count());
}

bool PeerSession::withinRate() {
  const Clock::time_point now = Clock::now();
  tokens_ = std::min(options_.maxDatagramsPerS,
                     tokens_ + secondsBetween(tokensAt_, now) * options_.maxDatagramsPerS);
  tokensAt_ = now;
  if (tokens_ < 1.0) return false;
  tokens_ -= 1.0;
  return true;
}

void PeerSession::receive() {
  socket_.async_receive_from(asio::buffer(inBuffer_), sender_, [this](asio::error_code ec, std::size_t n) {
    if (ec == asio::error::operation_aborted) return;
    if (!ec) onDatagram(n);
    receive();
  });
}

void PeerSession::onDatagram(std::size_t size) {
  ++counts_.datagramsIn;
  counts_.bytesIn += size;
  if (!withinRate()) {
    ++counts_.flooded;
    return;
  }
  if (!options_.allowBeyondLoopback && !sender_.address().is_loopback()) {
    ++counts_.unexpected;
    return;
  }
  DatagramHeader header;
  std::size_t payloadBytes = 0;
  const OpenResult result =
      opener_.open(std::span(inBuffer_.data(), size), payloadBuffer_, header, payloadBytes);
  ++counts_.opened[static_cast<std::size_t>(result)];
  if (result != OpenResult::Opened) return;
  if (header.sender == self_ || header.sender == kNoPeer) {
    ++counts_.unexpected;
    return;
  }
  const int bytes = static_cast<int>(payloadBytes);
  if (header.kind == DatagramKind::State) {
    pb::PeerState state;
    if (!state.ParseFromArray(payloadBuffer_.data(), bytes) || state.sent_us() <= 0 ||
        state.sent_us() > kLatestSentUs) {
      ++counts_.malformed;
      return;
    }
    onState(header.sender, header, state);
  } else {
    pb::Event event;
    if (!event.ParseFromArray(payloadBuffer_.data(), bytes) || event.body_case() == pb::Event::BODY_NOT_SET) {
      ++counts_.malformed;
      return;
    }
    onEvent(header.sender, header, event);
  }
}

PeerSession::Member* PeerSession::admit(PeerId peer, const asio::ip::udp::endpoint& endpoint, bool itself) {
  if (const auto it = members_.find(peer); it != members_.end()) return &it->second;
  if (const auto it = gone_.find(peer); it != gone_.end()) {
    const double goneS = secondsBetween(it->second.since, Clock::now());
    const bool back = itself && !it->second.left;
    if (goneS < kForgetGoneS && !back) return nullptr;
    if (back) {
      log_("peer " + std::to_string(peer) + " is heard again, " + std::to_string(std::lround(goneS * 1e3)) +
           " ms after it timed out");
    }
    gone_.erase(it);
  }
  if (members_.size() + 1 >= DatagramOpener::kMaxSenders) return nullptr;
  Member& m = members_[peer];
  m.endpoint = endpoint;
  m.heard = Clock::now();
  log_("peer " + std::to_string(peer) + " at " + text(endpoint) + " is a member");
  return &m;
}

void PeerSession::drop(PeerId peer, const std::string& why, bool left) {
  const auto it = members_.find(peer);
  if (it == members_.end()) return;
  log_("peer " + std::to_string(peer) + (it->second.name.empty() ? "" : " (" + it->second.name + ")") + " " +
       why);
  const Clock::time_point now = Clock::now();
  gone_[peer] = {now, it->second.endpoint, left, now};
  members_.erase(it);
  opener_.forget(peer);
  snapshots_.erase(peer);
  settleOwners();
}

void PeerSession::onState(PeerId from, const DatagramHeader& header, const pb::PeerState& state) {
  if (!started_) {
    ++counts_.unexpected;
    return;
  }
  if (state.leaving()) {
    drop(from, "left", true);
    return;
  }
  Member* m = admit(from, sender_, true);
  if (m == nullptr) {
    ++counts_.unexpected;
    return;
  }
  const Clock::time_point now = Clock::now();
  const std::optional<asio::ip::udp::endpoint> advertised = parseEndpoint(state.endpoint());
  m->endpoint = advertised && !advertised->address().is_unspecified() ? *advertised : sender_;
  m->heard = now;
  m->heardDirectly = true;
  m->name = state.name();
  m->bytesIn += kDatagramHeaderBytes + kDatagramTagBytes + static_cast<std::uint64_t>(state.ByteSizeLong());
  m->theirSentUs = header.sendTimeUs;
  m->theirSentAt = now;
  for (const pb::Echo& echo : state.echoes()) {
    if (echo.peer() != self_) continue;
    const std::uint32_t roundUs = nowUs32() - echo.their_sent_us() - echo.held_us();
    if (roundUs > 10'000'000) continue;  // a wrapped or nonsensical echo
    m->delay.addRoundTrip(1e-3 * roundUs);
  }
  m->owns = {state.owns().begin(), state.owns().end()};
  m->wants = {state.wants().begin(), state.wants().end()};
  m->holding = {state.holding().begin(), state.holding().end()};
  m->shares.clear();
  m->divergent.clear();
  for (const pb::Share& share : state.shares()) {
    m->shares[share.body().object()] = fromBody(share.body());
    if (share.divergent()) m->divergent.insert(share.body().object());
  }
  for (const pb::Member& gossip : state.members()) {
    if (gossip.peer() == self_ || gossip.peer() == kNoPeer || members_.count(gossip.peer())) continue;
    const std::optional<asio::ip::udp::endpoint> endpoint = parseEndpoint(gossip.endpoint());
    if (endpoint) admit(gossip.peer(), *endpoint, false);
  }
  settleOwners();
  const std::int64_t arrivalUs =
      std::chrono::duration_cast<std::chrono::microseconds>(now.time_since_epoch()).count();
  // an owner's bodies, and its instances of what it shares when it owns them
  const auto followOwner = [&](const pb::Body& body) {
    if (body.object() < owners_.size() && owners_[body.object()] == from && onBody_)
      onBody_(body.object(), from, state.sent_us(), fromBody(body), arrivalUs);
  };
  for (const pb::Body& body : state.bodies()) followOwner(body);
  for (const pb::Share& share : state.shares()) {
    if (!shares_.count(share.body().object())) {
      followOwner(share.body());
    } else if (onShared_) {
      onShared_(share.body().object(), from, state.sent_us(), fromBody(share.body()), share.in_j(),
                arrivalUs);
    }
  }
}

void PeerSession::onEvent(PeerId from, const DatagramHeader&, const pb::Event& event) {
  switch (event.body_case()) {
    case pb::Event::kJoin:
      onJoin(from, event.join());
      return;
    case pb::Event::kSnapshotRequest: {
      const auto it = snapshots_.find(from);
      const std::uint32_t offset = event.snapshot_request().offset();
      if (it == snapshots_.end() || offset > it->second.bytes.size()) {
        ++counts_.unexpected;
        return;
      }
      pb::Event reply;
      pb::SnapshotChunk& chunk = *reply.mutable_snapshot_chunk();
      chunk.set_offset(offset);
      const std::size_t n = std::min(kChunkBytes, it->second.bytes.size() - offset);
      chunk.set_data(reinterpret_cast<const char*>(it->second.bytes.data() + offset), n);
      sendEvent(sender_, reply);
      return;
    }
    case pb::Event::kWelcome:
      if (started_ || welcome_) {
        ++counts_.unexpected;
        return;
      }
      welcome_ = event.welcome();
      welcomer_ = from;
      return;
    case pb::Event::kSnapshotChunk: {
      const pb::SnapshotChunk& chunk = event.snapshot_chunk();
      if (started_ || !welcome_ || from != welcomer_ || chunk.offset() != joinSnapshot_.size() ||
          joinSnapshot_.size() + chunk.data().size() > welcome_->snapshot_bytes()) {
        ++counts_.unexpected;
        return;
      }
      const auto* data = reinterpret_cast<const std::byte*>(chunk.data().data());
      joinSnapshot_.insert(joinSnapshot_.end(), data, data + chunk.data().size());
      return;
    }
    default:
      ++counts_.malformed;
  }
}

void PeerSession::onJoin(PeerId from, const pb::Join& join) {
  if (!started_ || !snapshotFn_) {
    ++counts_.unexpected;
    return;
  }
  pb::Event reply;
  pb::Welcome& welcome = *reply.mutable_welcome();
  std::vector<std::string> warnings;
  const std::string why = refusal(options_.parameters, join.parameters(), warnings);
  if (!why.empty()) {
    welcome.set_accepted(false);
    welcome.set_refusal(why);
    log_("refused peer " + std::to_string(from) + " at " + text(sender_) + ": " + why);
    sendEvent(sender_, reply);
    return;
  }
  // a joiner repeating its Join before the Welcome came gets the same snapshot
  auto it = snapshots_.find(from);
  if (it == snapshots_.end()) it = snapshots_.emplace(from, Snapshot{snapshotFn_(), Clock::now()}).first;
  welcome.set_accepted(true);
  for (const std::string& w : warnings) {
    welcome.add_warnings(w);
    log_("peer " + std::to_string(from) + " (" + join.name() + ") joins with a different " + w);
  }
  pb::Member& me = *welcome.add_members();
  me.set_peer(self_);
  me.set_endpoint(advertised_);
  for (const auto& [id, m] : members_) {
    if (id == from) continue;
    pb::Member& member = *welcome.add_members();
    member.set_peer(id);
    member.set_endpoint(text(m.endpoint));
  }
  welcome.set_snapshot_bytes(static_cast<std::uint32_t>(it->second.bytes.size()));
  sendEvent(sender_, reply);
}

void PeerSession::send(const asio::ip::udp::endpoint& to, DatagramKind kind,
                       const google::protobuf::Message& payload) {
  const std::size_t bytes = payload.ByteSizeLong();
  if (bytes > kMaxDatagramPayloadBytes) {
    ++counts_.sendFailures;
    return;
  }
  payload.SerializeToArray(payloadBuffer_.data(), static_cast<int>(bytes));
  const std::size_t n = sealer_.seal(kind, nowUs32(), std::span(payloadBuffer_.data(), bytes), outBuffer_);
  asio::error_code ec;
  socket_.send_to(asio::buffer(outBuffer_.data(), n), to, 0, ec);
  if (ec) {
    ++counts_.sendFailures;
    return;
  }
  ++counts_.datagramsOut;
  counts_.bytesOut += n;
}

void PeerSession::sendEvent(const asio::ip::udp::endpoint& to, const pb::Event& event) {
  send(to, DatagramKind::Event, event);
}

std::vector<std::byte> PeerSession::join(const std::string& host, std::uint16_t port,
                                         std::chrono::milliseconds patience) {
  const std::optional<asio::ip::udp::endpoint> contact = parseEndpoint(host + ":" + std::to_string(port));
  if (!contact)
    throw Error("--join: '" + host + ":" + std::to_string(port) + "' is not an IP address and port");
  const Clock::time_point giveUp = Clock::now() + patience;
  pb::Event request;
  pb::Join& j = *request.mutable_join();
  *j.mutable_parameters() = options_.parameters;
  j.set_name(options_.name);
  // padded to the largest datagram: no reply to it is longer
  j.set_padding(std::string(kMaxDatagramPayloadBytes - request.ByteSizeLong(), '\0'));
  while (request.ByteSizeLong() > kMaxDatagramPayloadBytes) j.mutable_padding()->pop_back();
  Clock::time_point lastAsked{};
  std::size_t askedAt = SIZE_MAX;
  while (Clock::now() < giveUp) {
    const bool whole = welcome_ && joinSnapshot_.size() == welcome_->snapshot_bytes();
    if (welcome_ && !welcome_->accepted())
      throw Error("the session refused to let this peer join: " + welcome_->refusal());
    if (whole) break;
    const bool progressed = welcome_ && askedAt != joinSnapshot_.size();
    if (Clock::now() - lastAsked >= kRetry || progressed) {
      if (!welcome_) {
        sendEvent(*contact, request);
      } else {
        pb::Event ask;
        ask.mutable_snapshot_request()->set_offset(static_cast<std::uint32_t>(joinSnapshot_.size()));
        ask.mutable_snapshot_request()->set_padding(std::string(kChunkBytes + 64, '\0'));
        sendEvent(*contact, ask);
        askedAt = joinSnapshot_.size();
      }
      lastAsked = Clock::now();
    }
    io_.restart();
    io_.run_for(std::chrono::milliseconds(5));
  }
  if (!welcome_)
    throw Error("no member answered at " + text(*contact) + " within " + std::to_string(patience.count()) +
                " ms (is the session key the same?)");
  if (joinSnapshot_.size() != welcome_->snapshot_bytes())
    throw Error("the snapshot from " + text(*contact) + " did not come whole within " +
                std::to_string(patience.count()) + " ms");
  for (const std::string& w : welcome_->warnings()) {
    warnings_.push_back(w);
    log_("joined with a different " + w);
  }
  for (const pb::Member& m : welcome_->members()) {
    if (m.peer() == self_) continue;
    // the welcoming peer is where we reached it, whatever address it bound
    const std::optional<asio::ip::udp::endpoint> endpoint =
        m.peer() == welcomer_ ? contact : parseEndpoint(m.endpoint());
    if (endpoint) admit(m.peer(), *endpoint, false);
  }
  io_.restart();
  return std::move(joinSnapshot_);
}

void PeerSession::start(const std::vector<PeerId>& owners, RemoteBodyFn onBody, OwnerFn onOwner,
                        SnapshotFn snapshot) {
  owners_ = owners;
  onBody_ = std::move(onBody);
  onOwner_ = std::move(onOwner);
  snapshotFn_ = std::move(snapshot);
  // until their heartbeats say otherwise, members own what the snapshot says
  for (std::uint32_t o = 0; o < owners_.size(); ++o) {
    if (owners_[o] == self_) mine_.insert(o);
    if (const auto it = members_.find(owners_[o]); it != members_.end()) it->second.owns.insert(o);
  }
  started_ = true;
  settleOwners();
}

void PeerSession::want(std::uint32_t object) {
  if (object < owners_.size() && owners_[object] != self_ && !shares_.count(object)) wants_.insert(object);
}

void PeerSession::share(std::uint32_t object, SharedBodyFn onShared) {
  if (!started_ || object >= owners_.size()) return;
  shares_.insert(object);
  wants_.erase(object);
  onShared_ = std::move(onShared);
  settleOwners();
}

std::vector<SharerView> PeerSession::sharers(std::uint32_t object) const {
  std::vector<SharerView> out;
  for (const auto& [id, m] : members_) {
    const auto instance = m.shares.find(object);
    if (instance != m.shares.end())
      out.push_back({id, m.delay.oneWayMs(), m.divergent.count(object) > 0, instance->second});
  }
  return out;
}

void PeerSession::settleOwners() {
  // a lower-numbered claimant wins, and a sharer wins over any: drop what they claim too
  for (auto it = mine_.begin(); it != mine_.end();) {
    const bool outranked =
        shares_.count(*it) || std::any_of(members_.begin(), members_.end(), [&](const auto& m) {
          return m.second.shares.count(*it) || (m.first < self_ && m.second.owns.count(*it));
        });
    it = outranked ? mine_.erase(it) : std::next(it);
  }
  for (std::uint32_t o = 0; o < owners_.size(); ++o) {
    // a shared object's lowest sharer, else its lowest claimant
    PeerId owner = shares_.count(o) ? self_ : kNoPeer;
    for (const auto& [id, m] : members_) {
      if (m.shares.count(o) && (owner == kNoPeer || id < owner)) owner = id;
    }
    const bool shared = owner != kNoPeer;
    if (!shared && mine_.count(o)) owner = self_;
    for (const auto& [id, m] : members_) {
      if (!shared && m.owns.count(o) && (owner == kNoPeer || id < owner)) owner = id;
    }
    if (owner == owners_[o]) continue;
    owners_[o] = owner;
    if (owner == self_) wants_.erase(o);
    if (onOwner_) onOwner_(o, owner);
  }
}

pb::PeerState PeerSession::heartbeat(const LocalFrame& frame, bool leaving) const {
  pb::PeerState state;
  state.set_sent_us(frame.endedUs);
  state.set_frame(frame.frame);
  state.set_leaving(leaving);
  state.set_name(options_.name);
  state.set_endpoint(advertised_);
  for (const std::uint32_t o : mine_) {
    state.add_owns(o);
    if (o < frame.held.size() && frame.held[o]) state.add_holding(o);
    if (o < frame.bodies.size()) toBody(o, frame.bodies[o], *state.add_bodies());
  }
  for (const std::uint32_t o : shares_) {
    if (o >= frame.bodies.size()) continue;
    pb::Share& share = *state.add_shares();
    toBody(o, frame.bodies[o], *share.mutable_body());
    share.set_in_j(o < frame.sharedInJ.size() ? frame.sharedInJ[o] : 0.0);
    share.set_divergent(o < frame.divergent.size() && frame.divergent[o]);
  }
  for (const std::uint32_t o : wants_) state.add_wants(o);
  const Clock::time_point now = Clock::now();
  for (const auto& [id, m] : members_) {
    if (!m.heardDirectly) continue;  // only the members it hears from itself
    pb::Member& member = *state.add_members();
    member.set_peer(id);
    member.set_endpoint(text(m.endpoint));
    pb::Echo& echo = *state.add_echoes();
    echo.set_peer(id);
    echo.set_their_sent_us(m.theirSentUs);
    echo.set_held_us(static_cast<std::uint32_t>(
        std::chrono::duration_cast<std::chrono::microseconds>(now - m.theirSentAt).count()));
  }
  return state;
}

void PeerSession::tick(const LocalFrame& frame) {
  if (!started_) return;
  const Clock::time_point now = Clock::now();
  std::vector<PeerId> silent;
  for (const auto& [id, m] : members_) {
    if (now - m.heard > options_.timeout) silent.push_back(id);
  }
  for (const PeerId id : silent)
    drop(id, "timed out (nothing heard for " + std::to_string(options_.timeout.count()) + " ms)", false);
  for (auto it = snapshots_.begin(); it != snapshots_.end();) {
    it = secondsBetween(it->second.made, now) > kKeepSnapshotS ? snapshots_.erase(it) : std::next(it);
  }
  // hand over what another wants and nobody here holds; claim what is free and wanted
  for (auto it = mine_.begin(); it != mine_.end();) {
    const std::uint32_t o = *it;
    const bool heldHere = o < frame.held.size() && frame.held[o];
    const bool wanted = std::any_of(members_.begin(), members_.end(),
                                    [&](const auto& m) { return m.second.wants.count(o) > 0; });
    it = wanted && !heldHere ? mine_.erase(it) : std::next(it);
  }
  for (const std::uint32_t o : wants_) {
    if (o < owners_.size() && owners_[o] == kNoPeer) mine_.insert(o);
  }
  settleOwners();
  const pb::PeerState state = heartbeat(frame, false);
  for (auto& [id, m] : members_) {
    send(m.endpoint, DatagramKind::State, state);
    m.bytesOut += kDatagramHeaderBytes + kDatagramTagBytes + state.ByteSizeLong();
  }
  for (auto& [id, g] : gone_) {
    if (g.left || now < g.nextCall || secondsBetween(g.since, now) >= kForgetGoneS) continue;
    send(g.endpoint, DatagramKind::State, state);
    g.nextCall = now + kCallGone;
  }
}

void PeerSession::leave(const LocalFrame& frame) {
  if (!started_) return;
  const pb::PeerState state = heartbeat(frame, true);
  for (int i = 0; i < 3; ++i) {
    for (const auto& [id, m] : members_) send(m.endpoint, DatagramKind::State, state);
  }
}

std::vector<MemberView> PeerSession::members() const {
  std::vector<MemberView> out;
  const Clock::time_point now = Clock::now();
  for (const auto& [id, m] : members_) {
    out.push_back({id, text(m.endpoint), m.name, m.delay.roundTripMs(), m.delay.oneWayMs(),
                   secondsBetween(m.heard, now), m.heardDirectly, m.bytesIn, m.bytesOut});
  }
  return out;
}

}  // namespace voxhap::net

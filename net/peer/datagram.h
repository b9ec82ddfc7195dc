#pragma once
/// The peers' datagram (DESIGN §8): a clear 32-byte header, then the payload sealed with
/// XChaCha20-Poly1305 (libsodium's IETF AEAD) under the session key, the header bound
/// to it as associated data. All integers little-endian.
///
///   offset  bytes  field
///        0      4  magic "VXP" and the format version (1)
///        4      1  kind (DatagramKind)
///        5      3  zero
///        8      8  session id
///       16      4  sender: the peer's id in the session
///       20      8  sequence: per sender, each datagram one higher than the last
///       28      4  send time: the sender's clock, µs, modulo 2³²
///       32    N+16 the sealed payload and its 16-byte tag
///
/// The nonce is the session id, the sender and the sequence (and 4 zero bytes), so no
/// two datagrams under one key share it as long as a sender never repeats a sequence
/// number: a DatagramSealer starts its sequence at a random number below 2⁶², so that a
/// peer restarted with the same id and key does not start over at a used one.
///
/// DatagramOpener drops, cheaply and in this order, what is too short or long, not ours
/// (magic, version, kind, session), from a sender it cannot keep a window for, replayed
/// or too old (before any cryptography), and then what does not authenticate; each
/// reason has its counter. Neither side allocates, locks or throws once built.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "net/peer/replay_window.h"
#include "net/peer/session_key.h"

namespace voxhap::net {

/// What a datagram carries: unreliable latest-wins state, or the reliable channel's
/// session events and acknowledgements.
enum class DatagramKind : std::uint8_t { State = 1, Event = 2 };

inline constexpr std::size_t kDatagramHeaderBytes = 32;
inline constexpr std::size_t kDatagramTagBytes = 16;
/// The largest datagram sent or taken: a payload fits a 1280-byte IPv6 minimum MTU
/// with the IP and UDP headers.
inline constexpr std::size_t kMaxDatagramBytes = 1200;
inline constexpr std::size_t kMaxDatagramPayloadBytes =
    kMaxDatagramBytes - kDatagramHeaderBytes - kDatagramTagBytes;

/// The header's fields, as read from a datagram.
struct DatagramHeader {
  DatagramKind kind = DatagramKind::State;
  std::uint64_t session = 0;
  std::uint32_t sender = 0;
  std::uint64_t sequence = 0;
  std::uint32_t sendTimeUs = 0;  ///< the sender's clock, µs modulo 2³²
};

/// Seals one sender's datagrams.
class DatagramSealer {
public:
  /// `sender`'s datagrams in `session`; the first sequence number is random (see above).
  DatagramSealer(const SessionKey& key, std::uint64_t session, std::uint32_t sender);
  /// The same with a chosen first sequence number (for tests).
  DatagramSealer(const SessionKey& key, std::uint64_t session, std::uint32_t sender,
                 std::uint64_t firstSequence);

  /// Writes one datagram of `kind` carrying `payload` into `out`; its size in bytes, or 0
  /// when the payload is over kMaxDatagramPayloadBytes or `out` too small (nothing sent,
  /// no sequence number used).
  std::size_t seal(DatagramKind kind, std::uint32_t sendTimeUs, std::span<const std::uint8_t> payload,
                   std::span<std::uint8_t> out) noexcept;

  /// The sequence number the next datagram takes.
  std::uint64_t nextSequence() const { return nextSequence_; }

private:
  std::array<std::uint8_t, SessionKey::kBytes> key_;
  std::uint64_t session_;
  std::uint32_t sender_;
  std::uint64_t nextSequence_;
};

/// Why DatagramOpener took or dropped a datagram.
enum class OpenResult : std::uint8_t {
  Opened,         ///< authentic and new: the payload is in the output
  BadSize,        ///< shorter than a header and tag, or longer than kMaxDatagramBytes
  NotOurs,        ///< wrong magic, version, kind, session, or non-zero reserved bytes
  NoWindow,       ///< a sender beyond the table of senders this opener keeps
  Replayed,       ///< a sequence number already taken from that sender
  TooOld,         ///< below that sender's replay window
  Forged,         ///< does not authenticate under the session key
  PayloadTooBig,  ///< the caller's buffer is smaller than the payload would be (nothing checked)
};
inline constexpr std::size_t kOpenResults = 8;

/// Opens the datagrams of a session from up to kMaxSenders senders, each with its own
/// replay window.
class DatagramOpener {
public:
  static constexpr std::size_t kMaxSenders = 64;

  DatagramOpener(const SessionKey& key, std::uint64_t session);

  /// Checks `datagram` and, when it is authentic and new, writes its payload into
  /// `payload`, its header into `header` and its payload's size into `payloadBytes`.
  OpenResult open(std::span<const std::uint8_t> datagram, std::span<std::uint8_t> payload,
                  DatagramHeader& header, std::size_t& payloadBytes) noexcept;

  /// Forgets `sender`'s window (it left, or joins again with a new sequence).
  void forget(std::uint32_t sender) noexcept;

  /// How many datagrams ended with each result, indexed by OpenResult.
  const std::array<std::uint64_t, kOpenResults>& counts() const { return counts_; }
  std::uint64_t count(OpenResult r) const { return counts_[static_cast<std::size_t>(r)]; }

private:
  struct SenderWindow {
    bool used = false;
    std::uint32_t sender = 0;
    ReplayWindow window;
  };
  OpenResult tally(OpenResult r) noexcept {
    ++counts_[static_cast<std::size_t>(r)];
    return r;
  }
  SenderWindow* find(std::uint32_t sender) noexcept;

  std::array<std::uint8_t, SessionKey::kBytes> key_;
  std::uint64_t session_;
  std::array<SenderWindow, kMaxSenders> senders_{};
  std::array<std::uint64_t, kOpenResults> counts_{};
};

}  // namespace voxhap::net

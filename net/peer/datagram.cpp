#include "net/peer/datagram.h"

#include <cstring>

#include <sodium.h>

namespace voxhap::net {
namespace {

static_assert(crypto_aead_xchacha20poly1305_ietf_KEYBYTES == SessionKey::kBytes);
static_assert(crypto_aead_xchacha20poly1305_ietf_ABYTES == kDatagramTagBytes);
static_assert(crypto_aead_xchacha20poly1305_ietf_NPUBBYTES == 24);

constexpr std::array<std::uint8_t, 4> kMagic = {'V', 'X', 'P', 1};
/// Sequence numbers start below this, so that a sender never wraps.
constexpr std::uint64_t kFirstSequenceBound = std::uint64_t{1} << 62;

template <typename T>
void putLe(std::uint8_t* out, T value) {
  for (std::size_t i = 0; i < sizeof(T); ++i) out[i] = static_cast<std::uint8_t>(value >> (8 * i));
}

template <typename T>
T getLe(const std::uint8_t* in) {
  T value = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) value = static_cast<T>(value | (T(in[i]) << (8 * i)));
  return value;
}

void writeHeader(const DatagramHeader& h, std::uint8_t* out) {
  std::memcpy(out, kMagic.data(), kMagic.size());
  out[4] = static_cast<std::uint8_t>(h.kind);
  out[5] = out[6] = out[7] = 0;
  putLe(out + 8, h.session);
  putLe(out + 16, h.sender);
  putLe(out + 20, h.sequence);
  putLe(out + 28, h.sendTimeUs);
}

/// The header's fields, or false when the magic, kind or reserved bytes are not ours.
bool readHeader(const std::uint8_t* in, DatagramHeader& h) {
  if (std::memcmp(in, kMagic.data(), kMagic.size()) != 0 || in[5] != 0 || in[6] != 0 || in[7] != 0)
    return false;
  if (in[4] != static_cast<std::uint8_t>(DatagramKind::State) &&
      in[4] != static_cast<std::uint8_t>(DatagramKind::Event))
    return false;
  h.kind = static_cast<DatagramKind>(in[4]);
  h.session = getLe<std::uint64_t>(in + 8);
  h.sender = getLe<std::uint32_t>(in + 16);
  h.sequence = getLe<std::uint64_t>(in + 20);
  h.sendTimeUs = getLe<std::uint32_t>(in + 28);
  return true;
}

using Nonce = std::array<std::uint8_t, crypto_aead_xchacha20poly1305_ietf_NPUBBYTES>;

Nonce nonceOf(const DatagramHeader& h) {
  Nonce nonce{};
  putLe(nonce.data(), h.session);
  putLe(nonce.data() + 8, h.sender);
  putLe(nonce.data() + 12, h.sequence);
  return nonce;
}

std::uint64_t randomFirstSequence() {
  initSodium();
  std::uint64_t first = 0;
  randombytes_buf(&first, sizeof first);
  return first % kFirstSequenceBound;
}

}  // namespace

DatagramSealer::DatagramSealer(const SessionKey& key, std::uint64_t session, std::uint32_t sender)
    : DatagramSealer(key, session, sender, randomFirstSequence()) {}

DatagramSealer::DatagramSealer(const SessionKey& key, std::uint64_t session, std::uint32_t sender,
                               std::uint64_t firstSequence)
    : key_(key.bytes()), session_(session), sender_(sender), nextSequence_(firstSequence) {
  initSodium();
}

std::size_t DatagramSealer::seal(DatagramKind kind, std::uint32_t sendTimeUs,
                                 std::span<const std::uint8_t> payload,
                                 std::span<std::uint8_t> out) noexcept {
  const std::size_t bytes = kDatagramHeaderBytes + payload.size() + kDatagramTagBytes;
  if (payload.size() > kMaxDatagramPayloadBytes || out.size() < bytes) return 0;
  const DatagramHeader header{kind, session_, sender_, nextSequence_, sendTimeUs};
  writeHeader(header, out.data());
  const Nonce nonce = nonceOf(header);
  unsigned long long sealedBytes = 0;
  crypto_aead_xchacha20poly1305_ietf_encrypt(out.data() + kDatagramHeaderBytes, &sealedBytes, payload.data(),
                                             payload.size(), out.data(), kDatagramHeaderBytes, nullptr,
                                             nonce.data(), key_.data());
  ++nextSequence_;
  return kDatagramHeaderBytes + static_cast<std::size_t>(sealedBytes);
}

DatagramOpener::DatagramOpener(const SessionKey& key, std::uint64_t session)
    : key_(key.bytes()), session_(session) {
  initSodium();
}

DatagramOpener::SenderWindow* DatagramOpener::find(std::uint32_t sender) noexcept {
  for (SenderWindow& s : senders_) {
    if (s.used && s.sender == sender) return &s;
  }
  return nullptr;
}

OpenResult DatagramOpener::open(std::span<const std::uint8_t> datagram, std::span<std::uint8_t> payload,
                                DatagramHeader& header, std::size_t& payloadBytes) noexcept {
  if (datagram.size() < kDatagramHeaderBytes + kDatagramTagBytes || datagram.size() > kMaxDatagramBytes)
    return tally(OpenResult::BadSize);
  DatagramHeader h;
  if (!readHeader(datagram.data(), h) || h.session != session_) return tally(OpenResult::NotOurs);
  const std::size_t bytes = datagram.size() - kDatagramHeaderBytes - kDatagramTagBytes;
  if (payload.size() < bytes) return tally(OpenResult::PayloadTooBig);

  // the window is looked at before the cryptography, and only moved after it
  SenderWindow* known = find(h.sender);
  SenderWindow* slot = known;
  if (!slot) {
    for (SenderWindow& s : senders_) {
      if (!s.used) {
        slot = &s;
        break;
      }
    }
    if (!slot) return tally(OpenResult::NoWindow);
  }
  if (known) {
    switch (known->window.check(h.sequence)) {
      case ReplayWindow::Verdict::Replayed:
        return tally(OpenResult::Replayed);
      case ReplayWindow::Verdict::TooOld:
        return tally(OpenResult::TooOld);
      case ReplayWindow::Verdict::New:
        break;
    }
  }

  const Nonce nonce = nonceOf(h);
  unsigned long long opened = 0;
  if (crypto_aead_xchacha20poly1305_ietf_decrypt(payload.data(), &opened, nullptr,
                                                 datagram.data() + kDatagramHeaderBytes,
                                                 datagram.size() - kDatagramHeaderBytes, datagram.data(),
                                                 kDatagramHeaderBytes, nonce.data(), key_.data()) != 0) {
    return tally(OpenResult::Forged);
  }
  if (!known) *slot = SenderWindow{true, h.sender, ReplayWindow{}};
  slot->window.accept(h.sequence);
  header = h;
  payloadBytes = static_cast<std::size_t>(opened);
  return tally(OpenResult::Opened);
}

void DatagramOpener::forget(std::uint32_t sender) noexcept {
  if (SenderWindow* s = find(sender)) *s = SenderWindow{};
}

}  // namespace voxhap::net

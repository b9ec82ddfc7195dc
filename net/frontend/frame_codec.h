#pragma once
/// Length-prefixed framing of the front-end protocol (docs/protocol.md): every message
/// on the TCP stream is a 4-byte unsigned little-endian length N followed by N bytes of
/// one serialized protobuf message. The decoder checks each length against a cap before
/// it buffers the frame, so a peer cannot make it allocate more than the cap.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace voxhap::net {

/// The protocol version this build speaks (Hello.protocol_version).
inline constexpr std::uint32_t kProtocolVersion = 1;
/// Bytes of the length prefix.
inline constexpr std::size_t kFrameHeaderBytes = 4;
/// The largest frame payload either side accepts by default, bytes.
inline constexpr std::uint32_t kMaxFrameBytes = 16u << 20;

/// Appends `payload` to `out` as one frame. `payload` must not exceed kMaxFrameBytes.
void appendFrame(std::string& out, std::string_view payload);

/// Splits a received byte stream into frame payloads, whatever the chunks it arrives in.
class FrameDecoder {
public:
  /// What next() found.
  enum class Result {
    Frame,     ///< a whole frame: its payload is in the argument
    NeedMore,  ///< the buffered bytes end inside a frame (or there are none)
    Oversized  ///< the next frame announces more than the cap: the stream is unusable
  };

  explicit FrameDecoder(std::uint32_t maxFrameBytes = kMaxFrameBytes) : maxFrameBytes_(maxFrameBytes) {}

  /// Buffers received bytes.
  void feed(std::string_view bytes);
  /// Takes the next whole frame out of the buffer into `payload`.
  Result next(std::string& payload);
  /// Bytes buffered and not yet returned as frames.
  std::size_t buffered() const { return buffer_.size() - consumed_; }
  /// The length the next frame announces (valid after next() returned Oversized).
  std::uint32_t announcedBytes() const { return announced_; }

private:
  std::uint32_t maxFrameBytes_;
  std::string buffer_;
  std::size_t consumed_ = 0;  ///< bytes of buffer_ already returned
  std::uint32_t announced_ = 0;
};

}  // namespace voxhap::net

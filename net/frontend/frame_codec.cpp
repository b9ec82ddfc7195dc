#include "net/frontend/frame_codec.h"

#include <cassert>

namespace voxhap::net {

void appendFrame(std::string& out, std::string_view payload) {
  assert(payload.size() <= kMaxFrameBytes);
  const auto n = static_cast<std::uint32_t>(payload.size());
  for (std::size_t i = 0; i < kFrameHeaderBytes; ++i)
    out.push_back(static_cast<char>((n >> (8 * i)) & 0xffu));
  out.append(payload);
}

void FrameDecoder::feed(std::string_view bytes) {
  // drop what was returned before growing, so the buffer holds at most one frame and a chunk
  if (consumed_ > 0 && consumed_ >= buffer_.size() / 2) {
    buffer_.erase(0, consumed_);
    consumed_ = 0;
  }
  buffer_.append(bytes);
}

FrameDecoder::Result FrameDecoder::next(std::string& payload) {
  if (buffered() < kFrameHeaderBytes) return Result::NeedMore;
  std::uint32_t n = 0;
  for (std::size_t i = 0; i < kFrameHeaderBytes; ++i)
    n |= static_cast<std::uint32_t>(static_cast<unsigned char>(buffer_[consumed_ + i])) << (8 * i);
  announced_ = n;
  if (n > maxFrameBytes_) return Result::Oversized;
  if (buffered() - kFrameHeaderBytes < n) return Result::NeedMore;
  payload.assign(buffer_, consumed_ + kFrameHeaderBytes, n);
  consumed_ += kFrameHeaderBytes + n;
  return Result::Frame;
}

}  // namespace voxhap::net

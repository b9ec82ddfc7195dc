#include "haptics/voxel/cache_file.h"

#include <array>
#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstring>
#include <vector>

#include <unistd.h>

#include "haptics/core/error.h"

namespace voxhap {
namespace {

constexpr std::array<char, 8> kMagic = {'V', 'O', 'X', 'H', 'A', 'P', 'C', '\n'};

/// The fixed-size header, as laid out on disk (no padding: 8 + 4 + 4 + 16 + 8 bytes).
struct Header {
  std::array<char, 8> magic;
  std::uint32_t formatVersion;
  std::uint32_t kind;
  std::uint64_t keyLo;
  std::uint64_t keyHi;
  std::uint64_t payloadBytes;
};
static_assert(sizeof(Header) == 40);

constexpr std::uint64_t kTrailerBytes = 16;

}  // namespace

CacheFileWriter::CacheFileWriter(std::filesystem::path path, CacheKind kind, const Digest128& key)
    : path_(std::move(path)) {
  static std::atomic<unsigned> counter{0};
  tempPath_ = path_;
  tempPath_ += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  out_.open(tempPath_, std::ios::binary | std::ios::trunc);
  if (!out_) throw Error(tempPath_.string() + ": cannot create a cache file: " + std::strerror(errno));
  const Header header{kMagic, kCacheFormatVersion, static_cast<std::uint32_t>(kind), key.lo, key.hi, 0};
  out_.write(reinterpret_cast<const char*>(&header), sizeof header);
}

CacheFileWriter::~CacheFileWriter() {
  if (committed_) return;
  out_.close();
  std::error_code ignored;
  std::filesystem::remove(tempPath_, ignored);
}

void CacheFileWriter::write(const void* data, std::size_t bytes) {
  checksum_.update(data, bytes);
  out_.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
  payloadBytes_ += bytes;
}

void CacheFileWriter::commit() {
  const Digest128 sum = checksum_.digest();
  out_.write(reinterpret_cast<const char*>(&sum.lo), sizeof sum.lo);
  out_.write(reinterpret_cast<const char*>(&sum.hi), sizeof sum.hi);
  out_.seekp(static_cast<std::streamoff>(offsetof(Header, payloadBytes)));
  out_.write(reinterpret_cast<const char*>(&payloadBytes_), sizeof payloadBytes_);
  out_.close();
  if (!out_) throw Error(tempPath_.string() + ": cannot write the cache file (disk full?)");
  std::error_code ec;
  std::filesystem::rename(tempPath_, path_, ec);
  if (ec) throw Error(path_.string() + ": cannot move the cache file into place: " + ec.message());
  committed_ = true;
}

CacheFileReader::CacheFileReader(const std::filesystem::path& path, CacheKind kind, const Digest128& key) {
  const std::uint64_t fileBytes = std::filesystem::file_size(path);
  in_.open(path, std::ios::binary);
  if (!in_) throw CacheFileError(std::string("cannot be opened: ") + std::strerror(errno));
  Header header;
  if (fileBytes < sizeof header + kTrailerBytes ||
      !in_.read(reinterpret_cast<char*>(&header), sizeof header)) {
    throw CacheFileError("is truncated (" + std::to_string(fileBytes) + " bytes)");
  }
  if (header.magic != kMagic) throw CacheFileError("is not a Voxhap cache file (bad magic)");
  if (header.formatVersion != kCacheFormatVersion) {
    throw CacheFileError("has format version " + std::to_string(header.formatVersion) + ", expected " +
                         std::to_string(kCacheFormatVersion));
  }
  if (header.kind != static_cast<std::uint32_t>(kind) || header.keyLo != key.lo || header.keyHi != key.hi) {
    throw CacheFileError("holds other data (key mismatch)");
  }
  const std::uint64_t expected = sizeof header + header.payloadBytes + kTrailerBytes;
  if (header.payloadBytes > fileBytes || expected != fileBytes) {
    throw CacheFileError((fileBytes < expected ? "is truncated (" : "is corrupt (") +
                         std::to_string(fileBytes) + " bytes, the header says " + std::to_string(expected) +
                         ")");
  }
  remaining_ = header.payloadBytes;
  payloadBytes_ = header.payloadBytes;
  payloadStart_ = sizeof header;
}

void CacheFileReader::skip(std::uint64_t bytes) {
  std::vector<char> buffer(std::min<std::uint64_t>(bytes, std::uint64_t{16} << 20));
  while (bytes > 0) {
    const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(bytes, buffer.size()));
    read(buffer.data(), n);
    bytes -= n;
  }
}

void CacheFileReader::read(void* data, std::size_t bytes) {
  if (bytes > remaining_) throw CacheFileError("is corrupt (a field runs past the end)");
  if (!in_.read(static_cast<char*>(data), static_cast<std::streamsize>(bytes))) {
    throw CacheFileError("is truncated (read failed)");
  }
  checksum_.update(data, bytes);
  remaining_ -= bytes;
}

void CacheFileReader::finish() {
  if (remaining_ != 0)
    throw CacheFileError("is corrupt (" + std::to_string(remaining_) + " bytes left unread)");
  Digest128 stored;
  if (!in_.read(reinterpret_cast<char*>(&stored.lo), sizeof stored.lo) ||
      !in_.read(reinterpret_cast<char*>(&stored.hi), sizeof stored.hi)) {
    throw CacheFileError("is truncated (no checksum)");
  }
  if (!(stored == checksum_.digest())) throw CacheFileError("is corrupt (checksum mismatch)");
}

}  // namespace voxhap

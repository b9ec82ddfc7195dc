#pragma once
/// Versioned, checksummed cache files for voxel data (DESIGN §4.6).
///
/// Layout, little-endian:
///   header   8 bytes magic "VOXHAPC\n" | u32 format version | u32 kind |
///            16 bytes key (what the content was made from) | u64 payload bytes
///   payload  whatever the writer put, arrays as a u64 element count then the elements
///   trailer  16 bytes: ContentHash digest of the payload
///
/// The writer streams into a temporary file in the destination folder and renames it
/// over the final name on commit (atomic on POSIX), so a reader sees a whole file or
/// none. The reader checks the header and the file's length before reading anything,
/// never allocates more than the file holds, and checks the checksum at the end; any
/// problem is a CacheFileError whose message completes "cache file PATH …".

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "haptics/core/content_hash.h"

namespace voxhap {

/// Bump whenever what a cache file holds, or how it is made, changes.
/// 2: keys and checksums are XXH3-128 (ContentHash).
/// 3: voxmaps end with their surface planes (surface_planes.h), none when not asked for.
/// 4: the surface planes sparse: a bit per voxel of the mixed chunks, then the planes of
///    the voxels whose bit is set (sparse_surface_planes.h).
/// 5: the planes followed by their convex sides, a byte each (PlaneWithSides).
inline constexpr std::uint32_t kCacheFormatVersion = 5;

/// What a cache file holds.
enum class CacheKind : std::uint32_t { Voxmap = 1, Pointshell = 2 };

/// A cache file that cannot be used; what() reads as the end of "cache file X …",
/// e.g. "is corrupt (checksum mismatch)".
class CacheFileError : public std::runtime_error {
public:
  explicit CacheFileError(const std::string& problem) : std::runtime_error(problem) {}
};

class CacheFileWriter {
public:
  /// Starts writing the cache file `path` (its folder must exist). Throws voxhap::Error
  /// naming the file when the temporary file cannot be created.
  CacheFileWriter(std::filesystem::path path, CacheKind kind, const Digest128& key);
  /// Removes the temporary file unless commit() succeeded.
  ~CacheFileWriter();
  CacheFileWriter(const CacheFileWriter&) = delete;
  CacheFileWriter& operator=(const CacheFileWriter&) = delete;

  void write(const void* data, std::size_t bytes);
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    write(&value, sizeof value);
  }
  template <typename T>
  void putArray(std::span<const T> values) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(static_cast<std::uint64_t>(values.size()));
    write(values.data(), values.size_bytes());
  }

  /// Writes the trailer and renames the file into place. Throws voxhap::Error naming the
  /// file on any I/O failure (disk full, folder not writable).
  void commit();

private:
  std::filesystem::path path_;
  std::filesystem::path tempPath_;
  std::ofstream out_;
  ContentHash checksum_;
  std::uint64_t payloadBytes_ = 0;
  bool committed_ = false;
};

class CacheFileReader {
public:
  /// Opens `path` and checks magic, format version, kind, key and length. Throws
  /// CacheFileError on any mismatch, std::filesystem errors aside (a missing file is
  /// the caller's to check).
  CacheFileReader(const std::filesystem::path& path, CacheKind kind, const Digest128& key);

  /// Reads `bytes` payload bytes; throws CacheFileError past the payload's end.
  void read(void* data, std::size_t bytes);
  template <typename T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    read(&value, sizeof value);
    return value;
  }
  /// Reads an array written by putArray; its size is checked against what is left of
  /// the payload before anything is allocated. The vector gets room for `spare` more
  /// elements, for a caller that will append them.
  template <typename T>
  std::vector<T> getArray(std::size_t spare = 0) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto count = get<std::uint64_t>();
    if (count > remaining_ / sizeof(T)) throw CacheFileError("is corrupt (an array runs past the end)");
    std::vector<T> values;
    values.reserve(static_cast<std::size_t>(count) + spare);
    values.resize(static_cast<std::size_t>(count));
    read(values.data(), values.size() * sizeof(T));
    return values;
  }

  /// Reads past `bytes` payload bytes, checksumming them without keeping them (a paged
  /// voxmap's words, read again later by offset).
  void skip(std::uint64_t bytes);
  /// Where the next payload byte lies in the file, bytes from its start.
  std::uint64_t fileOffset() const { return payloadStart_ + (payloadBytes_ - remaining_); }

  /// Checks that the whole payload was read and that its checksum matches.
  void finish();

private:
  std::ifstream in_;
  ContentHash checksum_;
  std::uint64_t remaining_ = 0;
  std::uint64_t payloadBytes_ = 0;
  std::uint64_t payloadStart_ = 0;
};

}  // namespace voxhap

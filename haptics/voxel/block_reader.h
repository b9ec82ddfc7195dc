#pragma once
/// Where a pager (voxel_pager.h) reads blocks of voxel words from: the voxmap's cache
/// file, or a stand-in that a test gives (one that fails, or is slow, on purpose).

#include <cstdint>
#include <filesystem>
#include <span>

namespace voxhap {

/// Reads blocks of a paged voxmap's words; called by the pager thread only.
class BlockReader {
public:
  virtual ~BlockReader() = default;
  /// Reads block `block` (the file's index of a mixed chunk's words) whole into `into`
  /// (one block, Voxmap::PagedArrays::blockBytes); false when it could not (an I/O error,
  /// a file too short), with `into` left in any state.
  virtual bool read(std::uint32_t block, std::span<std::uint8_t> into) noexcept = 0;
};

/// Blocks of a cache file: block b lies at `wordsOffset` + b · its size, read with pread
/// (retried after EINTR and after a short read, until the block is whole, the file ends
/// or an error occurs).
class FileBlockReader final : public BlockReader {
public:
  /// Opens `file` read-only; throws voxhap::Error naming it when it cannot.
  FileBlockReader(const std::filesystem::path& file, std::uint64_t wordsOffset);
  /// Closes the file.
  ~FileBlockReader() override;
  FileBlockReader(const FileBlockReader&) = delete;
  FileBlockReader& operator=(const FileBlockReader&) = delete;

  /// Reads block `block` at wordsOffset + block · into.size(); false on an error or a file
  /// that ends inside the block.
  bool read(std::uint32_t block, std::span<std::uint8_t> into) noexcept override;

private:
  int fd_ = -1;
  std::uint64_t wordsOffset_;
};

}  // namespace voxhap

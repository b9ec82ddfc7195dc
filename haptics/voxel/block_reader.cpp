#include "haptics/voxel/block_reader.h"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <unistd.h>

#include "haptics/core/error.h"

namespace voxhap {

FileBlockReader::FileBlockReader(const std::filesystem::path& file, std::uint64_t wordsOffset)
    : wordsOffset_(wordsOffset) {
  fd_ = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw Error(file.string() + ": cannot open for paging: " + std::strerror(errno));
}

FileBlockReader::~FileBlockReader() {
  if (fd_ >= 0) ::close(fd_);
}

bool FileBlockReader::read(std::uint32_t block, std::span<std::uint8_t> into) noexcept {
  const std::uint64_t at = wordsOffset_ + std::uint64_t{block} * into.size();
  std::size_t done = 0;
  while (done < into.size()) {
    const ssize_t n = ::pread(fd_, into.data() + done, into.size() - done, static_cast<off_t>(at + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;  // an error, or the file ends inside the block
    done += static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace voxhap

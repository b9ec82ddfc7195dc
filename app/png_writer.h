#pragma once
/// Writes images as PNG files (libpng), for pictures such as voxel slices.

#include <cstdint>
#include <filesystem>
#include <vector>

namespace voxhap::cli {

/// An 8-bit RGB image: rows top to bottom, 3 bytes per pixel.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  ///< width × height × 3 bytes

  RgbImage() = default;
  /// A width × height image filled with one colour.
  RgbImage(int widthPx, int heightPx, std::uint8_t r, std::uint8_t g, std::uint8_t b);
  void set(int x, int y, const std::uint8_t (&colour)[3]);
};

/// Writes `image` to `file` as an 8-bit RGB PNG, through a temporary file renamed into
/// place, so that no partial file is ever left. Throws voxhap::Error naming the file.
void writePng(const std::filesystem::path& file, const RgbImage& image);

}  // namespace voxhap::cli

#pragma once
/// 8-bit RGB images and their PNG files (libpng): screenshots, voxel-slice pictures.

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace voxhap::render {

/// An 8-bit RGB image: rows top to bottom, 3 bytes per pixel.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  ///< width × height × 3 bytes

  RgbImage() = default;
  /// A width × height image filled with one colour.
  RgbImage(int widthPx, int heightPx, std::uint8_t r, std::uint8_t g, std::uint8_t b);
  void set(int x, int y, const std::uint8_t (&colour)[3]);
  /// The pixel at column x, row y (0 = top); both must be inside the image.
  std::array<std::uint8_t, 3> at(int x, int y) const;
};

/// Writes `image` to `file` as an 8-bit RGB PNG, through a temporary file renamed into
/// place, so that no partial file is ever left. Throws voxhap::Error naming the file.
void writePng(const std::filesystem::path& file, const RgbImage& image);

}  // namespace voxhap::render

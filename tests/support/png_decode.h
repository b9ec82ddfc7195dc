#pragma once
/// PNG files read back by tests (libpng), to check pictures the program wrote.

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace voxhap::test {

/// A PNG decoded to 8-bit RGB, rows top to bottom; width 0 when libpng cannot read it.
struct DecodedPng {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::uint8_t> rgb;
  std::array<int, 3> at(std::uint32_t x, std::uint32_t y) const {
    const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

DecodedPng decodePng(const std::filesystem::path& file);

}  // namespace voxhap::test

#include "render/png_image.h"

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string>

#include <png.h>
#include <unistd.h>

#include "haptics/core/error.h"

namespace voxhap::render {
namespace {

/// Writes the PNG stream to an open file; returns libpng's error message, or "" on success.
/// Holds no C++ object across setjmp, so libpng's longjmp on error skips no destructor.
const char* writePngStream(std::FILE* out, const RgbImage& image, std::vector<png_bytep>& rows) {
  static thread_local char message[256];
  message[0] = '\0';
  png_structp png = png_create_write_struct(
      PNG_LIBPNG_VER_STRING, nullptr,
      [](png_structp p, png_const_charp m) {
        std::snprintf(message, sizeof message, "%s", m);
        png_longjmp(p, 1);
      },
      [](png_structp, png_const_charp) {});
  if (!png) return "cannot start libpng";
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return message[0] ? message : "libpng failed";
  }
  png_init_io(png, out);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return "";
}

}  // namespace

RgbImage::RgbImage(int widthPx, int heightPx, std::uint8_t r, std::uint8_t g, std::uint8_t b)
    : width(widthPx), height(heightPx) {
  rgb.resize(static_cast<std::size_t>(widthPx) * static_cast<std::size_t>(heightPx) * 3);
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    rgb[i] = r;
    rgb[i + 1] = g;
    rgb[i + 2] = b;
  }
}

void RgbImage::set(int x, int y, const std::uint8_t (&colour)[3]) {
  const std::size_t at =
      (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
  std::memcpy(&rgb[at], colour, 3);
}

std::array<std::uint8_t, 3> RgbImage::at(int x, int y) const {
  const std::size_t i =
      (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
  return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

void writePng(const std::filesystem::path& file, const RgbImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() !=
          static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3) {
    throw Error(file.string() + ": no image to write");
  }
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
  for (std::size_t y = 0; y < rows.size(); ++y) {
    rows[y] = const_cast<png_bytep>(&image.rgb[y * static_cast<std::size_t>(image.width) * 3]);
  }
  std::filesystem::path temp = file;
  temp += ".tmp-" + std::to_string(::getpid());
  std::FILE* out = std::fopen(temp.c_str(), "wb");
  if (!out) throw Error(file.string() + ": cannot write: " + std::strerror(errno));
  const std::string problem = writePngStream(out, image, rows);
  const bool closed = std::fclose(out) == 0;
  std::error_code ec;
  if (!problem.empty() || !closed) {
    std::filesystem::remove(temp, ec);
    throw Error(file.string() + ": cannot write the PNG: " + (problem.empty() ? "disk full?" : problem));
  }
  std::filesystem::rename(temp, file, ec);
  if (ec) {
    std::filesystem::remove(temp, ec);
    throw Error(file.string() + ": cannot write: " + ec.message());
  }
}

}  // namespace voxhap::render

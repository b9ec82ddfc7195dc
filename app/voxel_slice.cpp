#include "app/voxel_slice.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "app/cli/option_values.h"

namespace voxhap::cli {
namespace {

/// Largest panel edge the pixels-per-voxel scale aims at, px.
constexpr int kTargetPanelPx = 600;
constexpr int kGapPx = 8;

using Colour = std::uint8_t[3];
constexpr Colour kFar = {28, 28, 32};
constexpr Colour kInterior = {45, 80, 170};
constexpr Colour kFeature = {255, 255, 255};
constexpr Colour kGap = {128, 128, 128};
// free space: from warm and bright next to the feature to cool and dark at the range
constexpr Colour kNear = {250, 205, 40};
constexpr Colour kFarthest = {30, 110, 70};

/// The two axes a slice across `axis` shows, right then up.
std::pair<int, int> planeAxes(int axis) {
  if (axis == 0) return {1, 2};
  return axis == 1 ? std::pair{0, 2} : std::pair{0, 1};
}

void colourOf(std::uint8_t value, int range, std::uint8_t (&out)[3]) {
  const std::uint8_t* c = value == kValueFar ? kFar : value == kValueInterior ? kInterior : kFeature;
  if (value > kValueFeature) {
    const double t = range > 1 ? std::min(1.0, double(value - kValueFeature - 1) / double(range - 1)) : 0.0;
    for (int k = 0; k < 3; ++k)
      out[k] = static_cast<std::uint8_t>(std::lround(kNear[k] + t * (kFarthest[k] - kNear[k])));
    return;
  }
  std::copy(c, c + 3, out);
}

}  // namespace

SliceSpec parseSlice(const std::string& text) {
  const std::size_t equals = text.find('=');
  const std::string axis = text.substr(0, equals);
  if (equals == std::string::npos || (axis != "x" && axis != "y" && axis != "z")) {
    throw UsageError("--slice wants AXIS=COORDINATE such as z=0.012 or x=-3mm (axis x, y or z), not '" +
                     text + "'");
  }
  return {axis[0] - 'x', parseLengthM(text.substr(equals + 1), "slice", LengthSign::Any)};
}

SliceLayout sliceLayout(const Voxmap& voxmap, const SliceSpec& slice) {
  const VoxelGrid& grid = voxmap.grid();
  const glm::ivec3 dims = grid.dimsVoxels();
  const double fromM = grid.originLocal[slice.axis];
  const double toM = fromM + dims[slice.axis] * grid.voxelSizeM;
  const double layer = std::floor((slice.coordinateM - fromM) / grid.voxelSizeM);
  if (!(layer >= 0.0 && layer < dims[slice.axis])) {
    std::ostringstream s;
    s << "--slice "
      << "xyz"[slice.axis] << "=" << slice.coordinateM << " misses the voxel grid, which spans " << fromM
      << " … " << toM << " m along "
      << "xyz"[slice.axis];
    throw UsageError(s.str());
  }
  const auto [right, up] = planeAxes(slice.axis);
  SliceLayout layout;
  layout.layer = static_cast<int>(layer);
  layout.widthVoxels = dims[right];
  layout.heightVoxels = dims[up];
  layout.pixelsPerVoxel = std::max(1, kTargetPanelPx / std::max(dims[right], dims[up]));
  layout.gapPx = kGapPx;
  return layout;
}

render::RgbImage drawSlice(const Voxmap& voxmap, const SliceSpec& slice, const SliceLayout& layout) {
  const int px = layout.pixelsPerVoxel;
  const int panelW = layout.widthVoxels * px;
  const int panelH = layout.heightVoxels * px;
  render::RgbImage image(kFieldCount * panelW + (kFieldCount - 1) * layout.gapPx, panelH, kGap[0], kGap[1],
                         kGap[2]);
  const auto [right, up] = planeAxes(slice.axis);
  const VoxelEncoding& encoding = voxmap.encoding();
  std::uint8_t colour[3];
  glm::ivec3 v;
  v[slice.axis] = layout.layer;
  for (int j = 0; j < layout.heightVoxels; ++j) {
    v[up] = j;
    for (int i = 0; i < layout.widthVoxels; ++i) {
      v[right] = i;
      const VoxelWord word = voxmap.word(v);
      for (int f = 0; f < kFieldCount; ++f) {
        colourOf(encoding.value(word, static_cast<Field>(f)), encoding.rangeVoxels, colour);
        const int x0 = f * (panelW + layout.gapPx) + i * px;
        const int y0 = (layout.heightVoxels - 1 - j) * px;  // up is up
        for (int dy = 0; dy < px; ++dy) {
          for (int dx = 0; dx < px; ++dx) image.set(x0 + dx, y0 + dy, colour);
        }
      }
    }
  }
  return image;
}

}  // namespace voxhap::cli

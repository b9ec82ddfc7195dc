#pragma once
/// Pictures of a voxmap's distance fields, like the paper's Figures 2 and 5: one plane
/// of voxels, cut across an axis, drawn once per field (surface, edge, vertex) side by
/// side, with one colour for far, one for interior, one for the field's feature voxels
/// and a ramp for free space at 1 … range voxels.

#include <string>

#include "haptics/voxel/voxmap.h"
#include "render/png_image.h"

namespace voxhap::cli {

/// Where to cut: a plane normal to `axis` (0 x, 1 y, 2 z) at `coordinateM` (object frame, m).
struct SliceSpec {
  int axis = 2;
  double coordinateM = 0.0;
};

/// Parses "x=0.012", "y=-3mm", "z=12 mm" (lengths as parseLengthM). Throws UsageError.
SliceSpec parseSlice(const std::string& text);

/// How a slice picture is laid out, for messages and JSON.
struct SliceLayout {
  int layer = 0;         ///< voxel index along the axis
  int widthVoxels = 0;   ///< voxels across one panel (the first other axis)
  int heightVoxels = 0;  ///< voxels up one panel (the second other axis)
  int pixelsPerVoxel = 1;
  int gapPx = 0;  ///< between panels
};

/// The layout of a slice through `voxmap`; throws UsageError naming the grid's extent
/// when the plane misses the grid.
SliceLayout sliceLayout(const Voxmap& voxmap, const SliceSpec& slice);

/// Draws the three fields of the layer; panels left to right surface, edge, vertex; in
/// each, the first other axis (y for x, x for y and z) runs right, the second runs up.
render::RgbImage drawSlice(const Voxmap& voxmap, const SliceSpec& slice, const SliceLayout& layout);

}  // namespace voxhap::cli

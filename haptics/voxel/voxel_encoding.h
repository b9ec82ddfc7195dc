#pragma once
/// How a voxel's three distance fields are encoded (DESIGN §4.1, paper §3).
///
/// Each field is `bitsPerField` bits (2, 4 or 8) holding:
///   0                 beyond the field's range ("far")
///   1                 interior
///   2                 feature voxel (surface / edge / vertex voxel for that field)
///   3 … 2 + range     free space at chessboard distance 1 … range voxels
/// The three fields of a voxel pack into one word, surface field in the low bits,
/// then edge, then vertex: 6 bits in a byte (2-bit), 12 bits in a 16-bit word (4-bit,
/// 4 bits unused), 24 bits in a 32-bit word (8-bit).

#include <cstdint>

namespace voxhap {

/// The three distance fields, by the feature they measure distance to.
enum class Field : std::uint8_t { Surface = 0, Edge = 1, Vertex = 2 };
inline constexpr int kFieldCount = 3;

/// A packed voxel: three fields of `bitsPerField` bits.
using VoxelWord = std::uint32_t;

inline constexpr std::uint8_t kValueFar = 0;       ///< beyond the distance-field range
inline constexpr std::uint8_t kValueInterior = 1;  ///< inside the object
inline constexpr std::uint8_t kValueFeature = 2;   ///< a surface (edge, vertex) voxel
/// The value of free space at `distanceVoxels` (≥ 1) from the field's feature voxels.
inline constexpr std::uint8_t distanceValue(int distanceVoxels) {
  return static_cast<std::uint8_t>(kValueFeature + distanceVoxels);
}

/// Bit width and range of the fields, fixed per voxmap.
struct VoxelEncoding {
  int bitsPerField = 4;  ///< 2, 4 or 8
  int rangeVoxels = 8;   ///< largest stored distance; at most 2^bits − 3 (1 for 2-bit)

  /// The default range for a bit width: one chunk (8 voxels), or what fits.
  static VoxelEncoding forBits(int bits) {
    const int fits = (1 << bits) - 3;
    return {bits, fits < 8 ? fits : 8};
  }

  bool valid() const {
    return (bitsPerField == 2 || bitsPerField == 4 || bitsPerField == 8) && rangeVoxels >= 1 &&
           rangeVoxels <= (1 << bitsPerField) - 3;
  }
  /// Bytes one packed voxel occupies in a chunk: 1, 2 or 4.
  int bytesPerWord() const { return bitsPerField == 2 ? 1 : (bitsPerField == 4 ? 2 : 4); }
  std::uint32_t fieldMask() const { return (1u << bitsPerField) - 1u; }
  /// Largest value a field holds (free space at `rangeVoxels`).
  std::uint8_t maxValue() const { return distanceValue(rangeVoxels); }

  VoxelWord pack(std::uint8_t surface, std::uint8_t edge, std::uint8_t vertex) const {
    const int b = bitsPerField;
    return VoxelWord{surface} | (VoxelWord{edge} << b) | (VoxelWord{vertex} << (2 * b));
  }
  std::uint8_t value(VoxelWord word, Field field) const {
    return static_cast<std::uint8_t>((word >> (static_cast<int>(field) * bitsPerField)) & fieldMask());
  }
};

}  // namespace voxhap

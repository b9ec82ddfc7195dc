#include "haptics/collide/point_sampler_avx2.h"

#include <bit>

#include <immintrin.h>

namespace voxhap {
namespace {

const bool kCpuHasAvx2 = [] {
  __builtin_cpu_init();  // this may run before the constructors that would call it
  return __builtin_cpu_supports("avx2") != 0;
}();

/// What the lookup of eight voxels needs, broadcast to every lane.
struct Lookup8 {
  Voxmap::LookupArrays arrays;
  __m256i lastVoxel[3];  ///< dimsVoxels − 1 along x, y, z
  __m256i dimsHyperX;
  __m256i dimsHyperY;
  __m128i byteShift;  ///< log2 bytesPerWord: a word's index to its byte offset
  __m256i wordMask;
};

[[gnu::target("avx2")]] Lookup8 lookup8Of(const Voxmap& voxmap) {
  const Voxmap::LookupArrays arrays = voxmap.lookupArrays();
  const VoxelGrid& grid = voxmap.grid();
  const glm::ivec3 last = grid.dimsVoxels() - 1;
  return {arrays,
          {_mm256_set1_epi32(last.x), _mm256_set1_epi32(last.y), _mm256_set1_epi32(last.z)},
          _mm256_set1_epi32(grid.dimsHyper.x),
          _mm256_set1_epi32(grid.dimsHyper.y),
          _mm_cvtsi32_si128(std::countr_zero(arrays.bytesPerWord)),
          _mm256_set1_epi32(static_cast<int>(arrays.wordMask))};
}

/// (i >> shift) & 7 for each lane: a cell's coordinate inside its block of 8³.
[[gnu::target("avx2")]] inline __m256i cellBits(__m256i v, int shift) {
  return _mm256_and_si256(_mm256_srli_epi32(v, shift), _mm256_set1_epi32(7));
}

/// Index of a cell in its block of 8³ (x fastest), from cells' coordinates >> `shift`:
/// voxelInChunk (shift 0) and chunkInHyper (shift 3) of tree_shape.h.
[[gnu::target("avx2")]] inline __m256i cellIndex(__m256i x, __m256i y, __m256i z, int shift) {
  return _mm256_or_si256(cellBits(x, shift), _mm256_or_si256(_mm256_slli_epi32(cellBits(y, shift), 3),
                                                             _mm256_slli_epi32(cellBits(z, shift), 6)));
}

/// Four words by their indices in the voxmap's words (block · 512 + voxel in chunk), by
/// 64-bit byte offsets (a voxmap's words may pass 2 GiB): gathered where `mixed` (sign
/// bits), else `uniformWord`. One gather of eight by 32-bit offsets measured no faster.
[[gnu::target("avx2")]] inline __m128i wordsOf4(const Lookup8& l, __m128i wordIndex, __m128i mixed,
                                                __m128i uniformWord) {
  const __m256i byteAt = _mm256_sll_epi64(_mm256_cvtepu32_epi64(wordIndex), l.byteShift);
  return _mm256_mask_i64gather_epi32(uniformWord, reinterpret_cast<const int*>(l.arrays.words), byteAt, mixed,
                                     1);
}

/// 0 ≤ v ≤ last, lane by lane: as unsigned, min(v, last) == v.
[[gnu::target("avx2")]] inline __m256i within(__m256i v, __m256i last) {
  return _mm256_cmpeq_epi32(_mm256_min_epu32(v, last), v);
}

/// Voxmap::word of eight voxels: far (0) outside the grid, the uniform word of a uniform
/// hyperchunk or chunk, else the chunk's stored word. Masked gathers read nothing for the
/// lanes they skip.
[[gnu::target("avx2")]] inline __m256i words8(const Lookup8& l, __m256i x, __m256i y, __m256i z) {
  const __m256i inside = _mm256_and_si256(
      _mm256_and_si256(within(x, l.lastVoxel[0]), within(y, l.lastVoxel[1])), within(z, l.lastVoxel[2]));
  const int hyperShift = kChunkEdgeLog2 + kHyperEdgeLog2;
  const __m256i hyperIndex = _mm256_add_epi32(
      _mm256_srli_epi32(x, hyperShift),
      _mm256_mullo_epi32(
          l.dimsHyperX,
          _mm256_add_epi32(_mm256_srli_epi32(y, hyperShift),
                           _mm256_mullo_epi32(l.dimsHyperY, _mm256_srli_epi32(z, hyperShift)))));
  const __m256i zero = _mm256_setzero_si256();
  const __m256i hyper =
      _mm256_mask_i32gather_epi32(zero, reinterpret_cast<const int*>(l.arrays.hyper), hyperIndex, inside, 4);
  // the sign bit is kUniform: gather where inside and not uniform
  const __m256i mixedHyper = _mm256_andnot_si256(hyper, inside);
  const __m256i chunkIndex = _mm256_or_si256(_mm256_slli_epi32(hyper, 9), cellIndex(x, y, z, kChunkEdgeLog2));
  const __m256i entry = _mm256_mask_i32gather_epi32(hyper, reinterpret_cast<const int*>(l.arrays.chunks),
                                                    chunkIndex, mixedHyper, 4);
  const __m256i mixed = _mm256_srai_epi32(_mm256_andnot_si256(entry, inside), 31);
  const __m256i uniformWord = _mm256_and_si256(entry, _mm256_set1_epi32(~static_cast<int>(Voxmap::kUniform)));
  // an unpaged voxmap's blocks follow each other: a word's index is block · 512 + voxel in chunk
  const __m256i wordIndex = _mm256_or_si256(_mm256_slli_epi32(entry, 9), cellIndex(x, y, z, 0));
  const __m128i low = wordsOf4(l, _mm256_castsi256_si128(wordIndex), _mm256_castsi256_si128(mixed),
                               _mm256_castsi256_si128(uniformWord));
  const __m128i high = wordsOf4(l, _mm256_extracti128_si256(wordIndex, 1), _mm256_extracti128_si256(mixed, 1),
                                _mm256_extracti128_si256(uniformWord, 1));
  const __m256i words = _mm256_set_m128i(high, low);
  return _mm256_blendv_epi8(words, _mm256_and_si256(words, l.wordMask), mixed);
}

/// floor(v) as int32, as voxelOf: the same conversion for every float, NaN and overflow
/// included (both give INT_MIN, outside every grid).
[[gnu::target("avx2")]] inline __m256i floorToInt(__m256 v) {
  return _mm256_cvttps_epi32(_mm256_floor_ps(v));
}

/// x, y and z of eight points stored x y z x y z …, each in a vector of its own: the
/// points 0-3 in the low lanes, 4-7 in the high lanes, shuffled alike.
[[gnu::target("avx2")]] inline void transposeEightPoints(const float* xyz, __m256 (&out)[3]) {
  // per half: a = x0 y0 z0 x1, b = y1 z1 x2 y2, c = z2 x3 y3 z3
  const __m256 a = _mm256_set_m128(_mm_loadu_ps(xyz + 12), _mm_loadu_ps(xyz));
  const __m256 b = _mm256_set_m128(_mm_loadu_ps(xyz + 16), _mm_loadu_ps(xyz + 4));
  const __m256 c = _mm256_set_m128(_mm_loadu_ps(xyz + 20), _mm_loadu_ps(xyz + 8));
  const __m256 xy23 = _mm256_shuffle_ps(b, c, _MM_SHUFFLE(2, 1, 3, 2));  // x2 y2 x3 y3
  const __m256 yz01 = _mm256_shuffle_ps(a, b, _MM_SHUFFLE(1, 0, 2, 1));  // y0 z0 y1 z1
  out[0] = _mm256_shuffle_ps(a, xy23, _MM_SHUFFLE(2, 0, 3, 0));
  out[1] = _mm256_shuffle_ps(yz01, xy23, _MM_SHUFFLE(3, 1, 2, 0));
  out[2] = _mm256_shuffle_ps(yz01, c, _MM_SHUFFLE(3, 0, 3, 1));
}

}  // namespace

bool cpuHasAvx2() noexcept {
  return kCpuHasAvx2;
}

[[gnu::target("avx2")]] std::uint32_t samplePointsAvx2(const Pointshell& shell, const Voxmap& voxmap,
                                                       const VoxelTransform& transform,
                                                       const std::array<std::uint8_t, 3>& fieldShifts,
                                                       std::uint8_t maxValue, std::uint32_t first,
                                                       std::uint32_t last, PointContact* contacts) noexcept {
  const Lookup8 lookup = lookup8Of(voxmap);
  const glm::mat3& m = transform.rotationScaled;
  __m256 rotation[3][3];
  for (int column = 0; column < 3; ++column)
    for (int row = 0; row < 3; ++row) rotation[column][row] = _mm256_set1_ps(m[column][row]);
  const __m256 offset[3] = {_mm256_set1_ps(transform.offset.x), _mm256_set1_ps(transform.offset.y),
                            _mm256_set1_ps(transform.offset.z)};
  const __m256i shiftOfFeature =
      _mm256_setr_epi32(fieldShifts[0], fieldShifts[1], fieldShifts[2], 0, 0, 0, 0, 0);
  const __m256i fieldMask = _mm256_set1_epi32(static_cast<int>(voxmap.encoding().fieldMask()));
  const __m256i pastLayer = _mm256_set1_epi32(maxValue + 1);
  const float* positions = &shell.positionsLocal.data()->x;
  const auto* features = reinterpret_cast<const std::uint8_t*>(shell.features.data());
  std::uint32_t found = 0;
  std::uint32_t i = first;
  for (; last - i >= 8; i += 8) {
    __m256 local[3];
    transposeEightPoints(positions + 3 * std::size_t{i}, local);
    __m256i voxel[3];
    for (int row = 0; row < 3; ++row) {
      // VoxelTransform::apply as glm's mat3 * vec3 evaluates it: ((m0·x + m1·y) + m2·z) + offset
      const __m256 sum = _mm256_add_ps(
          _mm256_add_ps(_mm256_mul_ps(rotation[0][row], local[0]), _mm256_mul_ps(rotation[1][row], local[1])),
          _mm256_mul_ps(rotation[2][row], local[2]));
      voxel[row] = floorToInt(_mm256_add_ps(sum, offset[row]));
    }
    const __m256i word = words8(lookup, voxel[0], voxel[1], voxel[2]);
    const __m256i feature =
        _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(features + i)));
    const __m256i value = _mm256_and_si256(
        _mm256_srlv_epi32(word, _mm256_permutevar8x32_epi32(shiftOfFeature, feature)), fieldMask);
    const __m256i hit = _mm256_and_si256(_mm256_cmpgt_epi32(value, _mm256_setzero_si256()),
                                         _mm256_cmpgt_epi32(pastLayer, value));
    const auto lanes = static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(hit)));
    if (lanes == 0) continue;
    alignas(32) std::int32_t ijk[3][8];
    alignas(32) std::int32_t values[8];
    for (int axis = 0; axis < 3; ++axis)
      _mm256_store_si256(reinterpret_cast<__m256i*>(ijk[axis]), voxel[axis]);
    _mm256_store_si256(reinterpret_cast<__m256i*>(values), value);
    // every lane written, the count advanced by the hits only: no branch per lane to
    // mispredict (which would stall the next group's gathers). The slot written for a lane
    // is at most its point's index in [first, last), inside the caller's room.
    for (unsigned lane = 0; lane < 8; ++lane) {
      PointContact& contact = contacts[found];
      contact.point = i + lane;
      contact.ijkVoxel = {ijk[0][lane], ijk[1][lane], ijk[2][lane]};
      contact.value = static_cast<std::uint8_t>(values[lane]);
      found += (lanes >> lane) & 1u;
    }
  }
  return found + samplePointsOn(PointTestPath::Scalar, shell, voxmap, transform, fieldShifts, maxValue, i,
                                last, contacts + found);
}

[[gnu::target("avx2")]] void voxelWordsAvx2(const Voxmap& voxmap, const glm::ivec3* ijkVoxels,
                                            std::size_t count, VoxelWord* words) noexcept {
  static_assert(sizeof(glm::ivec3) == 3 * sizeof(float));
  const Lookup8 lookup = lookup8Of(voxmap);
  for (std::size_t i = 0; i + 8 <= count; i += 8) {
    __m256 ijk[3];
    transposeEightPoints(reinterpret_cast<const float*>(ijkVoxels + i), ijk);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(words + i),
                        words8(lookup, _mm256_castps_si256(ijk[0]), _mm256_castps_si256(ijk[1]),
                               _mm256_castps_si256(ijk[2])));
  }
}

}  // namespace voxhap

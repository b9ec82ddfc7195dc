#pragma once
/// SpaceMouse-class HID input reports (3Dconnexion 6-DOF controllers) and their parser:
/// bytes in, deflection and buttons out. Pure: no I/O, no allocation, noexcept.
///
/// Reports (little-endian int16 counts, about ±350 at full deflection):
///   id 1, 7 bytes:  translation x, y, z               (older models: "separate" layout)
///   id 2, 7 bytes:  rotation x, y, z                  (older models)
///   id 1, 13 bytes: translation x, y, z, rotation x, y, z  (newer models: "combined")
///   id 3:           buttons, a little-endian bitmask of buttonBytes bytes (bit 0: button 1)
/// A buffer may hold several reports back to back (a coalesced read); the parser splits it
/// by id and known length. An unknown id cannot be skipped (its length is unknown), so it
/// ends the buffer; it and a report cut short are counted as errors, never read past.
///
/// Axes. The device reports in its own frame: +x right, +y toward the user, +z down
/// (right-handed), rotations about those axes by the right-hand rule. The parser hands
/// out the view frame used by the front end's camera: +x right, +y up, +z toward the
/// user (out of the screen), also right-handed, so the map is a proper rotation and the
/// same table serves translations and rotation vectors: kDeviceToViewAxes.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace voxhap {

/// The Logitech-era 3Dconnexion vendor id and 3Dconnexion's own.
inline constexpr std::uint16_t kVendorLogitech3Dconnexion = 0x046d;
inline constexpr std::uint16_t kVendor3Dconnexion = 0x256f;

/// HID usage of a multi-axis controller: Generic Desktop page, usage 0x08.
inline constexpr std::uint16_t kUsagePageGenericDesktop = 0x01;
inline constexpr std::uint16_t kUsageMultiAxisController = 0x08;

/// How a model sends its motion.
enum class SpaceMouseMotionLayout : std::uint8_t {
  kSeparate,  ///< id 1 translation and id 2 rotation, 7 bytes each
  kCombined,  ///< id 1 of 13 bytes, translation then rotation
  kAuto,      ///< unknown: an id-1 report is combined when 13 bytes or more remain and
              ///< the byte after the first 7 is not a motion or button id
};

/// The shape of a model's reports.
struct SpaceMouseReportFormat {
  SpaceMouseMotionLayout motion = SpaceMouseMotionLayout::kAuto;
  std::uint8_t buttonBytes = 2;  ///< bytes of the id-3 bitmask after the id, 1..4
};

/// A model the parser knows by its USB product id (under either 3Dconnexion vendor id).
struct SpaceMouseModel {
  std::uint16_t productId;
  std::string_view name;
  SpaceMouseReportFormat format;
};

/// The models known by id (others are found by their HID usage and read with kAuto).
std::span<const SpaceMouseModel> knownSpaceMouseModels() noexcept;

/// The known model with these ids (vendor: either of the two above), or nullptr.
const SpaceMouseModel* findSpaceMouseModel(std::uint16_t vendorId, std::uint16_t productId) noexcept;

/// Index of the six axes in a deflection array: translations, then rotations.
enum SpaceMouseAxis : std::size_t { kAxisTx, kAxisTy, kAxisTz, kAxisRx, kAxisRy, kAxisRz, kAxisCount };

/// One view axis taken from one device axis with a sign.
struct AxisMap {
  std::size_t deviceAxis;  ///< 0..2 within translation (or rotation)
  double sign;             ///< +1 or −1
};

/// Device frame (x right, y toward the user, z down) → view frame (x right, y up, z toward
/// the user): view x = device x, view y = −device z, view z = device y. Indexed by view
/// axis; applied alike to translation and rotation.
inline constexpr std::array<AxisMap, 3> kDeviceToViewAxes{{{0, 1.0}, {2, -1.0}, {1, 1.0}}};

/// The state the reports describe, in the view frame.
struct SpaceMouseState {
  /// Tx, Ty, Tz, Rx, Ry, Rz (SpaceMouseAxis), each in [−1, 1] of full deflection.
  std::array<double, kAxisCount> deflectionView{};
  std::uint32_t buttons = 0;  ///< bit i: button i + 1 is down
};

/// What a call of parseSpaceMouseReports changed (bits of SpaceMouseParseResult::changed).
enum SpaceMouseChange : std::uint8_t {
  kChangedTranslation = 1u << 0,
  kChangedRotation = 1u << 1,
  kChangedButtons = 1u << 2,
};

/// The outcome of parsing one buffer.
struct SpaceMouseParseResult {
  std::uint32_t reports = 0;       ///< whole reports applied
  std::uint32_t errors = 0;        ///< unknown ids and cut-short reports
  std::size_t bytesDiscarded = 0;  ///< bytes not applied, from the first error on
  std::uint8_t changed = 0;        ///< SpaceMouseChange bits whose values changed
};

/// Applies every whole report in `bytes` to `state`, in order, each axis as counts /
/// `fullScaleCounts` (> 0) clamped to [−1, 1]. Bytes from the first unknown id or cut-short
/// report on are discarded and counted.
SpaceMouseParseResult parseSpaceMouseReports(std::span<const std::uint8_t> bytes,
                                             const SpaceMouseReportFormat& format, double fullScaleCounts,
                                             SpaceMouseState& state) noexcept;

}  // namespace voxhap

#include "haptics/device/motion_script.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <system_error>

#include "haptics/core/error.h"

namespace voxhap {
namespace fs = std::filesystem;
namespace {

/// Motion scripts larger than this are refused rather than read into memory.
constexpr std::uintmax_t kMaxScriptBytes = std::uintmax_t{256} << 20;

/// Number of fields on a pose line, and their names for messages.
constexpr std::size_t kFieldCount = 8;
constexpr std::array<const char*, kFieldCount> kFieldNames = {"t", "qw", "qx", "qy", "qz", "tx", "ty", "tz"};

/// Shortest text that reads back as `v`.
std::string formatNumber(double v) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  return std::string(buffer.data(), result.ptr);
}

/// A token as shown in a message: quoted, long ones cut short.
std::string shown(std::string_view token) {
  constexpr std::size_t kMaxShown = 24;
  if (token.size() <= kMaxShown) return "'" + std::string(token) + "'";
  return "'" + std::string(token.substr(0, kMaxShown)) + "...'";
}

/// Unit quaternion of (w, x, y, z), or false when it is zero or not finite. Scales by
/// the largest component first so that tiny or huge values neither underflow nor overflow.
bool normalizedQuat(double w, double x, double y, double z, glm::dquat& out) {
  if (!std::isfinite(w) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return false;
  const double largest = std::max({std::abs(w), std::abs(x), std::abs(y), std::abs(z)});
  if (largest == 0.0) return false;
  const glm::dquat scaled = quatWxyz(w / largest, x / largest, y / largest, z / largest);
  out = scaled / glm::length(scaled);
  return true;
}

/// Checks keyframe `k` against the previous one (called `previousName` in messages);
/// returns what is wrong, or "".
std::string keyframeProblem(const MotionKeyframe& k, const MotionKeyframe* previous,
                            const std::string& previousName) {
  if (!std::isfinite(k.timeS)) return "time is not finite";
  if (!previous && k.timeS < 0.0) {
    return "time " + formatNumber(k.timeS) + " s is negative (the first must be >= 0)";
  }
  if (previous && !(k.timeS > previous->timeS)) {
    return "time " + formatNumber(k.timeS) + " s is not after " + formatNumber(previous->timeS) + " s at " +
           previousName + " (times must increase strictly)";
  }
  const glm::dvec3& p = k.handleWorld.position;
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return "translation is not finite";
  const glm::dquat& q = k.handleWorld.orientation;
  glm::dquat unit;
  if (!normalizedQuat(q.w, q.x, q.y, q.z, unit)) return "quaternion is zero or not finite";
  return {};
}

std::string_view trimmed(std::string_view s) {
  const auto isSpace = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
  while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
  return s;
}

/// Splits `line` at spaces and tabs into at most `out.size()` tokens; returns the count
/// found (which may exceed out.size(): the extra tokens are counted, not stored).
std::size_t splitFields(std::string_view line, std::array<std::string_view, kFieldCount>& out) {
  std::size_t count = 0;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    if (i == line.size()) break;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (count < out.size()) out[count] = line.substr(start, i - start);
    ++count;
  }
  return count;
}

/// Parses a whole token as a double (locale-independent; a leading '+' allowed);
/// returns what is wrong with it, or nullptr.
const char* parseNumber(std::string_view token, double& value) {
  if (token.size() > 1 && token.front() == '+' && token[1] != '-' && token[1] != '+') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ec == std::errc::result_out_of_range && ptr == end) return "is out of range";
  if (ec != std::errc() || ptr != end) return "is not a number";
  if (!std::isfinite(value)) return "is not finite";
  return nullptr;
}

}  // namespace

MotionScript::MotionScript(std::vector<MotionKeyframe> keyframes, std::string sourceName)
    : keyframes_(std::move(keyframes)), sourceName_(std::move(sourceName)) {
  if (keyframes_.empty()) throw Error(sourceName_ + ": motion script has no poses");
  for (std::size_t i = 0; i < keyframes_.size(); ++i) {
    MotionKeyframe& k = keyframes_[i];
    const std::string problem =
        keyframeProblem(k, i > 0 ? &keyframes_[i - 1] : nullptr, "keyframe " + std::to_string(i));
    if (!problem.empty()) throw Error(sourceName_ + ": keyframe " + std::to_string(i + 1) + ": " + problem);
    const glm::dquat& q = k.handleWorld.orientation;
    normalizedQuat(q.w, q.x, q.y, q.z, k.handleWorld.orientation);
  }
}

Pose MotionScript::sample(double tS) const noexcept {
  const MotionKeyframe& first = keyframes_.front();
  const MotionKeyframe& last = keyframes_.back();
  if (!(tS > first.timeS)) return first.handleWorld;
  if (!(tS < last.timeS)) return last.handleWorld;
  // the first keyframe later than tS; it has a predecessor since tS > first.timeS
  const auto next = std::upper_bound(keyframes_.begin(), keyframes_.end(), tS,
                                     [](double t, const MotionKeyframe& k) { return t < k.timeS; });
  const MotionKeyframe& b = *next;
  const MotionKeyframe& a = *(next - 1);
  if (tS == a.timeS) return a.handleWorld;
  return interpolate(a.handleWorld, b.handleWorld, (tS - a.timeS) / (b.timeS - a.timeS));
}

MotionScript parseMotionScript(std::string_view text, const std::string& fileName) {
  std::vector<MotionKeyframe> keyframes;
  std::size_t previousLine = 0;
  std::size_t lineNumber = 0;
  while (!text.empty()) {
    ++lineNumber;
    const std::size_t newline = text.find('\n');
    std::string_view line = text.substr(0, newline);
    text.remove_prefix(newline == std::string_view::npos ? text.size() : newline + 1);
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    line = trimmed(line);
    if (line.empty()) continue;

    const std::string where = fileName + ":" + std::to_string(lineNumber) + ": ";
    std::array<std::string_view, kFieldCount> fields;
    const std::size_t count = splitFields(line, fields);
    if (count != kFieldCount) {
      throw Error(where + "expected 8 numbers 't qw qx qy qz tx ty tz', found " + std::to_string(count) +
                  " fields");
    }
    std::array<double, kFieldCount> v{};
    for (std::size_t i = 0; i < kFieldCount; ++i) {
      if (const char* problem = parseNumber(fields[i], v[i])) {
        throw Error(where + "field " + std::to_string(i + 1) + " (" + kFieldNames[i] + ") " + problem + ": " +
                    shown(fields[i]));
      }
    }
    MotionKeyframe k;
    k.timeS = v[0];
    k.handleWorld.orientation = quatWxyz(v[1], v[2], v[3], v[4]);
    k.handleWorld.position = glm::dvec3(v[5], v[6], v[7]);
    const MotionKeyframe* previous = keyframes.empty() ? nullptr : &keyframes.back();
    const std::string problem = keyframeProblem(k, previous, "line " + std::to_string(previousLine));
    if (!problem.empty()) throw Error(where + problem);
    keyframes.push_back(k);
    previousLine = lineNumber;
  }
  if (keyframes.empty()) throw Error(fileName + ": motion script has no poses (only blank or comment lines)");
  return MotionScript(std::move(keyframes), fileName);
}

MotionScript loadMotionScript(const fs::path& file) {
  const std::string fileName = file.string();
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (ec || !fs::exists(status)) throw Error(fileName + ": no such file");
  if (!fs::is_regular_file(status)) throw Error(fileName + ": not a regular file");
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec) throw Error(fileName + ": cannot read its size: " + ec.message());
  if (size > kMaxScriptBytes) {
    throw Error(fileName + ": larger than the 256 MiB limit for motion scripts (" + std::to_string(size) +
                " bytes)");
  }
  std::ifstream in(file, std::ios::binary);
  std::string text(static_cast<std::size_t>(size), '\0');
  if (!in || !in.read(text.data(), static_cast<std::streamsize>(size))) {
    throw Error(fileName + ": cannot read: " + std::strerror(errno));
  }
  return parseMotionScript(text, fileName);
}

}  // namespace voxhap

#include "haptics/sim/sim_state.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <string>

#define XXH_STATIC_LINKING_ONLY  // XXH3_state_t on the stack: no allocation
#include <glm/gtc/quaternion.hpp>
#include <xxhash.h>

#include "haptics/core/error.h"

namespace voxhap {
namespace {

static_assert(std::endian::native == std::endian::little, "snapshots are written little-endian as in memory");

constexpr std::uint32_t kMagic = 0x54535856;  // "VXST"
constexpr std::uint32_t kVersion = 1;

/// Feeds every replicated field of `state` to `put(const void*, bytes)`, in snapshot order.
template <typename Put>
void writeFields(const SimState& state, Put&& put) {
  auto value = [&put](const auto& v) { put(&v, sizeof v); };
  auto vector = [&value](const glm::dvec3& v) {
    value(v.x);
    value(v.y);
    value(v.z);
  };
  value(kMagic);
  value(kVersion);
  value(static_cast<std::uint32_t>(state.bodies.size()));
  value(state.frame);
  value(state.timeS);
  value(state.forceLayer);
  for (std::size_t i = 0; i < state.bodies.size(); ++i) {
    const RigidBodyState& b = state.bodies[i];
    vector(b.comWorld);
    value(b.orientation.w);
    value(b.orientation.x);
    value(b.orientation.y);
    value(b.orientation.z);
    vector(b.linearVelocityWorld);
    vector(b.angularVelocityWorld);
    value(i < state.owners.size() ? state.owners[i] : kNoPeer);
  }
}

/// Reads the fields writeFields wrote, in order; throws on running out.
class FieldReader {
public:
  explicit FieldReader(std::span<const std::byte> bytes) : bytes_(bytes) {}

  template <typename T>
  T value() {
    T v;
    if (bytes_.size() - used_ < sizeof v)
      throw Error("state snapshot: truncated at byte " + std::to_string(used_));
    std::memcpy(&v, bytes_.data() + used_, sizeof v);
    used_ += sizeof v;
    return v;
  }
  double finite(const char* what) {
    const double v = value<double>();
    if (!std::isfinite(v)) throw Error(std::string("state snapshot: ") + what + " is not finite");
    return v;
  }
  glm::dvec3 vector(const char* what) {
    const double x = finite(what);
    const double y = finite(what);
    return {x, y, finite(what)};
  }
  std::size_t left() const { return bytes_.size() - used_; }

private:
  std::span<const std::byte> bytes_;
  std::size_t used_ = 0;
};

}  // namespace

SimState makeSimState(const SimModel& model) {
  SimState state;
  for (const MovingObjectModel& object : model.objects) state.bodies.push_back(restingState(object.body));
  state.owners.assign(model.objects.size(), kNoPeer);
  if (!model.pairs.empty()) state.forceLayer = model.pairs.front().params.forceLayer;
  return state;
}

std::uint64_t hashState(const SimState& state) noexcept {
  XXH3_state_t hash;
  XXH3_64bits_reset(&hash);
  writeFields(state,
              [&hash](const void* data, std::size_t bytes) { XXH3_64bits_update(&hash, data, bytes); });
  return XXH3_64bits_digest(&hash);
}

std::vector<std::byte> saveState(const SimState& state) {
  std::size_t size = 0;
  writeFields(state, [&size](const void*, std::size_t bytes) { size += bytes; });
  std::vector<std::byte> bytes(size);
  std::size_t used = 0;
  writeFields(state, [&bytes, &used](const void* data, std::size_t n) {
    std::memcpy(bytes.data() + used, data, n);
    used += n;
  });
  return bytes;
}

SimState restoreState(const SimModel& model, std::span<const std::byte> bytes) {
  FieldReader in(bytes);
  if (in.value<std::uint32_t>() != kMagic) throw Error("state snapshot: not a Voxhap state snapshot");
  if (const auto version = in.value<std::uint32_t>(); version != kVersion) {
    throw Error("state snapshot: version " + std::to_string(version) + ", this build reads version " +
                std::to_string(kVersion));
  }
  const auto count = in.value<std::uint32_t>();
  if (count != model.objects.size()) {
    throw Error("state snapshot: " + std::to_string(count) + " moving objects, the scene has " +
                std::to_string(model.objects.size()));
  }
  SimState state;
  state.frame = in.value<std::uint64_t>();
  state.timeS = in.finite("the time");
  state.forceLayer = in.value<std::uint8_t>();
  if (!model.forceLayerInRange(state.forceLayer)) {
    throw Error("state snapshot: force layer " + std::to_string(state.forceLayer) +
                " is outside the voxmaps' values");
  }
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::string what = "the body of " + model.objects[i].name;
    RigidBodyState& b = state.bodies.emplace_back();
    b.comWorld = in.vector(what.c_str());
    const double w = in.finite(what.c_str());
    const glm::dvec3 xyz = in.vector(what.c_str());
    b.orientation = glm::dquat(w, xyz.x, xyz.y, xyz.z);
    if (!(std::abs(glm::length(b.orientation) - 1.0) <= 1e-9)) {
      throw Error("state snapshot: " + what + " has an orientation that is not a unit quaternion");
    }
    b.linearVelocityWorld = in.vector(what.c_str());
    b.angularVelocityWorld = in.vector(what.c_str());
    state.owners.push_back(in.value<PeerId>());
  }
  if (in.left() != 0) throw Error("state snapshot: " + std::to_string(in.left()) + " bytes past its end");
  return state;
}

}  // namespace voxhap

#pragma once
/// The engine's vectors and poses as the front-end protocol's messages, and back.

#include <iterator>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>

#include "haptics/dynamics/pose.h"
#include "net/proto/frontend.pb.h"

namespace voxhap::net {

namespace pb = voxhap::frontend::v1;

inline void toProto(const glm::dvec3& v, pb::Vec3& out) {
  out.set_x(v.x);
  out.set_y(v.y);
  out.set_z(v.z);
}

inline void toProto(const Pose& pose, pb::Pose& out) {
  toProto(pose.position, *out.mutable_position_m());
  out.mutable_orientation()->set_w(pose.orientation.w);
  out.mutable_orientation()->set_x(pose.orientation.x);
  out.mutable_orientation()->set_y(pose.orientation.y);
  out.mutable_orientation()->set_z(pose.orientation.z);
}

/// Points as x y z in turn in a repeated float field (contact points, voxel centres), m.
template <typename Points>
void appendXyz(const Points& points, google::protobuf::RepeatedField<float>& out) {
  out.Reserve(out.size() + 3 * static_cast<int>(std::size(points)));
  for (const auto& p : points) {
    for (int k = 0; k < 3; ++k) out.Add(static_cast<float>(p[k]));
  }
}

/// Back: every whole x y z of `xyz`, appended to `out`.
inline void appendPoints(const google::protobuf::RepeatedField<float>& xyz, std::vector<glm::vec3>& out) {
  for (int c = 0; c + 2 < xyz.size(); c += 3) out.emplace_back(xyz[c], xyz[c + 1], xyz[c + 2]);
}

/// The pose as given: not checked for finiteness or a unit quaternion.
inline Pose fromProto(const pb::Pose& p) {
  Pose pose;
  pose.position = {p.position_m().x(), p.position_m().y(), p.position_m().z()};
  pose.orientation =
      quatWxyz(p.orientation().w(), p.orientation().x(), p.orientation().y(), p.orientation().z());
  return pose;
}

/// Of a divergent shared object's other instances, the one furthest from the shown pose
/// (what a front end draws marked); none when it has none.
inline std::optional<Pose> furthestOtherInstance(const pb::ObjectState& o) {
  std::optional<Pose> furthest;
  const glm::dvec3 shown = fromProto(o.pose()).position;
  for (const pb::Pose& p : o.other_instances()) {
    const Pose other = fromProto(p);
    if (!furthest || glm::length(other.position - shown) > glm::length(furthest->position - shown))
      furthest = other;
  }
  return furthest;
}

}  // namespace voxhap::net

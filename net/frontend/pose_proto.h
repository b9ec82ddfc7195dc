#pragma once
/// The engine's vectors and poses as the front-end protocol's messages, and back.

#include <optional>

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

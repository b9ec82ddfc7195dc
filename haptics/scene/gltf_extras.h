#pragma once
/// Voxhap's settings of an object in a glTF node's extras (`extras.voxhap`: role, object,
/// density, point_offset, force_layer; DESIGN §5): read by the loader, written by the
/// writer, so that the names and checks live in one place.

#include <optional>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "haptics/scene/scene.h"

namespace voxhap {

/// Settings found in a node's extras, if it has any for Voxhap.
struct NodeSettings {
  std::string objectName;
  ObjectSettings settings;
};

/// The settings in `node`'s extras (named `nodeName`, `where` for messages), or none when
/// it has no `extras.voxhap`. Throws voxhap::Error for a bad value; an unknown key is
/// added to `warnings` and ignored.
std::optional<NodeSettings> readNodeSettings(const tinygltf::Node& node, const std::string& nodeName,
                                             const std::string& where, std::vector<std::string>& warnings);

/// `object`'s settings as a node's extras, as readNodeSettings reads them.
tinygltf::Value objectExtras(const SceneObject& object);

}  // namespace voxhap

#include "haptics/scene/gltf_extras.h"

#include <cmath>

#include "haptics/core/error.h"

namespace voxhap {

std::optional<NodeSettings> readNodeSettings(const tinygltf::Node& node, const std::string& nodeName,
                                             const std::string& where, std::vector<std::string>& warnings) {
  if (!node.extras.IsObject() || !node.extras.Has("voxhap")) return std::nullopt;
  const tinygltf::Value& v = node.extras.Get("voxhap");
  if (!v.IsObject()) throw Error(where + ": extras.voxhap must be an object");
  NodeSettings result{nodeName, {}};
  for (const std::string& key : v.Keys()) {
    const tinygltf::Value& field = v.Get(key);
    const std::string fieldWhere = where + ": extras.voxhap." + key;
    if (key == "role") {
      const std::string role = field.IsString() ? field.Get<std::string>() : std::string();
      if (role == "static") {
        result.settings.role = ObjectRole::Static;
      } else if (role == "dynamic") {
        result.settings.role = ObjectRole::Dynamic;
      } else {
        throw Error(fieldWhere + " must be \"static\" or \"dynamic\"");
      }
    } else if (key == "object") {
      if (!field.IsString() || field.Get<std::string>().empty()) {
        throw Error(fieldWhere + " must be a non-empty string");
      }
      result.objectName = field.Get<std::string>();
    } else if (key == "density") {
      const double density = field.IsNumber() ? field.GetNumberAsDouble() : -1.0;
      if (!(density > 0.0) || !std::isfinite(density)) {
        throw Error(fieldWhere + " must be a positive number (kg/m³)");
      }
      result.settings.densityKgPerM3 = density;
    } else if (key == "point_offset") {
      const double offsetM = field.IsNumber() ? field.GetNumberAsDouble() : std::nan("");
      if (!(std::abs(offsetM) <= kMaxPointOffsetM)) {
        throw Error(fieldWhere + " must be a length of at most 1 m either way (metres)");
      }
      result.settings.pointOffsetM = offsetM;
    } else if (key == "force_layer") {
      const double layer = field.IsNumber() ? field.GetNumberAsDouble() : 0.0;
      if (!(layer >= 1.0 && layer <= 255.0) || layer != std::floor(layer)) {
        throw Error(fieldWhere + " must be a whole number of voxel layers, 1 … 255");
      }
      result.settings.forceLayer = static_cast<std::uint8_t>(layer);
    } else {
      warnings.push_back(fieldWhere + " is not a Voxhap setting; ignored");
    }
  }
  return result;
}

tinygltf::Value objectExtras(const SceneObject& object) {
  tinygltf::Value::Object voxhap;
  voxhap["role"] = tinygltf::Value(std::string(roleName(object.settings.role)));
  if (object.settings.densityKgPerM3) voxhap["density"] = tinygltf::Value(*object.settings.densityKgPerM3);
  if (object.settings.pointOffsetM) voxhap["point_offset"] = tinygltf::Value(*object.settings.pointOffsetM);
  if (object.settings.forceLayer) voxhap["force_layer"] = tinygltf::Value(int{*object.settings.forceLayer});
  tinygltf::Value::Object extras;
  extras["voxhap"] = tinygltf::Value(std::move(voxhap));
  return tinygltf::Value(std::move(extras));
}

}  // namespace voxhap

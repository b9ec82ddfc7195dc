#pragma once
/// glTF 2.0 import (`.gltf` with external or embedded buffers, and `.glb`).
///
/// Every mesh node becomes a `Part` in world coordinates. Parts are grouped into
/// logical objects by the nearest node, the mesh node itself or an ancestor, whose
/// `extras` carry Voxhap settings:
///
///     "extras": {"voxhap": {"role": "dynamic", "object": "actuator", "density": 7800,
///                           "point_offset": -0.0005, "force_layer": 3}}
///
/// `role` is "static" (default) or "dynamic"; `object` names the logical object
/// (nodes naming the same object merge into it; default: that node's name);
/// `density` is in kg/m³; `point_offset` moves the object's points along their
/// normals, in metres, negative inward (ObjectSettings::pointOffsetM); `force_layer` is
/// the force layer of the object's pairs when it moves (ObjectSettings::forceLayer). A mesh node with
/// no such node above it is a static object of its own. A node with no mesh and no such
/// settings, on it or above it, that holds parts is a `SceneGroup` (a CAD sub-assembly):
/// its name may be moved as one object (object_selection.h). Objects, then groups, that
/// share a name are numbered " (2)", " (3)", … with a warning. Bad files throw
/// `voxhap::Error` with one line that names the file and the node, mesh, accessor or
/// field; nothing the loader skips goes unreported.

#include <cstdint>
#include <filesystem>

#include "haptics/core/progress.h"
#include "haptics/scene/scene.h"

namespace voxhap {

/// Largest glTF file accepted, bytes (tinygltf takes at most 4 GiB in one piece).
inline constexpr std::uint64_t kMaxGltfFileBytes = (std::uint64_t{1} << 32) - 1;

/// Loads `file` (glTF JSON or GLB, decided by content, not by extension).
/// Throws voxhap::Error on a file that cannot be read or is not valid glTF.
Scene loadGltfScene(const std::filesystem::path& file, const ProgressFn& progress = {});

}  // namespace voxhap

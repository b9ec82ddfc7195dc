#pragma once
/// glTF 2.0 export of a Scene as a binary .glb, the inverse of the loader.
///
/// Each object becomes a node carrying `extras.voxhap` (role, density); its parts
/// become child nodes with one indexed triangle primitive each (the mesh sits on
/// the object node itself when the object is one part of the same name). Output is
/// deterministic: the same Scene gives the same bytes.

#include <filesystem>
#include <vector>

#include "haptics/scene/scene.h"

namespace voxhap {

/// The scene as GLB bytes.
std::vector<unsigned char> writeGlb(const Scene& scene);

/// Writes the scene to `file` atomically (a temporary file renamed into place), so
/// that an interrupted write never leaves a partial file. Throws voxhap::Error.
void writeGlbFile(const Scene& scene, const std::filesystem::path& file);

}  // namespace voxhap

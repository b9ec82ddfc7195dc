#pragma once
/// What `voxhap scene info` and `voxhap demo` say about a scene: as a JSON object
/// and as a text table.

#include <ostream>

#include <nlohmann/json.hpp>

#include "haptics/scene/scene.h"

namespace voxhap::cli {

/// Objects (name, role, parts with colours, triangles, bounds in metres, closed,
/// consistently oriented), groups (name, objects, parts, triangles, bounds in metres,
/// whether --move may name them), totals by role, scene bounds, and the loader's warnings.
nlohmann::ordered_json sceneSummaryJson(const Scene& scene);

/// The same figures as a table; `withParts` adds a line per part and names every
/// object of a group.
void printSceneSummary(std::ostream& out, const Scene& scene, bool withParts);

}  // namespace voxhap::cli

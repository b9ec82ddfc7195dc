#pragma once
/// The subcommands of `voxhap`, one function each, assembled in cli/command.cpp.

#include "app/cli/command.h"

namespace voxhap::cli {

/// `voxhap scene info|generate`.
Command sceneCommand();
/// `voxhap simulate`: the headless 1 kHz simulation driven by motion scripts.
Command simulateCommand();
/// `voxhap voxelize`: one object's or the static environment's voxmap, Table 1 figures.
Command voxelizeCommand();
/// `voxhap bench NAME`: the paper's measurements (Table 1, …) as tables, JSON, CSV, SVG.
Command benchCommand();
/// `voxhap demo`: the main job on the built-in default scene.
Command demoCommand();
/// `voxhap controller`: the haptic controller serving front ends.
Command controllerCommand();

}  // namespace voxhap::cli

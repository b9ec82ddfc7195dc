#pragma once
/// The subcommands of `voxhap`, one function each, assembled in cli/command.cpp.

#include "app/cli/command.h"

namespace voxhap::cli {

/// `voxhap scene info|generate`.
Command sceneCommand();
/// `voxhap demo`: the main job on the built-in default scene.
Command demoCommand();

}  // namespace voxhap::cli

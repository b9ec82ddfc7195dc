#pragma once
/// The subcommands of `voxhap`, one function each, assembled in cli/command.cpp. Each adds
/// its command (or group) under the tree's root, with its options bound to the fields of
/// a struct its handler owns.

#include "app/cli/command.h"

namespace voxhap::cli {

/// `voxhap scene info|generate`.
void addSceneCommands(CommandTree& tree);
/// `voxhap simulate`: the headless 1 kHz simulation driven by motion scripts.
void addSimulateCommand(CommandTree& tree);
/// `voxhap voxelize`: one object's or the static environment's voxmap, Table 1 figures.
void addVoxelizeCommand(CommandTree& tree);
/// `voxhap bench NAME`: the paper's measurements (Table 1, …) as tables, JSON, CSV, SVG.
void addBenchCommands(CommandTree& tree);
/// `voxhap demo`: the main job, a session of three peers on the built-in landing gear.
void addDemoCommand(CommandTree& tree);
/// `voxhap extract`: the main job for one user, offline.
void addExtractCommand(CommandTree& tree);
/// `voxhap controller`: the haptic controller serving front ends.
void addControllerCommand(CommandTree& tree);
/// `voxhap view`: the front end's window.
void addViewCommand(CommandTree& tree);
/// `voxhap peer`: a controller joined to other peers over UDP, and its window.
void addPeerCommand(CommandTree& tree);
/// `voxhap relay`: a UDP forwarder that impairs the path, for trying peers on one machine.
void addRelayCommand(CommandTree& tree);

}  // namespace voxhap::cli

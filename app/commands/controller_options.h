#pragma once
/// What every command that runs a haptic controller takes (`voxhap controller`, `voxhap
/// peer`): the model's sizes and device profile, a duration, realtime or not, JSON, and
/// the check of a --device string.

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "app/cli/console.h"
#include "app/controller/controller_run.h"
#include "app/sim_options.h"

namespace voxhap::cli {

struct ControllerRunArgs {
  SimOptions sim;
  std::optional<double> durationS;
  bool noRealtime = false;
  bool json = false;
};

/// Adds the model's sizes and --frame-helper, --duration, --no-realtime, the cache options and
/// --json, in that order.
void addControllerRunOptions(CLI::App& command, ControllerRunArgs& args);

/// Fills `options`' model, duration, realtime and JSON from `args`.
void applyControllerRunArgs(const ControllerRunArgs& args, Console& console, ControllerOptions& options);

/// Throws UsageError unless `device` is empty or script:FILE, hand:FILE or spacemouse[:PATH].
void checkDeviceOption(const std::string& device);

}  // namespace voxhap::cli

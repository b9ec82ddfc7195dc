#pragma once
/// The benchmarks of `voxhap bench NAME`, one function each.
///
/// A benchmark measures and fills a BenchTable; `voxhap bench` (commands/bench_command.cpp)
/// adds its options and the output ones, refuses what it cannot do and writes the table as
/// text, JSON, CSV and, for benchmarks with a curve, an SVG plot. Adding one is: write a function
/// returning its Benchmark and add it to the list in bench_command.cpp.

#include <functional>
#include <optional>
#include <string>

#include "app/bench/bench_table.h"
#include "app/bench/svg_plot.h"
#include "app/cli/console.h"
#include "app/cli/option_values.h"

namespace CLI {
class App;
}  // namespace CLI

namespace voxhap::cli {

/// Measures with the options the benchmark was given (bound when its options were added),
/// reporting progress and notes on `console`; throws UsageError on bad options,
/// voxhap::Error on bad data.
using BenchRunFn = std::function<BenchTable(Console& console)>;

struct Benchmark {
  std::string name;         ///< as typed after `voxhap bench`
  std::string summary;      ///< one line for `voxhap bench --help`
  std::string usage;        ///< the options it takes beyond the output ones, e.g. "[--quick]"
  std::string description;  ///< paragraphs for `voxhap bench NAME --help`
  /// Adds its own options to `command` (the output options are added for it), bound to
  /// fields the returned function measures with.
  std::function<BenchRunFn(CLI::App& command)> addOptions;
  /// How `--svg` plots its rows; none for a benchmark with no curve, which refuses --svg.
  std::optional<SvgPlotSpec> plot;
};

/// The paper's Table 1: voxelize and load times, triangles, points and voxels of the
/// built-in scenes at the paper's voxel sizes.
Benchmark table1Benchmark();

/// The paper's ball-and-socket measure: one turn of the ball at MaxTravel.
Benchmark rotationBenchmark();

/// The paper's landing-gear task (§7): the actuator extraction of `voxhap demo` at
/// several resolutions, with frame timings, deadlines, contacts and exact penetration.
Benchmark extractionBenchmark();

/// Frame time against pointshell size (10^4 … 10^7 points), coherent and brute force.
Benchmark scalingBenchmark();

/// Handle motion to pose at a front end, through a controller on loopback.
Benchmark latencyBenchmark();

/// A shared object's two instances through a simulated network: tracking error against
/// delay with and without the passivity controller, stability after release, bandwidth.
Benchmark sharingBenchmark();

/// Time against error: gap and force direction over analytic scenes, voxel sizes, bit
/// widths, geometrical awareness and coherence.
Benchmark errorBenchmark();

}  // namespace voxhap::cli

// `voxhap bench NAME`: the benchmarks of app/bench/, one subcommand each, with the
// output options they all share.

#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>

#include "app/bench/benchmark.h"
#include "app/cli/command.h"
#include "app/commands/commands.h"
#include "haptics/core/error.h"

namespace voxhap::cli {
namespace {

namespace fs = std::filesystem;

/// Every benchmark `voxhap bench` offers, in the order `--help` lists them.
std::vector<Benchmark> benchmarks() {
  return {table1Benchmark(), rotationBenchmark(), extractionBenchmark(), scalingBenchmark(),
          errorBenchmark(),  latencyBenchmark(),  sharingBenchmark()};
}

/// The output options every benchmark takes.
struct BenchOutput {
  bool json = false;
  std::optional<std::string> csv;
  std::optional<std::string> svg;
};

/// Throws voxhap::Error unless the folder `file` would be written in exists, so that a
/// long run is not lost to a typo in the output path.
void checkWritable(const std::string& option, const std::string& file) {
  const fs::path parent = fs::path(file).parent_path();
  std::error_code ec;
  if (!parent.empty() && !fs::is_directory(parent, ec)) {
    throw Error(file + ": cannot write --" + option + " here: no folder " + parent.string());
  }
}

int runBenchmark(const Benchmark& benchmark, const BenchRunFn& measure, const BenchOutput& output,
                 const CommandContext& c) {
  if (output.svg && !benchmark.plot) {
    throw UsageError("--svg: " + benchmark.name +
                     " is a table of figures with no curve to plot; use --csv or --json");
  }
  if (output.csv) checkWritable("csv", *output.csv);
  if (output.svg) checkWritable("svg", *output.svg);

  const BenchTable table = measure(c.console);

  if (output.csv) {
    std::ostringstream text;
    writeBenchCsv(text, table);
    writeTextFileAtomically(*output.csv, text.str());
  }
  if (output.svg) writeTextFileAtomically(*output.svg, svgPlot(table, *benchmark.plot));
  if (output.json) {
    c.out << benchJson(table).dump(2) << "\n";
  } else {
    writeBenchText(c.out, table);
  }
  return kExitOk;
}

void addBenchmark(CommandTree& tree, CLI::App& group, const Benchmark& benchmark) {
  CommandHelp help;
  help.summary = benchmark.summary;
  help.usage = "voxhap bench " + benchmark.name + (benchmark.usage.empty() ? "" : " " + benchmark.usage) +
               "\n       [--json] [--csv FILE]" + (benchmark.plot ? " [--svg FILE]" : "");
  help.description = benchmark.description;
  auto output = std::make_shared<BenchOutput>();
  auto measure = std::make_shared<BenchRunFn>();
  CLI::App& command =
      tree.add(group, benchmark.name, std::move(help), [benchmark, measure, output](const CommandContext& c) {
        return runBenchmark(benchmark, *measure, *output, c);
      });
  *measure = benchmark.addOptions(command);
  command.add_flag("--json", output->json, "print one JSON document {\"benchmark\", \"rows\", …} on stdout");
  command.add_option("--csv", output->csv, "also write the rows as CSV (header line of keys) to FILE")
      ->type_name("FILE");
  command
      .add_option("--svg", output->svg,
                  benchmark.plot ? "also plot the rows as an SVG picture in FILE"
                                 : "refused: " + benchmark.name + " has no curve to plot")
      ->type_name("FILE");
}

}  // namespace

void addBenchCommands(CommandTree& tree) {
  CommandHelp bench;
  bench.summary = "Run a benchmark of the paper (Table 1, …) and print its rows.";
  bench.usage = "voxhap bench NAME [OPTIONS] [--json] [--csv FILE]";
  bench.description =
      "Each benchmark prints an aligned table on stdout, or one JSON document with --json\n"
      "({\"benchmark\": NAME, \"rows\": [{…}, …], …}); --csv FILE also writes the rows as CSV with\n"
      "a header line, and --svg FILE plots them for benchmarks that have a curve. Timings\n"
      "depend on the machine and its load: run on a quiet one.\n\n"
      "Examples:\n"
      "  voxhap bench table1\n"
      "  voxhap bench table1 --quick --json\n"
      "  voxhap bench table1 --csv table1.csv";
  bench.subcommandNoun = "benchmark";
  CLI::App& group = tree.add(tree.root(), "bench", std::move(bench));
  for (const Benchmark& benchmark : benchmarks()) addBenchmark(tree, group, benchmark);
}

}  // namespace voxhap::cli

// `voxhap bench NAME`: the benchmarks of app/bench/, one subcommand each, with the
// output options they all share.

#include <filesystem>
#include <sstream>

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
          errorBenchmark()};
}

const OptionSpec kJsonOption{"json", 0, "", "print one JSON document {\"benchmark\", \"rows\", …} on stdout"};
const OptionSpec kCsvOption{"csv", 0, "FILE", "also write the rows as CSV (header line of keys) to FILE"};
const OptionSpec kSvgOption{"svg", 0, "FILE", "also plot the rows as an SVG picture in FILE"};

/// Throws voxhap::Error unless the folder `file` would be written in exists, so that a
/// long run is not lost to a typo in the output path.
void checkWritable(const std::string& option, const std::string& file) {
  const fs::path parent = fs::path(file).parent_path();
  std::error_code ec;
  if (!parent.empty() && !fs::is_directory(parent, ec)) {
    throw Error(file + ": cannot write --" + option + " here: no folder " + parent.string());
  }
}

int runBenchmark(const Benchmark& benchmark, const CommandContext& c) {
  const std::optional<std::string> csv = c.args.value(kCsvOption.longName);
  const std::optional<std::string> svg = c.args.value(kSvgOption.longName);
  if (svg && !benchmark.plot) {
    throw UsageError("bench " + benchmark.name + ": --svg: " + benchmark.name +
                     " is a table of figures with no curve to plot; use --csv or --json");
  }
  std::optional<SvgPlotSpec> plot;
  if (svg) plot = benchmark.plot(c.args);
  if (csv) checkWritable(kCsvOption.longName, *csv);
  if (svg) checkWritable(kSvgOption.longName, *svg);

  const BenchTable table = benchmark.run(BenchContext{c.args, c.console});

  if (csv) {
    std::ostringstream text;
    writeBenchCsv(text, table);
    writeTextFileAtomically(*csv, text.str());
  }
  if (svg) writeTextFileAtomically(*svg, svgPlot(table, *plot));
  if (c.args.has(kJsonOption.longName)) {
    c.out << benchJson(table).dump(2) << "\n";
  } else {
    writeBenchText(c.out, table);
  }
  return kExitOk;
}

Command commandOf(const Benchmark& benchmark) {
  Command command;
  command.name = benchmark.name;
  command.summary = benchmark.summary;
  command.usage = "voxhap bench " + benchmark.name + (benchmark.usage.empty() ? "" : " " + benchmark.usage) +
                  "\n       [--json] [--csv FILE]" + (benchmark.plot ? " [--svg FILE]" : "");
  command.description = benchmark.description;
  command.options = benchmark.options;
  command.options.push_back(kJsonOption);
  command.options.push_back(kCsvOption);
  OptionSpec svg = kSvgOption;
  if (!benchmark.plot) svg.help = "refused: " + benchmark.name + " has no curve to plot";
  command.options.push_back(svg);
  command.run = [benchmark](const CommandContext& c) { return runBenchmark(benchmark, c); };
  return command;
}

}  // namespace

Command benchCommand() {
  Command bench;
  bench.name = "bench";
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
  for (const Benchmark& benchmark : benchmarks()) bench.subcommands.push_back(commandOf(benchmark));
  return bench;
}

}  // namespace voxhap::cli

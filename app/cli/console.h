#pragma once
/// Where `voxhap` talks to the user: warnings, verbose notes and progress bars go
/// to stderr (bars only on a terminal); results go to stdout, as one JSON
/// document with `--json`.

#include <chrono>
#include <ostream>
#include <string>

#include "haptics/core/progress.h"

namespace voxhap::cli {

/// How much `voxhap` says on stderr: -q, default, -v.
enum class Verbosity { Quiet, Normal, Verbose };

class Console {
public:
  /// `err` is the diagnostic stream; `errIsTerminal` enables progress bars.
  Console(std::ostream& err, bool errIsTerminal, Verbosity verbosity = Verbosity::Normal)
      : err_(err), errIsTerminal_(errIsTerminal), verbosity_(verbosity) {}

  void setVerbosity(Verbosity verbosity) { verbosity_ = verbosity; }
  Verbosity verbosity() const { return verbosity_; }

  /// "voxhap: warning: …", unless quiet.
  void warning(const std::string& message);
  /// "voxhap: …", unless quiet: what a long-running command is doing.
  void info(const std::string& message);
  /// A note shown only with -v.
  void note(const std::string& message);
  /// "voxhap: error: …", always.
  void error(const std::string& message);

  /// A progress callback that draws `label [####    ] 42%` on a terminal, or nothing.
  /// The bar ends with a newline when the fraction reaches 1.
  ProgressFn progress(const std::string& label);

private:
  std::ostream& err_;
  bool errIsTerminal_;
  Verbosity verbosity_;
};

/// Seconds elapsed since `start`, for verbose notes and JSON timings.
double secondsSince(std::chrono::steady_clock::time_point start);

}  // namespace voxhap::cli

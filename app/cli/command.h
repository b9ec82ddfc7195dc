#pragma once
/// The `voxhap` command tree: each command has a name, help text, options and a
/// handler, or subcommands. Every command also takes -h/--help, -v/--verbose and
/// -q/--quiet. Exit status: 0 success, 1 failure (bad file, bad data), 2 usage error.

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "app/cli/args.h"
#include "app/cli/console.h"

namespace voxhap::cli {

/// Exit statuses of `voxhap`.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

/// What a handler gets: its arguments, stdout for results, the console for the rest.
struct CommandContext {
  const ParsedArgs& args;
  std::ostream& out;
  Console& console;
};

struct Command {
  std::string name;
  std::string summary;      ///< one line, shown in the parent's list
  std::string usage;        ///< e.g. "voxhap scene info SCENE [--json]"
  std::string description;  ///< paragraphs and examples for `--help`
  std::vector<OptionSpec> options;
  std::function<int(const CommandContext&)> run;  ///< empty for a group of subcommands
  std::vector<Command> subcommands;
  std::string subcommandNoun = "command";  ///< what a subcommand is called in help and errors
};

/// The whole command tree of `voxhap`.
Command voxhapCommands();

/// Runs `voxhap` with `args` (without the program name); returns the exit status.
/// Catches every error at this boundary and prints it as one line on `err`.
int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err, bool errIsTerminal);

}  // namespace voxhap::cli

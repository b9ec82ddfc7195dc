#pragma once
/// The `voxhap` command tree, on CLI11. Each command is a CLI::App with its help (usage,
/// one-line summary, a description with examples), typed options bound to the fields of
/// a struct its handler owns, and the handler; a group has subcommands instead. Every
/// command also takes -h/--help, -v/--verbose and -q/--quiet. Exit status: 0 success,
/// 1 failure (bad file, bad data), 2 usage mistake.
///
/// CommandTree::run parses the whole command line first (so every value is parsed and
/// checked, option_values.h), then runs the chosen command's handler. A usage mistake,
/// whether CLI11, an option's parser or a handler finds it, is one line on stderr naming
/// the command and the option, with "(see --help)".

#include <functional>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "app/cli/console.h"
#include "app/cli/option_values.h"

namespace CLI {
class App;
}  // namespace CLI

namespace voxhap::cli {

class HelpFormatter;

/// Exit statuses of `voxhap`.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

/// What a handler gets besides its own options: stdout for results, the console for the rest.
struct CommandContext {
  std::ostream& out;
  Console& console;
};

/// Runs a command with the options parsed into its fields; returns the exit status.
using CommandHandler = std::function<int(const CommandContext&)>;

/// What `--help` says about a command besides its options.
struct CommandHelp {
  std::string summary;      ///< one line, also shown in the parent's list
  std::string usage;        ///< e.g. "voxhap scene info SCENE [--json]"; empty: "PATH COMMAND [OPTIONS]"
  std::string description;  ///< paragraphs and examples
  std::string subcommandNoun = "command";  ///< what a group calls its subcommands in help and errors
};

/// The commands of `voxhap` as CLI::App objects, with their help and handlers. Not
/// copyable: the options hold pointers into the tree.
class CommandTree {
public:
  /// A tree of just the root command, `voxhap`.
  explicit CommandTree(CommandHelp rootHelp);
  ~CommandTree();
  CommandTree(const CommandTree&) = delete;
  CommandTree& operator=(const CommandTree&) = delete;

  CLI::App& root() { return *root_; }

  /// Adds the command `name` under `parent` (the root or a group) with -h, -v and -q, and
  /// returns it for its options. `run` is empty for a group, whose subcommands are added
  /// under it in the order its help lists them.
  CLI::App& add(CLI::App& parent, const std::string& name, CommandHelp help, CommandHandler run = {});

  /// The whole `--help` text of `command`.
  std::string helpText(const CLI::App& command) const;

  /// Parses `args` (without the program name) and runs the command they choose: prints
  /// help and returns 0 on -h/--help, prints help and returns 2 for a group given no
  /// subcommand. Throws UsageError (its message starting with the command's path) on a
  /// usage mistake; whatever the handler throws passes through. Once per tree.
  int run(const std::vector<std::string>& args, std::ostream& out, Console& console);

private:
  void addCommonFlags(CLI::App& command);
  /// The command the parsed words chose (so far, when parsing stopped at a mistake).
  const CLI::App& chosen() const;
  /// What is wrong with the words nothing took, for the UsageError.
  std::string extrasMistake(const CLI::App& command) const;

  std::unique_ptr<CLI::App> root_;
  std::shared_ptr<HelpFormatter> formatter_;            // holds every command's CommandHelp; shared by CLI11
  std::map<const CLI::App*, CommandHandler> handlers_;  // of the commands that are not groups
  const CLI::App* helpWanted_ = nullptr;                // the command whose -h/--help was given
  bool verbose_ = false;
  bool quiet_ = false;
};

/// `command`'s path from the root, e.g. "voxhap scene info".
std::string commandPath(const CLI::App& command);

/// The whole command tree of `voxhap`.
std::unique_ptr<CommandTree> voxhapCommands();

/// Runs `voxhap` with `args` (without the program name); returns the exit status.
/// Catches every error at this boundary and prints it as one line on `err`.
int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err, bool errIsTerminal);

}  // namespace voxhap::cli

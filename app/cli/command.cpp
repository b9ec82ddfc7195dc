#include "app/cli/command.h"

#include <cctype>
#include <new>
#include <sstream>

#include <CLI/CLI.hpp>

#include "app/commands/commands.h"
#include "haptics/core/error.h"

namespace voxhap::cli {

/// `--help` of a command: usage, summary, description with examples, the subcommands of a
/// group, then the arguments and options with their help (-h, -v and -q last).
class HelpFormatter : public CLI::Formatter {
public:
  HelpFormatter() { column_width(30); }

  void describe(const CLI::App& command, CommandHelp help) { help_[&command] = std::move(help); }
  const CommandHelp& helpOf(const CLI::App& command) const { return help_.at(&command); }

  std::string make_help(const CLI::App* command, std::string, CLI::AppFormatMode) const override {
    const CommandHelp& help = helpOf(*command);
    const std::string path = commandPath(*command);
    const std::vector<const CLI::App*> subcommands =
        command->get_subcommands([](const CLI::App*) { return true; });
    std::ostringstream s;
    s << "Usage: " << (help.usage.empty() ? path + " COMMAND [OPTIONS]" : help.usage) << "\n\n";
    s << help.summary << "\n";
    if (!help.description.empty()) s << "\n" << help.description << "\n";
    if (!subcommands.empty()) {
      std::string heading = help.subcommandNoun + "s";
      heading[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(heading[0])));
      s << "\n" << heading << ":\n";
      for (const CLI::App* sub : subcommands) {
        const std::string& name = sub->get_name();
        s << "  " << name << std::string(name.size() < 12 ? 12 - name.size() : 1, ' ')
          << sub->get_description() << "\n";
      }
      const std::string placeholder = help.subcommandNoun == "command" ? "COMMAND" : "NAME";
      s << "\nRun '" << path << " " << placeholder << " --help' for the options of one "
        << help.subcommandNoun << ".\n";
    }
    const auto positionals = command->get_options([](const CLI::Option* o) { return o->get_positional(); });
    if (!positionals.empty()) {
      s << "\nArguments:\n";
      for (const CLI::Option* o : positionals) s << make_option(o, true);
    }
    auto isCommon = [](const CLI::Option* o) {
      return o->check_lname("help") || o->check_lname("verbose") || o->check_lname("quiet");
    };
    s << "\nOptions:\n";
    for (const bool common : {false, true}) {
      for (const CLI::Option* o : command->get_options(
               [&](const CLI::Option* o) { return o->nonpositional() && isCommon(o) == common; })) {
        s << make_option(o, false);
      }
    }
    return s.str();
  }

  /// "-o, --output" or "    --json", so that long names line up.
  std::string make_option_name(const CLI::Option* o, bool positional) const override {
    if (positional) return o->get_name(true, false);
    std::string name;
    for (const std::string& s : o->get_snames()) name += "-" + s + ", ";
    if (name.empty()) name = "    ";
    for (std::size_t i = 0; i < o->get_lnames().size(); ++i) name += (i ? ", --" : "--") + o->get_lnames()[i];
    return name;
  }

  /// The value's name, e.g. " LENGTH"; nothing for flags and arguments (the help says
  /// what is required or repeatable).
  std::string make_option_opts(const CLI::Option* o) const override {
    if (o->get_positional() || o->get_type_size() == 0) return "";
    return " " + o->get_type_name();
  }

private:
  std::map<const CLI::App*, CommandHelp> help_;
};

namespace {

/// CLI11's message for a flag given a value ("json was given a disallowed flag override")
/// as "--json takes no value"; any other mismatch (a missing value) as CLI11 words it.
std::string mismatchMistake(const std::string& message) {
  const std::string override = " was given a disallowed flag override";
  if (message.size() <= override.size() ||
      message.compare(message.size() - override.size(), override.size(), override) != 0) {
    return message;
  }
  const std::string name = message.substr(0, message.size() - override.size());
  return (name.size() == 1 ? "-" : "--") + name + " takes no value";
}

}  // namespace

std::string commandPath(const CLI::App& command) {
  std::string path = command.get_name();
  for (const CLI::App* parent = command.get_parent(); parent; parent = parent->get_parent()) {
    path = parent->get_name() + " " + path;
  }
  return path;
}

CommandTree::CommandTree(CommandHelp rootHelp)
    : root_(std::make_unique<CLI::App>(rootHelp.summary, "voxhap")),
      formatter_(std::make_shared<HelpFormatter>()) {
  // every command copies these from its parent when it is added
  root_->formatter(formatter_);
  root_->set_help_flag();  // ours, addCommonFlags, answers before the values are checked
  root_->option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)->disable_flag_override();
  root_->require_subcommand(0, 1);
  addCommonFlags(*root_);
  formatter_->describe(*root_, std::move(rootHelp));
}

CommandTree::~CommandTree() = default;

void CommandTree::addCommonFlags(CLI::App& command) {
  const CLI::App* self = &command;
  command
      .add_flag_callback(
          "-h,--help",
          [this, self] {
            helpWanted_ = self;
            throw CLI::CallForHelp();
          },
          "show this help and exit")
      ->trigger_on_parse();
  command.add_flag("-v,--verbose", verbose_, "say more on stderr (timings, every warning)");
  command.add_flag("-q,--quiet", quiet_, "say nothing on stderr but errors");
}

CLI::App& CommandTree::add(CLI::App& parent, const std::string& name, CommandHelp help, CommandHandler run) {
  CLI::App* command = parent.add_subcommand(name, help.summary);
  addCommonFlags(*command);
  if (run) {
    handlers_[command] = std::move(run);
  } else {
    command->require_subcommand(0, 1);
  }
  formatter_->describe(*command, std::move(help));
  return *command;
}

std::string CommandTree::helpText(const CLI::App& command) const {
  return formatter_->make_help(&command, command.get_name(), CLI::AppFormatMode::Normal);
}

const CLI::App& CommandTree::chosen() const {
  const CLI::App* command = root_.get();
  while (!command->get_subcommands().empty()) command = command->get_subcommands().front();
  return *command;
}

std::string CommandTree::extrasMistake(const CLI::App& command) const {
  const std::vector<std::string> extras = root_->remaining(true);
  const std::string word = extras.empty() ? std::string() : extras.front();
  if (word.size() > 1 && word[0] == '-') return "unknown option '" + word.substr(0, word.find('=')) + "'";
  if (handlers_.count(&command)) {
    const bool takesArguments =
        !command.get_options([](const CLI::Option* o) { return o->get_positional(); }).empty();
    return takesArguments ? "unexpected argument '" + word + "'" : "takes no arguments, got '" + word + "'";
  }
  const std::string& noun = formatter_->helpOf(command).subcommandNoun;
  std::string names;
  for (const CLI::App* sub : command.get_subcommands([](const CLI::App*) { return true; })) {
    names += (names.empty() ? "" : ", ") + sub->get_name();
  }
  return "no " + noun + " '" + word + "' (" + noun + "s: " + names + ")";
}

int CommandTree::run(const std::vector<std::string>& args, std::ostream& out, Console& console) {
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // as CLI11 takes them
  try {
    root_->parse(reversed);
  } catch (const CLI::CallForHelp&) {
    out << helpText(helpWanted_ ? *helpWanted_ : chosen());
    return kExitOk;
  } catch (const CLI::ExtrasError&) {
    const CLI::App& command = chosen();
    if (!handlers_.count(&command) && root_->remaining(true) == std::vector<std::string>{"help"}) {
      out << helpText(command);  // `voxhap help`, `voxhap bench help`
      return kExitOk;
    }
    throw UsageError(commandPath(command) + ": " + extrasMistake(command));
  } catch (const CLI::ArgumentMismatch& e) {
    throw UsageError(commandPath(chosen()) + ": " + mismatchMistake(e.what()));
  } catch (const CLI::ParseError& e) {
    throw UsageError(commandPath(chosen()) + ": " + e.what());
  } catch (const UsageError& e) {  // a bad value, from option_values.h
    throw UsageError(commandPath(chosen()) + ": " + e.what());
  }
  if (quiet_) console.setVerbosity(Verbosity::Quiet);
  if (verbose_) console.setVerbosity(Verbosity::Verbose);

  const CLI::App& command = chosen();
  const auto handler = handlers_.find(&command);
  if (handler == handlers_.end()) {
    out << helpText(command);  // a group without its subcommand
    return kExitUsage;
  }
  try {
    return handler->second(CommandContext{out, console});
  } catch (const UsageError& e) {
    throw UsageError(commandPath(command) + ": " + e.what());
  }
}

std::unique_ptr<CommandTree> voxhapCommands() {
  CommandHelp help;
  help.summary = "Voxhap: collaborative voxel-based 6-DOF haptics (Voxmap PointShell) for CAD assemblies.";
  help.description =
      "Engineers at several sites grab parts of a CAD assembly (glTF) and feel them collide at\n"
      "1 kHz. SCENE arguments are a .gltf/.glb file or a built-in scene name:\n"
      "ball-and-socket, small-ball-and-socket (half the size: a 12.5 mm ball), peg-in-hole,\n"
      "landing-gear, landing-gear-crew (the gear with a spare actuator and hose, for three\n"
      "users; the gears are generated on first use and cached).\n\n"
      "Examples:\n"
      "  voxhap demo\n"
      "  voxhap bench table1\n"
      "  voxhap scene info assets/ball-and-socket.glb --json";
  auto tree = std::make_unique<CommandTree>(std::move(help));
  addSceneCommands(*tree);
  addVoxelizeCommand(*tree);
  addSimulateCommand(*tree);
  addBenchCommands(*tree);
  addDemoCommand(*tree);
  addExtractCommand(*tree);
  addControllerCommand(*tree);
  addViewCommand(*tree);
  addPeerCommand(*tree);
  addRelayCommand(*tree);
  return tree;
}

int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err, bool errIsTerminal) {
  Console console(err, errIsTerminal);
  try {
    return voxhapCommands()->run(args, out, console);
  } catch (const UsageError& e) {
    console.error(std::string(e.what()) + " (see --help)");
    return kExitUsage;
  } catch (const Error& e) {
    console.error(e.what());
    return kExitFailure;
  } catch (const std::bad_alloc&) {
    console.error("out of memory");
    return kExitFailure;
  } catch (const std::exception& e) {
    console.error(std::string("unexpected failure: ") + e.what());
    return kExitFailure;
  }
}

}  // namespace voxhap::cli

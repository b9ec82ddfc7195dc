#include "app/cli/command.h"

#include <cctype>
#include <new>
#include <sstream>

#include "app/commands/commands.h"
#include "haptics/core/error.h"

namespace voxhap::cli {
namespace {

const std::vector<OptionSpec>& commonOptions() {
  static const std::vector<OptionSpec> options = {
      {"help", 'h', "", "show this help and exit"},
      {"verbose", 'v', "", "say more on stderr (timings, every warning)"},
      {"quiet", 'q', "", "say nothing on stderr but errors"},
  };
  return options;
}

std::string helpText(const Command& command, const std::string& path) {
  std::ostringstream s;
  s << "Usage: " << (command.usage.empty() ? path + " COMMAND [OPTIONS]" : command.usage) << "\n\n";
  s << command.summary << "\n";
  if (!command.description.empty()) s << "\n" << command.description << "\n";
  if (!command.subcommands.empty()) {
    std::string heading = command.subcommandNoun + "s";
    heading[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(heading[0])));
    s << "\n" << heading << ":\n";
    for (const Command& sub : command.subcommands) {
      s << "  " << sub.name << std::string(sub.name.size() < 12 ? 12 - sub.name.size() : 1, ' ')
        << sub.summary << "\n";
    }
    std::string placeholder = command.subcommandNoun == "command" ? "COMMAND" : "NAME";
    s << "\nRun '" << path << " " << placeholder << " --help' for the options of one "
      << command.subcommandNoun << ".\n";
  }
  std::vector<OptionSpec> options = command.options;
  options.insert(options.end(), commonOptions().begin(), commonOptions().end());
  s << "\nOptions:\n";
  for (const OptionSpec& o : options) {
    std::string left = o.shortName ? std::string("-") + o.shortName + ", " : "    ";
    left += "--" + o.longName + (o.valueName.empty() ? "" : " " + o.valueName);
    s << "  " << left << std::string(left.size() < 26 ? 26 - left.size() : 1, ' ') << o.help << "\n";
  }
  return s.str();
}

int dispatch(const Command& command, const std::string& path, std::vector<std::string> args,
             std::ostream& out, Console& console) {
  if (!command.subcommands.empty()) {
    const bool wantsHelp = args.empty() || args[0] == "-h" || args[0] == "--help" || args[0] == "help";
    if (wantsHelp) {
      out << helpText(command, path);
      return args.empty() ? kExitUsage : kExitOk;
    }
    for (const Command& sub : command.subcommands) {
      if (sub.name == args[0]) {
        args.erase(args.begin());
        return dispatch(sub, path + " " + sub.name, std::move(args), out, console);
      }
    }
    std::string names;
    for (const Command& sub : command.subcommands) names += (names.empty() ? "" : ", ") + sub.name;
    throw UsageError("'" + path + "' has no " + command.subcommandNoun + " '" + args[0] + "' (" +
                     command.subcommandNoun + "s: " + names + ")");
  }
  std::vector<OptionSpec> options = command.options;
  options.insert(options.end(), commonOptions().begin(), commonOptions().end());
  ParsedArgs parsed;
  try {
    parsed = parseArgs(args, options);
  } catch (const UsageError& e) {
    throw UsageError(path + ": " + e.what());
  }
  if (parsed.has("help")) {
    out << helpText(command, path);
    return kExitOk;
  }
  if (parsed.has("quiet")) console.setVerbosity(Verbosity::Quiet);
  if (parsed.has("verbose")) console.setVerbosity(Verbosity::Verbose);
  return command.run(CommandContext{parsed, out, console});
}

}  // namespace

Command voxhapCommands() {
  Command root;
  root.name = "voxhap";
  root.summary = "Voxhap: collaborative voxel-based 6-DOF haptics (Voxmap PointShell) for CAD assemblies.";
  root.description =
      "Engineers at several sites grab parts of a CAD assembly (glTF) and feel them collide at\n"
      "1 kHz. SCENE arguments are a .gltf/.glb file or a built-in scene name:\n"
      "ball-and-socket, peg-in-hole, landing-gear (generated on first use and cached).\n\n"
      "Examples:\n"
      "  voxhap demo\n"
      "  voxhap bench table1\n"
      "  voxhap scene info assets/ball-and-socket.glb --json";
  root.subcommands = {sceneCommand(), voxelizeCommand(), simulateCommand(),
                      benchCommand(), demoCommand(),     controllerCommand()};
  return root;
}

int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err, bool errIsTerminal) {
  Console console(err, errIsTerminal);
  try {
    return dispatch(voxhapCommands(), "voxhap", args, out, console);
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

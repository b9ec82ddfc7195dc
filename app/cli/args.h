#pragma once
/// Command-line parsing for `voxhap` subcommands: long and short options, values
/// given as `--name value` or `--name=value`, repeatable options, `--` to end them.

#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace voxhap::cli {

/// A mistake in how the command was called; the CLI prints it with a hint to `--help`
/// and exits with status 2.
class UsageError : public std::runtime_error {
public:
  explicit UsageError(const std::string& message) : std::runtime_error(message) {}
};

/// One option a command accepts.
struct OptionSpec {
  std::string longName;   ///< without the leading "--"
  char shortName = 0;     ///< 0 when there is none
  std::string valueName;  ///< e.g. "FILE"; empty for a flag that takes no value
  std::string help;       ///< one line for `--help`
};

/// The options and positional arguments of one command line.
class ParsedArgs {
public:
  /// The flag or option was given at least once.
  bool has(const std::string& longName) const { return values_.count(longName) != 0; }
  /// The last value given for the option, if any.
  std::optional<std::string> value(const std::string& longName) const;
  /// Every value given for a repeatable option, in order.
  std::vector<std::string> values(const std::string& longName) const;

  std::vector<std::string> positionals;

private:
  friend ParsedArgs parseArgs(const std::vector<std::string>&, const std::vector<OptionSpec>&);
  std::map<std::string, std::vector<std::string>> values_;
};

/// Parses `args` (the words after the command's name) against `specs`.
/// Throws UsageError on an unknown option or a missing value.
ParsedArgs parseArgs(const std::vector<std::string>& args, const std::vector<OptionSpec>& specs);

/// Parses a whole unsigned decimal number for the option named in messages.
/// Throws UsageError on anything else (sign, fraction, junk, overflow).
std::uint64_t parseUnsigned(const std::string& text, const std::string& optionName);

/// Parses a size in bytes for the option named in messages: a decimal number, optionally
/// followed (spaces allowed) by B, KiB, MiB or GiB (also K, M, G; powers of 1024), e.g.
/// "2GiB", "512 MiB", "1.5G", "65536". Throws UsageError on anything else, on a size
/// below one byte or beyond 2^63.
std::uint64_t parseBytes(const std::string& text, const std::string& optionName);

/// Whether parseLengthM accepts zero and negative lengths.
enum class LengthSign { Positive, Any };

/// Parses a length in metres for the option named in messages: a decimal number,
/// optionally followed (spaces allowed) by "mm" or "m"; no unit means metres. So
/// "0.35mm", "2.5 mm", "0.00035m" and "0.00035" are all accepted. Throws UsageError
/// on anything else, on NaN or infinity, and on a length ≤ 0 unless `sign` is Any.
double parseLengthM(const std::string& text, const std::string& optionName,
                    LengthSign sign = LengthSign::Positive);

}  // namespace voxhap::cli

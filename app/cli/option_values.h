#pragma once
/// The values of `voxhap` options as the command line spells them (lengths in m or mm,
/// byte sizes, whole numbers, seconds), and the CLI11 options that parse them into typed
/// fields while the command line is parsed.
///
/// An option added here parses its text as CLI11 meets it, after the whole command line
/// has been read and before the command runs; a bad value throws UsageError naming the
/// option, which runCli (command.h) prints as a usage mistake. The field a setter writes
/// must outlive the CLI::App.

#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace voxhap::cli {

/// A mistake in how the command was called; the CLI prints it with a hint to `--help`
/// and exits with status 2.
class UsageError : public std::runtime_error {
public:
  explicit UsageError(const std::string& message) : std::runtime_error(message) {}
};

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

/// Parses a duration in seconds for the option named in messages: a decimal number,
/// optionally followed (spaces allowed) by "s" or "ms", finite and ≥ 0; "2.5", "2.5s"
/// and "2500ms" are the same. Throws UsageError on anything else.
double parseSeconds(const std::string& text, const std::string& optionName);

/// Parses a share from 0 to 1 for the option named in messages: a decimal number, or a
/// percentage with "%" ("0.05" and "5%" are the same). Throws UsageError on anything else.
double parseFraction(const std::string& text, const std::string& optionName);

/// Turns the text of one value into its field; throws UsageError on a bad value.
using SetFromText = std::function<void(const std::string& text)>;

/// Adds `name` (e.g. "--capacity") to `app`, taking one value shown as `valueName` in
/// --help; `set` gets the value (the last one when the option is given again).
CLI::Option* addParsedOption(CLI::App& app, const std::string& name, const std::string& valueName,
                             const std::string& help, SetFromText set);

/// Adds a repeatable `name` to `app`: each occurrence takes exactly one value (the words
/// after it stay positionals), and `add` gets every value in order.
CLI::Option* addRepeatedOption(CLI::App& app, const std::string& name, const std::string& valueName,
                               const std::string& help, SetFromText add);

/// `name LENGTH` parsed by parseLengthM into `metres`.
CLI::Option* addLengthOption(CLI::App& app, const std::string& name, std::optional<double>& metres,
                             const std::string& help, LengthSign sign = LengthSign::Positive);

/// A repeatable `name LENGTH`, every value parsed by parseLengthM (positive) into `metres`.
CLI::Option* addLengthListOption(CLI::App& app, const std::string& name, std::vector<double>& metres,
                                 const std::string& help);

/// `name N` parsed by parseUnsigned into `value`.
CLI::Option* addUnsignedOption(CLI::App& app, const std::string& name, std::optional<std::uint64_t>& value,
                               const std::string& help);

/// `name N` parsed by parseUnsigned into `value`, which keeps its default when not given.
CLI::Option* addUnsignedOption(CLI::App& app, const std::string& name, std::uint64_t& value,
                               const std::string& help);

}  // namespace voxhap::cli

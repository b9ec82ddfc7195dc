#include "app/cli/args.h"

#include <charconv>
#include <cmath>

namespace voxhap::cli {

std::optional<std::string> ParsedArgs::value(const std::string& longName) const {
  const auto found = values_.find(longName);
  if (found == values_.end() || found->second.empty()) return std::nullopt;
  return found->second.back();
}

std::vector<std::string> ParsedArgs::values(const std::string& longName) const {
  const auto found = values_.find(longName);
  return found == values_.end() ? std::vector<std::string>{} : found->second;
}

ParsedArgs parseArgs(const std::vector<std::string>& args, const std::vector<OptionSpec>& specs) {
  ParsedArgs parsed;
  auto findLong = [&](const std::string& name) -> const OptionSpec* {
    for (const OptionSpec& s : specs) {
      if (s.longName == name) return &s;
    }
    return nullptr;
  };
  auto findShort = [&](char name) -> const OptionSpec* {
    for (const OptionSpec& s : specs) {
      if (s.shortName != 0 && s.shortName == name) return &s;
    }
    return nullptr;
  };

  bool optionsEnded = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& word = args[i];
    if (optionsEnded || word.size() < 2 || word[0] != '-') {
      parsed.positionals.push_back(word);
      continue;
    }
    if (word == "--") {
      optionsEnded = true;
      continue;
    }
    const OptionSpec* spec = nullptr;
    std::optional<std::string> inlineValue;
    std::string shown = word;
    if (word.rfind("--", 0) == 0) {
      const std::size_t equals = word.find('=');
      const std::string name = word.substr(2, equals == std::string::npos ? std::string::npos : equals - 2);
      if (equals != std::string::npos) inlineValue = word.substr(equals + 1);
      spec = findLong(name);
      shown = "--" + name;
    } else if (word.size() == 2) {
      spec = findShort(word[1]);
    }
    if (!spec) throw UsageError("unknown option '" + shown + "'");
    std::vector<std::string>& slot = parsed.values_[spec->longName];
    if (spec->valueName.empty()) {
      if (inlineValue) throw UsageError(shown + " takes no value");
      slot.emplace_back();
    } else if (inlineValue) {
      slot.push_back(*inlineValue);
    } else if (i + 1 < args.size()) {
      slot.push_back(args[++i]);
    } else {
      throw UsageError(shown + " needs a value (" + spec->valueName + ")");
    }
  }
  return parsed;
}

std::uint64_t parseUnsigned(const std::string& text, const std::string& optionName) {
  std::uint64_t value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end) {
    throw UsageError("--" + optionName + " wants a whole number from 0 to 18446744073709551615, not '" +
                     text + "'");
  }
  return value;
}

std::uint64_t parseBytes(const std::string& text, const std::string& optionName) {
  auto fail = [&]() -> std::uint64_t {
    throw UsageError("--" + optionName + " wants a size such as 2GiB, 512MiB or 65536 (bytes), not '" + text +
                     "'");
  };
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc()) return fail();
  std::string unit(ptr, end);
  unit.erase(0, unit.find_first_not_of(' '));
  double scale = 0.0;
  if (unit.empty() || unit == "B") scale = 1.0;
  if (unit == "K" || unit == "KiB") scale = 1024.0;
  if (unit == "M" || unit == "MiB") scale = 1024.0 * 1024.0;
  if (unit == "G" || unit == "GiB") scale = 1024.0 * 1024.0 * 1024.0;
  const double bytes = value * scale;
  if (!(bytes >= 1.0) || !(bytes < 9.2e18)) return fail();
  return static_cast<std::uint64_t>(bytes);
}

double parseLengthM(const std::string& text, const std::string& optionName, LengthSign sign) {
  const std::string example =
      sign == LengthSign::Positive ? "0.35mm, 2.5 mm or 0.00035 (metres)" : "0.012, 12mm or -3.5 mm";
  auto fail = [&](const std::string& why) -> double {
    throw UsageError("--" + optionName + " wants " + why + " such as " + example + ", not '" + text + "'");
  };
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc()) return fail("a length");
  std::string unit(ptr, end);
  unit.erase(0, unit.find_first_not_of(' '));
  double scale = 1.0;
  if (unit == "mm") {
    scale = 1e-3;
  } else if (unit != "m" && !unit.empty()) {
    return fail("a length in m or mm");
  }
  value *= scale;
  if (!std::isfinite(value)) return fail("a finite length");
  if (sign == LengthSign::Positive && !(value > 0.0)) return fail("a positive length");
  return value;
}

}  // namespace voxhap::cli

#include "app/cli/option_values.h"

#include <charconv>
#include <cmath>
#include <optional>
#include <utility>

#include <CLI/CLI.hpp>

namespace voxhap::cli {

namespace {

/// The decimal number `text` starts with and what follows it, leading spaces dropped (its
/// unit); none when it does not start with a number.
std::optional<std::pair<double, std::string>> numberAndUnit(const std::string& text) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc()) return std::nullopt;
  std::string unit(ptr, end);
  unit.erase(0, unit.find_first_not_of(' '));
  return std::pair{value, unit};
}

}  // namespace

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
  const auto parsed = numberAndUnit(text);
  if (!parsed) return fail();
  auto [value, unit] = *parsed;
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
  const auto parsed = numberAndUnit(text);
  if (!parsed) return fail("a length");
  auto [value, unit] = *parsed;
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

double parseSeconds(const std::string& text, const std::string& optionName) {
  auto fail = [&]() -> double {
    throw UsageError("--" + optionName + " wants a time ≥ 0 such as 2.5, 2.5s or 100ms, not '" + text + "'");
  };
  const auto parsed = numberAndUnit(text);
  if (!parsed) return fail();
  auto [value, unit] = *parsed;
  if (unit == "ms") {
    value *= 1e-3;
  } else if (unit != "s" && !unit.empty()) {
    return fail();
  }
  if (!(value >= 0.0) || !std::isfinite(value)) return fail();
  return value;
}

double parseFraction(const std::string& text, const std::string& optionName) {
  auto fail = [&]() -> double {
    throw UsageError("--" + optionName + " wants a share from 0 to 1 such as 0.05 or 5%, not '" + text + "'");
  };
  const auto parsed = numberAndUnit(text);
  if (!parsed) return fail();
  auto [value, unit] = *parsed;
  if (unit == "%") {
    value *= 0.01;
  } else if (!unit.empty()) {
    return fail();
  }
  if (!(value >= 0.0 && value <= 1.0)) return fail();
  return value;
}

namespace {

/// "--voxel-size" → "voxel-size", as the parse functions name options.
std::string bareName(const std::string& name) {
  return name.substr(name.find_first_not_of('-'));
}

}  // namespace

CLI::Option* addParsedOption(CLI::App& app, const std::string& name, const std::string& valueName,
                             const std::string& help, SetFromText set) {
  return app.add_option_function<std::string>(name, std::move(set), help)
      ->type_name(valueName)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
}

CLI::Option* addRepeatedOption(CLI::App& app, const std::string& name, const std::string& valueName,
                               const std::string& help, SetFromText add) {
  auto addEach = [add = std::move(add)](const std::vector<std::string>& texts) {
    for (const std::string& text : texts) add(text);
  };
  return app.add_option_function<std::vector<std::string>>(name, addEach, help)
      ->type_name(valueName)
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

CLI::Option* addLengthOption(CLI::App& app, const std::string& name, std::optional<double>& metres,
                             const std::string& help, LengthSign sign) {
  return addParsedOption(app, name, "LENGTH", help,
                         [&metres, bare = bareName(name), sign](const std::string& text) {
                           metres = parseLengthM(text, bare, sign);
                         });
}

CLI::Option* addLengthListOption(CLI::App& app, const std::string& name, std::vector<double>& metres,
                                 const std::string& help) {
  return addRepeatedOption(app, name, "LENGTH", help,
                           [&metres, bare = bareName(name)](const std::string& text) {
                             metres.push_back(parseLengthM(text, bare));
                           });
}

CLI::Option* addUnsignedOption(CLI::App& app, const std::string& name, std::optional<std::uint64_t>& value,
                               const std::string& help) {
  return addParsedOption(app, name, "N", help, [&value, bare = bareName(name)](const std::string& text) {
    value = parseUnsigned(text, bare);
  });
}

CLI::Option* addUnsignedOption(CLI::App& app, const std::string& name, std::uint64_t& value,
                               const std::string& help) {
  return addParsedOption(app, name, "N", help, [&value, bare = bareName(name)](const std::string& text) {
    value = parseUnsigned(text, bare);
  });
}

}  // namespace voxhap::cli

#include "app/cli/console.h"

#include <memory>

namespace voxhap::cli {

void Console::warning(const std::string& message) {
  if (verbosity_ != Verbosity::Quiet) err_ << "voxhap: warning: " << message << '\n';
}

void Console::info(const std::string& message) {
  if (verbosity_ != Verbosity::Quiet) err_ << "voxhap: " << message << std::endl;
}

void Console::note(const std::string& message) {
  if (verbosity_ == Verbosity::Verbose) err_ << "voxhap: " << message << '\n';
}

void Console::error(const std::string& message) {
  err_ << "voxhap: error: " << message << std::endl;
}

ProgressFn Console::progress(const std::string& label) {
  if (!errIsTerminal_ || verbosity_ == Verbosity::Quiet) return {};
  constexpr int kBarWidth = 30;
  auto lastPercent = std::make_shared<int>(-1);
  return [this, label, lastPercent](double fractionDone) {
    const double f = fractionDone < 0.0 ? 0.0 : (fractionDone > 1.0 ? 1.0 : fractionDone);
    const int percent = static_cast<int>(f * 100.0);
    if (percent == *lastPercent) return;
    *lastPercent = percent;
    const int filled = static_cast<int>(f * kBarWidth);
    err_ << '\r' << label << " [" << std::string(static_cast<std::size_t>(filled), '#')
         << std::string(static_cast<std::size_t>(kBarWidth - filled), ' ') << "] " << percent << '%';
    if (percent == 100) err_ << '\n';
    err_.flush();
  };
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace voxhap::cli

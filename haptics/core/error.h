#pragma once
/// Load- and set-up-time errors of the engine (the third tier of CONVENTIONS).
///
/// The engine never prints: it throws `voxhap::Error` with a one-line message that
/// names the file, object or field, and the command boundary in `app/` prints it.
/// Nothing in the 1 kHz frame throws.

#include <stdexcept>
#include <string>

namespace voxhap {

/// A set-up error with a one-line, user-facing message (no trailing newline).
class Error : public std::runtime_error {
public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace voxhap

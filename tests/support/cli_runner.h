#pragma once
/// Test support: runs the real `voxhap` executable in a private folder with a private
/// cache folder, and captures its exit status, stdout and stderr.

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace voxhap::test {

/// What one run of `voxhap` did.
struct CliRun {
  int exitCode;
  std::string out;
  std::string err;
};

/// The bytes of a file (empty when it cannot be read).
std::string slurp(const std::filesystem::path& file);

/// Number of lines (newlines) in `text`.
int lineCount(const std::string& text);

/// A fixture with a fresh folder per test (removed afterwards) in which voxhap runs.
class CliTest : public ::testing::Test {
protected:
  void SetUp() override;
  void TearDown() override;

  /// Runs voxhap with `args` in dir_, with VOXHAP_CACHE_DIR=dir_/cache; stdin is empty.
  /// `launcher`: a program and its arguments that run it (e.g. xvfb-run -a).
  CliRun voxhap(const std::vector<std::string>& args, const std::vector<std::string>& launcher = {}) const;

  /// The path of a committed asset, e.g. asset("ball-and-socket.glb").
  static std::string asset(const std::string& name);

  std::filesystem::path dir_;
};

}  // namespace voxhap::test

#include "support/cli_runner.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

namespace voxhap::test {
namespace {

namespace fs = std::filesystem;

std::string shellQuote(const std::string& s) {
  std::string q(1, '\'');
  for (char c : s) {
    if (c == '\'') {
      q.append("'\\''");
    } else {
      q.push_back(c);
    }
  }
  q.push_back('\'');
  return q;
}

}  // namespace

std::string slurp(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

int lineCount(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

void CliTest::SetUp() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  dir_ = fs::temp_directory_path() /
         ("voxhap-cli-" + std::string(info->name()) + "-" + std::to_string(::getpid()));
  fs::remove_all(dir_);
  fs::create_directories(dir_);
}

void CliTest::TearDown() {
  fs::remove_all(dir_);
}

CliRun CliTest::voxhap(const std::vector<std::string>& args, const std::vector<std::string>& launcher) const {
  std::string command =
      "cd " + shellQuote(dir_.string()) + " && VOXHAP_CACHE_DIR=" + shellQuote((dir_ / "cache").string());
  for (const std::string& a : launcher) {
    command.push_back(' ');
    command.append(shellQuote(a));
  }
  command.push_back(' ');
  command.append(shellQuote(VOXHAP_EXE));
  for (const std::string& a : args) {
    command.push_back(' ');
    command.append(shellQuote(a));
  }
  command += " </dev/null >out.txt 2>err.txt";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir_ / "out.txt"), slurp(dir_ / "err.txt")};
}

std::string CliTest::asset(const std::string& name) {
  return (fs::path(VOXHAP_SOURCE_DIR) / "assets" / name).string();
}

}  // namespace voxhap::test

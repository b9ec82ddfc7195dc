#include "support/child_process.h"

#include <csignal>
#include <stdexcept>
#include <thread>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "support/cli_runner.h"

namespace voxhap::test {

ChildProcess::ChildProcess(const std::string& program, const std::vector<std::string>& args,
                           const std::filesystem::path& dir, const std::string& name)
    : outFile_(dir / (name + "-out.txt")), errFile_(dir / (name + "-err.txt")) {
  std::vector<std::string> argv = {program};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> cargs;
  for (std::string& a : argv) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  std::vector<std::string> env = {"VOXHAP_CACHE_DIR=" + (dir / "cache").string()};
  for (char** e = environ; *e != nullptr; ++e) {
    if (std::string(*e).rfind("VOXHAP_CACHE_DIR=", 0) != 0) env.emplace_back(*e);
  }
  std::vector<char*> cenv;
  for (std::string& e : env) cenv.push_back(e.data());
  cenv.push_back(nullptr);
  pid_ = ::fork();
  if (pid_ < 0) throw std::runtime_error("fork failed");
  if (pid_ == 0) {
    // the child: only async-signal-safe calls until exec
    const int in = ::open("/dev/null", O_RDONLY);
    const int out = ::open(outFile_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open(errFile_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    // a process group of its own, so that a test that gives up kills what it started too
    // (xvfb-run's X server and the commands it runs)
    if (in < 0 || out < 0 || err < 0 || ::chdir(dir.c_str()) != 0 || ::setpgid(0, 0) != 0) ::_exit(127);
    ::dup2(in, 0);
    ::dup2(out, 1);
    ::dup2(err, 2);
    ::execve(program.c_str(), cargs.data(), cenv.data());
    ::_exit(127);
  }
  ::setpgid(pid_, pid_);  // the child does it too: whichever runs first
}

ChildProcess::~ChildProcess() {
  if (!status_) {
    ::kill(-pid_, SIGKILL);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
}

std::optional<std::string> ChildProcess::waitForStderr(const std::string& prefix,
                                                       std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    const std::string text = err();
    const std::size_t at = text.find(prefix);
    if (at != std::string::npos) {
      const std::size_t from = at + prefix.size();
      const std::size_t end = text.find('\n', from);
      if (end != std::string::npos) return text.substr(from, end - from);
    }
    if (std::chrono::steady_clock::now() >= deadline || wait(std::chrono::milliseconds(0)))
      return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

void ChildProcess::signal(int signal) {
  if (!status_) ::kill(pid_, signal);
}

std::optional<int> ChildProcess::wait(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!status_) {
    int status = 0;
    const pid_t r = ::waitpid(pid_, &status, WNOHANG);
    if (r == pid_) {
      status_ = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      break;
    }
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return status_;
}

std::string ChildProcess::out() const {
  return slurp(outFile_);
}
std::string ChildProcess::err() const {
  return slurp(errFile_);
}

}  // namespace voxhap::test

#pragma once
/// Test support: a real child process (the `voxhap` executable) running beside the test,
/// with its stdout and stderr going to files the test reads while it runs, so that a
/// test can wait for a line (the controller's listening address), talk to it over
/// loopback, signal it and collect its exit status. Every wait is bounded.

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <sys/types.h>

namespace voxhap::test {

class ChildProcess {
public:
  /// Starts `program` with `args` in `dir`, stdin empty, stdout and stderr to files there
  /// named after `name` (several children in one directory need different names).
  ChildProcess(const std::string& program, const std::vector<std::string>& args,
               const std::filesystem::path& dir, const std::string& name = "child");
  /// Kills it and every process of its group (SIGKILL) when it is still running: it starts a
  /// group of its own.
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  /// Waits up to `timeout` for stderr to hold `prefix`; returns what follows it up to the
  /// end of its line, none when time ran out or the process ended first. (No std::regex:
  /// GCC 12's <regex> warns falsely under ASan's -O1.)
  std::optional<std::string> waitForStderr(const std::string& prefix, std::chrono::milliseconds timeout);
  /// Sends `signal`.
  void signal(int signal);
  /// Waits up to `timeout` for it to end; its exit status, or -1 for a signal, none when
  /// it is still running.
  std::optional<int> wait(std::chrono::milliseconds timeout);

  std::string out() const;
  std::string err() const;

private:
  pid_t pid_ = -1;
  std::optional<int> status_;
  std::filesystem::path outFile_;
  std::filesystem::path errFile_;
};

}  // namespace voxhap::test

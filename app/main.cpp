#include <iostream>
#include <string>
#include <vector>

#include <unistd.h>

#include "app/cli/command.h"

int main(int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  const std::vector<std::string> args(argv + 1, argv + argc);
  return voxhap::cli::runCli(args, std::cout, std::cerr, isatty(STDERR_FILENO) == 1);
}

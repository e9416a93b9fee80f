// Shared by the CLI tests: run the `plumage` executable (PLUMAGE_EXE, set by CMake) or any shell
// command and capture its output (stdout and stderr together) and exit status.
#pragma once

#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace plumage::cli_test {

struct Result {
  int status = -1;
  std::string output;  // stdout and stderr together
};

inline Result run_command(const std::string& command) {
  Result r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  REQUIRE(pipe != nullptr);
  char buffer[4096];
  while (std::size_t n = fread(buffer, 1, sizeof buffer, pipe)) r.output.append(buffer, n);
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// `plumage <args>`.
inline Result run(const std::string& args) { return run_command(std::string(PLUMAGE_EXE) + " " + args); }

}  // namespace plumage::cli_test

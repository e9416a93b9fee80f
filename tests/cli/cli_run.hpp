// Shared by the CLI tests: run the `plumage` executable (PLUMAGE_EXE, set by CMake) or any shell
// command and capture its output (stdout and stderr together) and exit status.
#pragma once

#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
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

// The scratch folder of one CLI test suite under the system's temporary directory (created).
inline std::filesystem::path scratch_dir(const std::string& suite) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / suite;
  std::filesystem::create_directories(dir);
  return dir;
}

// A fresh, not yet existing folder `name` inside a suite's scratch folder (earlier runs removed),
// for commands that create their output folder themselves.
inline std::filesystem::path fresh_scratch_path(const std::string& suite, const std::string& name) {
  const std::filesystem::path dir = scratch_dir(suite) / name;
  std::filesystem::remove_all(dir);
  return dir;
}

// A fresh, empty folder `name` inside a suite's scratch folder (earlier runs removed, created).
inline std::filesystem::path fresh_scratch_dir(const std::string& suite, const std::string& name) {
  const std::filesystem::path dir = fresh_scratch_path(suite, name);
  std::filesystem::create_directories(dir);
  return dir;
}

// A file's bytes ("" when it cannot be read).
inline std::string file_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace plumage::cli_test

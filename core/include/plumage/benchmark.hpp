// Extension point: a backend's speed benchmark (issue 22). `plumage bench <type>` creates the
// registered benchmark of that type with its parameters from the command line (one flag per row
// of its parameter table: --width-um 5,10 sets width_um: [5, 10]) and runs it; --record FILE puts
// the report into that section of docs/benchmarks.md (bench_record.hpp). Benchmarks measure: they
// never pass or fail. Each backend ships its own beside itself, as it ships its accuracy ladder,
// so the command names no backend.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include "plumage/local_reflection.hpp"
#include "plumage/plugin.hpp"

namespace plumage {

class Benchmark : public PluginObject {
 public:
  static constexpr std::string_view plugin_kind = "benchmark";

  struct Options {
    std::string command;                             // as typed, for the record's "command" column
    std::function<void(std::string_view)> progress;  // status lines while it runs; may be empty
    std::filesystem::path record;  // where the report will be recorded (empty: nowhere), for relative links
    // How the preparation step of a benchmarked species may run (the command's --tables); done
    // before anything is timed.
    PreparationOptions preparation;
  };
  struct Report {
    std::string id;        // its section in docs/benchmarks.md, e.g. "bem"
    std::string markdown;  // what was measured and a table with machine, command, date and load
  };

  virtual Report run(const Options& options) const = 0;
};

}  // namespace plumage

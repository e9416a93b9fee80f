#include "app_context.hpp"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>

#include "plumage/atomic_file.hpp"
#include "plumage/builtin_plugins.hpp"
#include "plumage/memory_budget.hpp"
#include "progress.hpp"

namespace plumage::cli {

void check_output_flag(std::string_view flag, const std::string& path, const std::vector<std::string>& inputs,
                       std::string_view role) {
  if (path.empty()) return;
  check_output_path(path, flag);
  for (const std::string& input : inputs) check_output_not_input(path, flag, input, role);
}

void check_output_folder_flag(std::string_view flag, const std::string& path) { check_output_directory(path, flag); }

std::string material_warnings_report(const std::string& warnings) {
  if (warnings.empty()) return {};
  std::string out = "the material's warnings (stored in it):\n";
  std::istringstream in(warnings);
  for (std::string line; std::getline(in, line);) out += "  " + line + "\n";
  return out;
}

const PluginRegistry& AppContext::registry() {
  if (!registry_) {
    registry_ = std::make_unique<PluginRegistry>();
    register_builtin_plugins(*registry_);
    registry_->load_search_path(PluginRegistry::search_path(plugin_dirs));
  }
  return *registry_;
}

PreparationOptions AppContext::preparation() const {
  PreparationOptions options;
  options.tables = tables == "preview" ? PreparationOptions::Tables::preview
                   : tables == "never" ? PreparationOptions::Tables::never
                                       : PreparationOptions::Tables::build;
  if (quiet) return options;
  // A status line for total 0, else one progress bar per kind of work.
  struct Bar {
    std::string what;
    std::unique_ptr<Progress> progress;
  };
  options.progress = [bar = std::make_shared<Bar>()](std::size_t done, std::size_t total, std::string_view what) {
    if (total == 0) {
      std::cerr << what << "\n";
      return;
    }
    if (!bar->progress || bar->what != what) {
      bar->what = std::string(what);
      bar->progress = std::make_unique<Progress>(bar->what, total, false);
    }
    bar->progress->advance(done);
  };
  return options;
}

namespace {
// Prints report_step() lines: a status step (total 0) once; of a counted step the first and last
// line and at most one every 10 s between, with the elapsed time and the ETA from the mean rate.
class StepPrinter {
 public:
  void operator()(std::string_view step, double done, double total, std::string_view detail) {
    using clock = std::chrono::steady_clock;
    std::lock_guard lock(mutex_);
    const auto now = clock::now();
    // A status line (no total: "bem: dense LU (...)") is printed once per process: parallel
    // solves of many instances repeat it, and it says only which step runs.
    if (total <= 0) {
      if (!status_.emplace(step).second) return;
      std::cerr << step << (detail.empty() ? "" : ": ") << detail << "\n";
      return;
    }
    auto [it, first] = steps_.try_emplace(std::string(step), State{now, now});
    const double elapsed = std::chrono::duration<double>(now - it->second.start).count();
    const bool last = total > 0 && done >= total;
    if (!first && !last && std::chrono::duration<double>(now - it->second.printed).count() < 10.0) return;
    it->second.printed = now;
    std::string line = std::string(step);
    char buf[160];
    if (total > 0) {
      std::snprintf(buf, sizeof buf, " %.0f/%.0f", done, total);
      line += buf;
    }
    if (!detail.empty()) line += ": " + std::string(detail);
    std::snprintf(buf, sizeof buf, ", %.0f s", elapsed);
    line += buf;
    if (total > 0 && done > 0 && !last) {
      std::snprintf(buf, sizeof buf, ", ETA %.0f s", elapsed * (total - done) / done);
      line += buf;
    }
    std::cerr << line << "\n";
    if (last) steps_.erase(it);
  }

 private:
  struct State {
    std::chrono::steady_clock::time_point start, printed;
  };
  std::mutex mutex_;
  std::map<std::string, State, std::less<>> steps_;
  std::set<std::string, std::less<>> status_;
};
}  // namespace

void AppContext::apply_budget_and_progress() const {
  if (!max_memory.empty()) {
    try {
      set_memory_limit(parse_memory_size(max_memory), "--max-memory " + max_memory);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--max-memory: ") + e.what());
    }
  }
  if (quiet) {
    set_step_progress_sink({});
  } else {
    auto printer = std::make_shared<StepPrinter>();
    set_step_progress_sink([printer](std::string_view step, double done, double total, std::string_view detail) {
      (*printer)(step, done, total, detail);
    });
  }
}

void AppContext::warn_about_problems() const {
  if (!registry_ || quiet) return;
  for (const auto& p : registry_->problems()) std::cerr << "warning: " << p.message << "\n";
}

}  // namespace plumage::cli

// Memory and work budgets (issue 23 Deliver 2): every solver and builder estimates its peak memory
// BEFORE it allocates, and refuses a job that would not fit with MemoryBudgetError (exit status 2)
// naming the estimate, the memory available and the options that lower it — instead of being
// killed by the kernel after minutes (`bench bem` at 24 GB) or dying in std::bad_alloc.
//
// The memory available is the process's limit (set_memory_limit: `plumage --max-memory 8GiB`, or a
// plug-in section's `max_memory` key) or, by default, what the machine has: MemAvailable from
// /proc/meminfo and any cgroup v2 (memory.max − memory.current) or v1 (memory.limit_in_bytes −
// memory.usage_in_bytes) limit, whichever is smallest.
//
// Estimates are plain functions of a job's parameters that each plug-in or stage exposes (so that
// `plumage check` can call the same ones as the run); they are upper bounds, validated against
// measured peak RSS in docs/benchmarks.md ("Memory estimates").
//
// Step progress: long steps inside the library (a BEM factorisation, GMRES, a compare method)
// report through report_step(); the CLI installs the sink that prints (nothing with -q).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/error.hpp"

namespace plumage {

// "8GiB", "512 MiB", "2GB", "1.5G", "4096k", "1e9" (bytes): binary suffixes K/M/G/T (with or
// without "iB") are powers of 1024, decimal "kB/MB/GB/TB" powers of 1000. Throws
// std::invalid_argument naming the text for anything else (negative, zero, NaN, unknown unit).
std::uint64_t parse_memory_size(std::string_view text);

// "1.50 GiB", "312 MiB", "24.0 KiB", "512 B".
std::string format_bytes(double bytes);

struct MemoryAvailability {
  std::uint64_t bytes = 0;
  std::string source;  // "MemAvailable (/proc/meminfo)", "cgroup v2 memory.max", "--max-memory", ...
};

// What the machine offers now: the smallest of MemAvailable and the cgroup's remaining limit.
MemoryAvailability machine_memory_available();

// This process's resident set now (/proc/self/statm; 0 where there is none).
std::uint64_t resident_bytes();

// The process's budget: a limit set with set_memory_limit() less what the process already holds
// (resident_bytes(): the limit bounds the whole process), else machine_memory_available().
MemoryAvailability memory_available();
void set_memory_limit(std::uint64_t bytes, std::string source);
void clear_memory_limit();

// The budget for one job: `configured` (a config key's text, "" = none; a whole-process limit like
// --max-memory, less what is resident) if set, else the process's.
// Throws std::invalid_argument for unparsable text (a table's key is checked when it is read).
MemoryAvailability memory_available(std::string_view configured);

// A job's peak memory, in named parts ("dense matrix 16 N^2", "Krylov basis"...), with the options
// that lower it ("points_per_wavelength (now 30)", "method: hmatrix").
struct MemoryEstimate {
  std::string job;  // "bem hmatrix solve of 211 464 unknowns at 550 nm"
  struct Part {
    std::string name;
    double bytes = 0;
  };
  std::vector<Part> parts;
  std::vector<std::string> lower_with;

  MemoryEstimate& add(std::string name, double bytes);
  double total_bytes() const;
  // "bem ...: estimated 24.1 GiB (near field 5.0 GiB, LU fill 12 GiB, ...)"
  std::string describe() const;
};

// A job over its budget: exit status 2 (bad input: a job the machine cannot hold), refused before
// any work. what() names the estimate, its parts, the memory available and what lowers it.
class MemoryBudgetError : public Error {
 public:
  MemoryBudgetError(MemoryEstimate estimate, MemoryAvailability available);
  // A job whose work (unit count, time) is absurd: `what` names the count and the options.
  explicit MemoryBudgetError(std::string message);
  const std::optional<MemoryEstimate>& estimate() const { return estimate_; }

 private:
  std::optional<MemoryEstimate> estimate_;
};

// Throws MemoryBudgetError when estimate.total_bytes() > available.bytes.
void check_memory(const MemoryEstimate& estimate, const MemoryAvailability& available);
inline void check_memory(const MemoryEstimate& estimate) { check_memory(estimate, memory_available()); }

// Work bound: refuses a job of more than `max_units` units (`what`: "characterize: 1e10 work
// units (grid 100000 x ...)", `lower_with`: the options). The default bound is kMaxWorkUnits.
inline constexpr double kMaxWorkUnits = 1e8;
void check_work(double units, std::string_view what, std::string_view lower_with,
                double max_units = kMaxWorkUnits);

// Progress of a long step inside the library: step ("bem: GMRES"), done/total (0 total: unknown),
// detail ("residual 3e-4, ETA 120 s"). A no-op until the CLI installs a sink.
using StepProgressSink = std::function<void(std::string_view step, double done, double total, std::string_view detail)>;
void set_step_progress_sink(StepProgressSink sink);
void report_step(std::string_view step, double done, double total, std::string_view detail = {});
bool step_progress_enabled();

}  // namespace plumage

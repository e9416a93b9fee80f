// Memory budgets and step progress (memory_budget.hpp).
#include "plumage/memory_budget.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

namespace plumage {

namespace {

std::string trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return std::string(s);
}

// The first number in a file ("max" or missing: none).
std::optional<double> read_number(const std::string& path) {
  std::ifstream in(path);
  std::string word;
  if (!(in >> word) || word == "max") return std::nullopt;
  try {
    return std::stod(word);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// The cgroup this process is in ("0::/user.slice/..." for v2, "N:memory:/path" for v1).
std::string cgroup_path(bool v2) {
  std::ifstream in("/proc/self/cgroup");
  std::string line;
  while (std::getline(in, line)) {
    const auto a = line.find(':'), b = line.find(':', a + 1);
    if (a == std::string::npos || b == std::string::npos) continue;
    const std::string controllers = line.substr(a + 1, b - a - 1);
    if (v2 ? line.rfind("0::", 0) == 0 : controllers.find("memory") != std::string::npos) return line.substr(b + 1);
  }
  return {};
}

// Remaining bytes under a cgroup limit (limit − usage), walking up to the root; none when unlimited.
std::optional<MemoryAvailability> cgroup_available() {
  std::optional<MemoryAvailability> best;
  const auto consider = [&](std::optional<double> limit, std::optional<double> usage, const std::string& source) {
    if (!limit || *limit <= 0 || *limit > 1e18) return;  // v1 "unlimited" is ~9.2e18
    const double left = std::max(0.0, *limit - usage.value_or(0.0));
    if (!best || left < static_cast<double>(best->bytes)) best = MemoryAvailability{static_cast<std::uint64_t>(left), source};
  };
  for (std::string p = cgroup_path(true); !p.empty();) {
    const std::string dir = "/sys/fs/cgroup" + (p == "/" ? std::string() : p);
    consider(read_number(dir + "/memory.max"), read_number(dir + "/memory.current"), "cgroup v2 " + dir + "/memory.max");
    if (p.empty() || p == "/") break;
    p = p.substr(0, p.find_last_of('/'));
    if (p.empty()) p = "/";
  }
  const std::string v1 = cgroup_path(false);
  if (!v1.empty()) {
    for (const std::string& dir : {"/sys/fs/cgroup/memory" + v1, std::string("/sys/fs/cgroup/memory")}) {
      consider(read_number(dir + "/memory.limit_in_bytes"), read_number(dir + "/memory.usage_in_bytes"),
               "cgroup v1 " + dir + "/memory.limit_in_bytes");
    }
  }
  return best;
}

std::mutex& state_mutex() {
  static std::mutex m;
  return m;
}
std::optional<MemoryAvailability>& process_limit() {
  static std::optional<MemoryAvailability> limit;
  return limit;
}
StepProgressSink& sink() {
  static StepProgressSink s;
  return s;
}

}  // namespace

std::uint64_t parse_memory_size(std::string_view text) {
  const std::string t = trim(text);
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(t, &used);
  } catch (const std::exception&) {
    throw std::invalid_argument("'" + t + "' is not a memory size (e.g. 8GiB, 512MiB, 2GB, 1e9)");
  }
  std::string unit = trim(std::string_view(t).substr(used));
  for (char& c : unit) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  double scale = 0;
  if (unit.empty() || unit == "b") scale = 1;
  else if (unit == "k" || unit == "kib") scale = 1024.0;
  else if (unit == "m" || unit == "mib") scale = 1024.0 * 1024;
  else if (unit == "g" || unit == "gib") scale = 1024.0 * 1024 * 1024;
  else if (unit == "t" || unit == "tib") scale = 1024.0 * 1024 * 1024 * 1024;
  else if (unit == "kb") scale = 1e3;
  else if (unit == "mb") scale = 1e6;
  else if (unit == "gb") scale = 1e9;
  else if (unit == "tb") scale = 1e12;
  const double bytes = value * scale;
  if (scale == 0 || !std::isfinite(bytes) || bytes < 1.0 || bytes > 1.8e19) {
    throw std::invalid_argument("'" + t + "' is not a memory size (a positive number with B, KiB, MiB, GiB, TiB, kB, MB, GB or TB; e.g. 8GiB)");
  }
  return static_cast<std::uint64_t>(bytes);
}

std::string format_bytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 6) {
    bytes /= 1024.0;
    ++u;
  }
  char buf[64];
  if (u == 0) std::snprintf(buf, sizeof buf, "%.0f B", bytes);
  else std::snprintf(buf, sizeof buf, bytes < 10 ? "%.2f %s" : bytes < 100 ? "%.1f %s" : "%.0f %s", bytes, units[u]);
  return buf;
}

MemoryAvailability machine_memory_available() {
  MemoryAvailability out{UINT64_MAX, "unknown (no /proc/meminfo)"};
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0;
  std::string unit;
  while (in >> key >> kb >> unit) {
    if (key == "MemAvailable:") {
      out = {static_cast<std::uint64_t>(kb * 1024.0), "MemAvailable (/proc/meminfo)"};
      break;
    }
  }
  if (const auto cg = cgroup_available(); cg && cg->bytes < out.bytes) out = *cg;
  return out;
}

std::uint64_t resident_bytes() {
  std::ifstream in("/proc/self/statm");
  double size_pages = 0, resident_pages = 0;
  if (!(in >> size_pages >> resident_pages)) return 0;
  return static_cast<std::uint64_t>(resident_pages * static_cast<double>(sysconf(_SC_PAGESIZE)));
}

namespace {
// A limit bounds the whole process: what is already resident (libraries, plug-ins, loaded
// tables, earlier steps' results) is not available to the next job. MemAvailable needs no such
// correction: it already excludes what this process holds.
MemoryAvailability less_resident(std::uint64_t limit, const std::string& source) {
  const std::uint64_t in_use = resident_bytes();
  const std::uint64_t left = limit > in_use ? limit - in_use : 0;
  return {left, source + " less " + format_bytes(static_cast<double>(in_use)) + " resident"};
}
}  // namespace

MemoryAvailability memory_available() {
  std::optional<MemoryAvailability> limit;
  {
    std::lock_guard lock(state_mutex());
    limit = process_limit();
  }
  if (limit) return less_resident(limit->bytes, limit->source);
  return machine_memory_available();
}

MemoryAvailability memory_available(std::string_view configured) {
  if (trim(configured).empty()) return memory_available();
  return less_resident(parse_memory_size(configured), "max_memory: " + trim(configured));
}

void set_memory_limit(std::uint64_t bytes, std::string source) {
  std::lock_guard lock(state_mutex());
  process_limit() = MemoryAvailability{bytes, std::move(source)};
}

void clear_memory_limit() {
  std::lock_guard lock(state_mutex());
  process_limit().reset();
}

MemoryEstimate& MemoryEstimate::add(std::string name, double bytes) {
  parts.push_back({std::move(name), bytes});
  return *this;
}

double MemoryEstimate::total_bytes() const {
  double sum = 0;
  for (const auto& p : parts) sum += p.bytes;
  return sum;
}

std::string MemoryEstimate::describe() const {
  std::string out = job + ": estimated " + format_bytes(total_bytes());
  if (!parts.empty()) {
    out += " (";
    for (std::size_t i = 0; i < parts.size(); ++i) out += (i ? ", " : "") + parts[i].name + " " + format_bytes(parts[i].bytes);
    out += ")";
  }
  return out;
}

namespace {
std::string budget_message(const MemoryEstimate& e, const MemoryAvailability& a) {
  std::string m = e.describe() + " exceeds the memory available, " + format_bytes(static_cast<double>(a.bytes)) +
                  " (" + a.source + ")";
  if (!e.lower_with.empty()) {
    m += "; lower it with ";
    for (std::size_t i = 0; i < e.lower_with.size(); ++i) m += (i ? ", " : "") + e.lower_with[i];
  }
  return m + "; or raise the budget with --max-memory SIZE if the machine really has it";
}
}  // namespace

MemoryBudgetError::MemoryBudgetError(MemoryEstimate estimate, MemoryAvailability available)
    : Error(budget_message(estimate, available)), estimate_(std::move(estimate)) {}

MemoryBudgetError::MemoryBudgetError(std::string message) : Error(std::move(message)) {}

void check_memory(const MemoryEstimate& estimate, const MemoryAvailability& available) {
  if (estimate.total_bytes() > static_cast<double>(available.bytes)) throw MemoryBudgetError(estimate, available);
}

void check_work(double units, std::string_view what, std::string_view lower_with, double max_units) {
  if (!(units <= max_units)) {
    std::ostringstream m;
    m << what << ": " << units << " work units, more than the " << max_units
      << " any sensible job needs (days of computing); lower " << lower_with;
    throw MemoryBudgetError(m.str());
  }
}

void set_step_progress_sink(StepProgressSink s) {
  std::lock_guard lock(state_mutex());
  sink() = std::move(s);
}

bool step_progress_enabled() {
  std::lock_guard lock(state_mutex());
  return static_cast<bool>(sink());
}

void report_step(std::string_view step, double done, double total, std::string_view detail) {
  StepProgressSink s;
  {
    std::lock_guard lock(state_mutex());
    s = sink();
  }
  if (s) s(step, done, total, detail);
}

}  // namespace plumage

#include "plumage/bench_record.hpp"

#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include "plumage/atomic_file.hpp"

namespace plumage {

std::string machine_description() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  }
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  std::ostringstream os;
  os.precision(3);
  os << model << " (" << std::thread::hardware_concurrency() << " cores), "
     << static_cast<double>(pages) * static_cast<double>(page) / (1024.0 * 1024 * 1024) << " GiB";
  // Timings on a shared machine mean little without the load they ran under.
  std::ifstream loadavg("/proc/loadavg");
  double load = 0;
  if (loadavg >> load) os << ", load " << load;
  return os.str();
}

std::string today_iso() {
  const auto now = std::chrono::system_clock::now();
  const auto days = std::chrono::floor<std::chrono::days>(now);
  std::chrono::year_month_day ymd{days};
  std::ostringstream os;
  os << static_cast<int>(ymd.year()) << '-';
  os.width(2), os.fill('0'), os << static_cast<unsigned>(ymd.month()) << '-';
  os.width(2), os << static_cast<unsigned>(ymd.day());
  return os.str();
}

void record_benchmark(const std::filesystem::path& markdown, const std::string& id,
                      const std::string& body) {
  std::string text;
  {
    std::ifstream in(markdown);
    if (in) {
      std::ostringstream ss;
      ss << in.rdbuf();
      text = ss.str();
    }
  }
  if (text.empty()) {
    text = "# Benchmarks\n\nEach section is written by `plumage bench <name> --record " +
           markdown.filename().string() +
           "` and replaced when the benchmark runs again.\n";
  }
  const std::string begin = "<!-- bench:" + id + ":begin -->";
  const std::string end = "<!-- bench:" + id + ":end -->";
  const std::string section = begin + "\n" + body + (body.ends_with("\n") ? "" : "\n") + end;
  const auto b = text.find(begin);
  const auto e = text.find(end);
  if (b != std::string::npos && e != std::string::npos && e > b) {
    text.replace(b, e + end.size() - b, section);
  } else {
    text += "\n" + section + "\n";
  }
  write_text_atomically(markdown, text);
}

}  // namespace plumage

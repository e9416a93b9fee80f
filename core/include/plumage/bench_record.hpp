// Recording benchmark results in docs/benchmarks.md: each benchmark owns one section between
// markers, replaced on every run, stamped with the machine, the command and the date.
#pragma once

#include <filesystem>
#include <string>

namespace plumage {

// "Intel(R) Xeon(R) ... (2 cores), 23.4 GiB".
std::string machine_description();
std::string today_iso();

void record_benchmark(const std::filesystem::path& markdown, const std::string& id,
                      const std::string& body);

}  // namespace plumage

// plumage/memory_budget.hpp (issue 23, memory budgets): sizes, the machine's availability, estimates
// and their refusal, the work bound and the step-progress sink.
#include <catch2/catch.hpp>

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "plumage/memory_budget.hpp"

using namespace plumage;

TEST_CASE("memory sizes parse with binary and decimal units", "[memory_budget]") {
  CHECK(parse_memory_size("8GiB") == 8ull << 30);
  CHECK(parse_memory_size("8G") == 8ull << 30);
  CHECK(parse_memory_size(" 512 MiB ") == 512ull << 20);
  CHECK(parse_memory_size("2GB") == 2000000000ull);
  CHECK(parse_memory_size("1.5kB") == 1500ull);
  CHECK(parse_memory_size("1e9") == 1000000000ull);
  CHECK(parse_memory_size("4096") == 4096ull);
  CHECK(parse_memory_size("1TiB") == 1ull << 40);
  for (const char* bad : {"", "0", "-1GiB", "nan", "inf", "8 parsecs", "GiB", "1e30"}) {
    INFO(bad);
    CHECK_THROWS_WITH(parse_memory_size(bad), Catch::Contains("not a memory size"));
  }
}

TEST_CASE("format_bytes picks a binary unit", "[memory_budget]") {
  CHECK(format_bytes(512) == "512 B");
  CHECK(format_bytes(1536) == "1.50 KiB");
  CHECK(format_bytes(8.0 * (1ull << 30)) == "8.00 GiB");
  CHECK(format_bytes(100.0 * (1ull << 30)) == "100 GiB");
}

TEST_CASE("the machine's memory is read from /proc/meminfo and the cgroup", "[memory_budget]") {
  const MemoryAvailability a = machine_memory_available();
  CHECK(a.bytes > (16ull << 20));  // a machine that runs the tests has more than 16 MiB free
  CHECK_FALSE(a.source.empty());
  clear_memory_limit();
  CHECK(memory_available().source == a.source);
  // A limit bounds the whole process: what is already resident is not available.
  const std::uint64_t resident = resident_bytes();
  CHECK(resident > (1ull << 20));  // this test binary holds more than 1 MiB
  set_memory_limit(1ull << 30, "--max-memory 1GiB");
  const MemoryAvailability limited = memory_available();
  CHECK(limited.bytes < 1ull << 30);
  // In doubles: under ASan the resident set (shadow memory included) can exceed the limit.
  const auto at_least = [resident](double limit) { return limit - 2.0 * static_cast<double>(resident) - 16.0 * (1 << 20); };
  CHECK(static_cast<double>(limited.bytes) > at_least(1ull << 30));
  CHECK_THAT(memory_available("").source, Catch::StartsWith("--max-memory 1GiB less ") && Catch::EndsWith(" resident"));
  CHECK(memory_available("2GiB").bytes < 2ull << 30);
  CHECK(static_cast<double>(memory_available("2GiB").bytes) > at_least(2ull << 30));
  CHECK_THAT(memory_available("2GiB").source, Catch::StartsWith("max_memory: 2GiB less "));
  set_memory_limit(1ull << 10, "--max-memory 1KiB");
  CHECK(memory_available().bytes == 0);  // less than the process already holds: nothing left
  CHECK_THROWS_AS(memory_available("lots"), std::invalid_argument);
  clear_memory_limit();
}

TEST_CASE("an estimate over the budget is refused naming its parts, the budget and the options", "[memory_budget]") {
  MemoryEstimate e;
  e.job = "bem dense solve of 40000 unknowns";
  e.add("dense matrix 16 N^2", 16.0 * 40000 * 40000).add("right-hand sides", 1e6);
  e.lower_with = {"points_per_wavelength (now 30)", "method: hmatrix"};
  CHECK(e.total_bytes() == Approx(16.0 * 40000 * 40000 + 1e6));
  CHECK_NOTHROW(check_memory(e, {1ull << 40, "test"}));
  try {
    check_memory(e, {8ull << 30, "--max-memory 8GiB"});
    FAIL("not refused");
  } catch (const MemoryBudgetError& err) {
    const std::string m = err.what();
    CHECK_THAT(m, Catch::Contains("bem dense solve of 40000 unknowns: estimated 23.8 GiB"));
    CHECK_THAT(m, Catch::Contains("dense matrix 16 N^2 23.8 GiB"));
    CHECK_THAT(m, Catch::Contains("exceeds the memory available, 8.00 GiB (--max-memory 8GiB)"));
    CHECK_THAT(m, Catch::Contains("points_per_wavelength (now 30), method: hmatrix"));
    REQUIRE(err.estimate().has_value());
    CHECK(err.estimate()->parts.size() == 2);
  }
  // An error of the project's hierarchy (the CLI maps MemoryBudgetError to exit status 2).
  CHECK_THROWS_AS(check_memory(e, {1, "x"}), Error);
}

TEST_CASE("absurd work is refused naming the count and the options", "[memory_budget]") {
  CHECK_NOTHROW(check_work(1e6, "characterize x", "--grid"));
  CHECK_THROWS_AS(check_work(1e10, "characterize x", "--grid"), MemoryBudgetError);
  CHECK_THROWS_WITH(check_work(1e10, "characterize x: fit units", "--grid"),
                    Catch::Contains("characterize x: fit units: 1e+10 work units") && Catch::Contains("lower --grid"));
  CHECK_THROWS_AS(check_work(std::numeric_limits<double>::quiet_NaN(), "x", "y"), MemoryBudgetError);
}

TEST_CASE("step progress goes to the installed sink only", "[memory_budget][progress]") {
  report_step("nobody listens", 1, 2);  // no sink: a no-op
  std::vector<std::string> seen;
  set_step_progress_sink([&](std::string_view step, double done, double total, std::string_view detail) {
    seen.push_back(std::string(step) + " " + std::to_string(static_cast<int>(done)) + "/" +
                   std::to_string(static_cast<int>(total)) + " " + std::string(detail));
  });
  CHECK(step_progress_enabled());
  report_step("bem: GMRES", 3, 40, "residual 1e-3");
  set_step_progress_sink({});
  CHECK_FALSE(step_progress_enabled());
  report_step("bem: GMRES", 4, 40);
  REQUIRE(seen.size() == 1);
  CHECK(seen[0] == "bem: GMRES 3/40 residual 1e-3");
}

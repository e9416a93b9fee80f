#include "plumage/accuracy_ladder.hpp"

#include <chrono>
#include <ctime>

namespace plumage {

RungCost measure_rung(const std::function<void()>& work) {
  timespec c0{}, c1{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c0);
  const auto t0 = std::chrono::steady_clock::now();
  work();
  const auto t1 = std::chrono::steady_clock::now();
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c1);
  return {std::chrono::duration<double>(t1 - t0).count(),
          static_cast<double>(c1.tv_sec - c0.tv_sec) + 1e-9 * static_cast<double>(c1.tv_nsec - c0.tv_nsec)};
}

}  // namespace plumage

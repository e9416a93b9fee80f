// Benchmark "bem" (`plumage bench bem`, benchmark.hpp): the full-wave solver on a segment of a
// species' barbule against the approximate solver on the same segment; see bem_benchmark.cpp.
#pragma once

#include "plumage/plugin.hpp"

namespace plumage::bem {

void register_bem_benchmark(Registrar& registrar);

}  // namespace plumage::bem

// Gauss–Legendre rules on [0, 1] (nodes and weights), cached per order.
#pragma once

#include <vector>

namespace plumage::bem {

struct Rule {
  std::vector<double> x, w;  // on [0, 1], weights sum to 1
};

// Order n ≥ 1 (computed once by Newton iteration on P_n, thread-safe).
const Rule& gauss_legendre(int n);

// A composite rule on [0, 1] graded geometrically toward 0 (pieces [0, r^{k}], …, [r, 1] with
// ratio r = 1/4), `per_piece` points each; integrates x ln x-type endpoint behaviour accurately.
const Rule& graded_rule(int pieces, int per_piece);

}  // namespace plumage::bem

#include "quadrature.hpp"

#include <cmath>
#include <map>
#include <mutex>
#include <numbers>

namespace plumage::bem {

namespace {

Rule make_gauss(int n) {
  Rule r;
  r.x.resize(n);
  r.w.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1, p1 = p2;
      }
      if (n == 1) p0 = 1.0, p1 = x;
      const double dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) {
        // recompute derivative at the converged node for the weight
        double q0 = 1.0, q1 = x;
        for (int k = 2; k <= n; ++k) {
          const double q2 = ((2.0 * k - 1.0) * x * q1 - (k - 1.0) * q0) / k;
          q0 = q1, q1 = q2;
        }
        const double d = n * (x * q1 - q0) / (x * x - 1.0);
        r.x[i] = 0.5 * (1.0 - x);
        r.w[i] = 1.0 / ((1.0 - x * x) * d * d);  // 2/((1−x²)P'²) halved for [0, 1]
        break;
      }
    }
  }
  return r;
}

std::mutex mutex;
std::map<int, Rule> gauss_cache;
std::map<std::pair<int, int>, Rule> graded_cache;

}  // namespace

const Rule& gauss_legendre(int n) {
  std::lock_guard lock(mutex);
  auto it = gauss_cache.find(n);
  if (it == gauss_cache.end()) it = gauss_cache.emplace(n, make_gauss(n)).first;
  return it->second;
}

const Rule& graded_rule(int pieces, int per_piece) {
  const Rule& g = gauss_legendre(per_piece);
  std::lock_guard lock(mutex);
  auto it = graded_cache.find({pieces, per_piece});
  if (it != graded_cache.end()) return it->second;
  Rule r;
  double hi = 1.0;
  for (int p = 0; p < pieces; ++p) {
    const double lo = p + 1 == pieces ? 0.0 : hi * 0.25;
    for (std::size_t k = 0; k < g.x.size(); ++k) {
      r.x.push_back(lo + (hi - lo) * g.x[k]);
      r.w.push_back((hi - lo) * g.w[k]);
    }
    hi = lo;
  }
  return graded_cache.emplace(std::make_pair(pieces, per_piece), std::move(r)).first->second;
}

}  // namespace plumage::bem

// Real-data FFTs through FFTW for core (rough profiles, autocovariances, noise pools).
//
// Determinism across machines (DESIGN §6: a barbule instance and a material's noise pool must be
// bit-identical everywhere): plans are made with FFTW_ESTIMATE (the plan follows from operation
// counts, never from timings on the machine at hand) and FFTW_NO_SIMD (scalar codelets only: the
// SIMD ones are chosen per CPU and round differently). The planner is not thread-safe, so plan
// creation and destruction hold one process-wide lock; execution runs concurrently.
#pragma once

#include <complex>
#include <cstddef>
#include <vector>

namespace plumage::detail {

class RealFft {
 public:
  explicit RealFft(std::size_t n);  // any n >= 2
  ~RealFft();
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;

  std::size_t size() const { return n_; }
  // out[k] = Σ_t in[t] e^{-2πikt/n}, k = 0 … n/2 (the half spectrum of real data).
  void forward(const std::vector<double>& in, std::vector<std::complex<double>>& out) const;
  // out[t] = Σ_k c_k e^{+2πikt/n} over the Hermitian spectrum whose half is `in` (k = 0 … n/2),
  // without 1/n. `in` is overwritten (FFTW's c2r destroys its input).
  void inverse(std::vector<std::complex<double>>& in, std::vector<double>& out) const;

 private:
  std::size_t n_;
  void* forward_ = nullptr;  // fftw_plan
  void* inverse_ = nullptr;
};

}  // namespace plumage::detail

#include "real_fft.hpp"

#include <fftw3.h>

#include <mutex>

#include "plumage/error.hpp"

namespace plumage::detail {

namespace {

std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

constexpr unsigned kFlags = FFTW_ESTIMATE | FFTW_NO_SIMD;

fftw_complex* as_fftw(std::complex<double>* p) { return reinterpret_cast<fftw_complex*>(p); }

}  // namespace

RealFft::RealFft(std::size_t n) : n_(n) {
  if (n < 2) throw Error("FFT size must be at least 2");
  // Plans are made on scratch arrays and executed on the caller's through the new-array interface;
  // FFTW_NO_SIMD plans need no particular alignment.
  std::vector<double> real(n);
  std::vector<std::complex<double>> half(n / 2 + 1);
  std::lock_guard lock(planner_mutex());
  forward_ = fftw_plan_dft_r2c_1d(static_cast<int>(n), real.data(), as_fftw(half.data()), kFlags);
  inverse_ = fftw_plan_dft_c2r_1d(static_cast<int>(n), as_fftw(half.data()), real.data(), kFlags);
  if (!forward_ || !inverse_) throw Error("FFTW could not plan a transform of size " + std::to_string(n));
}

RealFft::~RealFft() {
  std::lock_guard lock(planner_mutex());
  if (forward_) fftw_destroy_plan(static_cast<fftw_plan>(forward_));
  if (inverse_) fftw_destroy_plan(static_cast<fftw_plan>(inverse_));
}

void RealFft::forward(const std::vector<double>& in, std::vector<std::complex<double>>& out) const {
  if (in.size() != n_) throw Error("FFT input of the wrong size");
  out.resize(n_ / 2 + 1);
  std::vector<double> copy(in);  // r2c plans may overwrite their input under some flags
  fftw_execute_dft_r2c(static_cast<fftw_plan>(forward_), copy.data(), as_fftw(out.data()));
}

void RealFft::inverse(std::vector<std::complex<double>>& in, std::vector<double>& out) const {
  if (in.size() != n_ / 2 + 1) throw Error("FFT half spectrum of the wrong size");
  out.resize(n_);
  fftw_execute_dft_c2r(static_cast<fftw_plan>(inverse_), as_fftw(in.data()), out.data());
}

}  // namespace plumage::detail

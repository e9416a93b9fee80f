#include "lu.hpp"

#include <complex>
#include <utility>

namespace {
using Complex = std::complex<double>;
}

namespace plumage::rcwa {

Lu::Lu(Mat a) : lu_(std::move(a)), swaps_(static_cast<std::size_t>(lu_.rows())) {
  const Eigen::Index n = lu_.rows();
  for (Eigen::Index k = 0; k < n; ++k) {
    Eigen::Index p = k;
    double best = std::norm(lu_(k, k));
    for (Eigen::Index i = k + 1; i < n; ++i) {
      const double v = std::norm(lu_(i, k));
      if (v > best) best = v, p = i;
    }
    swaps_[static_cast<std::size_t>(k)] = static_cast<int>(p);
    if (p != k) lu_.row(k).swap(lu_.row(p));
    const Eigen::Index r = n - k - 1;
    if (r == 0 || best == 0.0) continue;  // a zero pivot: singular, as Eigen's PartialPivLU leaves it
    // The rank-1 update of the trailing block column by column on the contiguous column-major
    // storage (Eigen's outer-product expression on the nested block was ~3x slower at n ≈ 22).
    Complex* a = lu_.data();
    Complex* lk = a + k * n;
    const Complex inv_pivot = 1.0 / lk[k];
    for (Eigen::Index i = k + 1; i < n; ++i) lk[i] *= inv_pivot;
    for (Eigen::Index j = k + 1; j < n; ++j) {
      Complex* cj = a + j * n;
      const Complex ukj = cj[k];
      for (Eigen::Index i = k + 1; i < n; ++i) cj[i] -= lk[i] * ukj;
    }
  }
}

Lu::Mat Lu::solve(const Mat& b) const {
  Mat x = b;
  for (std::size_t k = 0; k < swaps_.size(); ++k)
    if (swaps_[k] != static_cast<int>(k)) x.row(static_cast<Eigen::Index>(k)).swap(x.row(swaps_[k]));
  lu_.triangularView<Eigen::UnitLower>().solveInPlace(x);
  lu_.triangularView<Eigen::Upper>().solveInPlace(x);
  return x;
}

// b A⁻¹ = ((b U⁻¹) L⁻¹) P, P applied on the right as the row swaps' column swaps in reverse order.
Lu::Mat Lu::solve_right(const Mat& b) const {
  Mat x = b;
  lu_.triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(x);
  lu_.triangularView<Eigen::UnitLower>().solveInPlace<Eigen::OnTheRight>(x);
  for (std::size_t k = swaps_.size(); k-- > 0;)
    if (swaps_[k] != static_cast<int>(k)) x.col(static_cast<Eigen::Index>(k)).swap(x.col(swaps_[k]));
  return x;
}

Lu::Mat Lu::inverse() const { return solve(Mat::Identity(lu_.rows(), lu_.cols())); }

}  // namespace plumage::rcwa

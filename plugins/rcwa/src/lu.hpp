// Dense LU factorisation with partial pivoting for the solver's small complex systems (2(2M+1) ≤
// ~40 unknowns). Eigen's PartialPivLU picks its pivots by |z| = hypot(Re, Im), a libm call per
// candidate that took ~60 % of the LU time here (NOTES.md §5); this one picks the same pivots by
// |z|² (monotone in |z|), and leaves the triangular solves to Eigen.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace plumage::rcwa {

class Lu {
 public:
  using Mat = Eigen::MatrixXcd;
  explicit Lu(Mat a);
  Mat solve(const Mat& b) const;        // A⁻¹ b
  Mat solve_right(const Mat& b) const;  // b A⁻¹
  Mat inverse() const;

 private:
  Mat lu_;                  // unit-lower L and upper U of P A = L U
  std::vector<int> swaps_;  // row k was swapped with row swaps_[k], in order k = 0, 1, ...
};

}  // namespace plumage::rcwa

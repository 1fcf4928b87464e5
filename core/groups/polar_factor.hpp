#pragma once
// The orthogonal polar factor of a nearly orthogonal matrix: the orthogonal Q nearest to y in the Frobenius
// norm (y = Q P, P symmetric positive definite). Computed by the Newton-Schulz iteration
//   y_{k+1} = y_k (3 I - y_k^T y_k) / 2,
// which converges quadratically to Q when ||y^T y - I||_2 < 1 (Higham, Functions of Matrices, sec. 8.3).
// Used for the z rule (a user z replaced by its polar factor, so that z^-1 = z^T holds and (1.1) is the
// equation on the group) and to re-orthogonalise long products y_n exp(u_n).
#include <limits>

namespace lienewton {

// ||y^T y - I||_F at or below which y is orthogonal to working precision (its own polar factor to rounding).
inline double orthogonal_to_rounding(int n) { return 4.0 * std::numeric_limits<double>::epsilon() * n; }

template <class M>
double orthogonality_defect(const M& y) {
  return (y.transpose() * y - M::Identity(y.rows(), y.cols())).norm();
}

// The polar factor of y (left unchanged when y is already orthogonal to rounding).
template <class M>
M orthogonal_polar_factor(const M& y) {
  M q = y;
  double defect = orthogonality_defect(q);
  const double done = orthogonal_to_rounding(static_cast<int>(y.rows()));
  for (int k = 0; k < 8 && defect > done; ++k) {
    const M next = 0.5 * q * (3.0 * M::Identity(y.rows(), y.cols()) - q.transpose() * q);
    const double d = orthogonality_defect(next);
    if (!(d < defect)) break;  // at rounding: further steps only move q within it
    q = next;
    defect = d;
  }
  return q;
}

}  // namespace lienewton

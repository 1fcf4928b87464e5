#pragma once
// a * b for an a that may be mostly zeros: differentials of simple fields are sparse (paper-linear's dg_y has at
// most two entries per column), and a dense product would cost q^3 where the nonzeros need nnz(a) q.
#include <Eigen/Core>

namespace lienewton {

template <class Matrix>
Matrix product_skipping_zeros(const Matrix& a, const Matrix& b) {
  const Eigen::Index nonzeros = (a.array() != 0.0).count();
  if (8 * nonzeros > a.size()) return a * b;
  Matrix out = Matrix::Zero(a.rows(), b.cols());
  for (Eigen::Index c = 0; c < a.cols(); ++c)
    for (Eigen::Index r = 0; r < a.rows(); ++r)
      if (a(r, c) != 0.0) out.row(r) += a(r, c) * b.row(c);
  return out;
}

}  // namespace lienewton

#pragma once
// How far a user's value is from a group's algebra, and whether that is only rounding.
#include <Eigen/Dense>
#include <cmath>
#include <limits>

namespace lienewton {

// What a user's program reads and returns for G's elements and algebra elements: G's matrix, or for a system of
// bodies (whose matrix is the strip [y1 ... yk]) the square diag(y1, ..., yk), so that the program's y U is the
// tangent y_i U_i body by body and its matrix algebra is the bodies' side by side.
template <class G>
Eigen::MatrixXd program_matrix(const G& group, const typename G::Element& y) {
  if constexpr (requires { group.block_diagonal(y); }) {
    return group.block_diagonal(y);
  } else {
    return group.matrix(y);
  }
}
template <class G>
typename G::Element program_element(const G& group, const Eigen::MatrixXd& m) {
  if constexpr (requires { group.diagonal_blocks(m); }) {
    return group.diagonal_blocks(m);
  } else {
    return group.element(m);
  }
}

// ||program_matrix(a) - m||; on a system of bodies without forming its square matrix (a value of a program's dg_y
// is checked once per direction): the blocks' differences and the entries off the blocks, column by column.
template <class G>
double program_distance(const G& group, const typename G::Element& a, const Eigen::MatrixXd& m) {
  if constexpr (requires { group.diagonal_blocks(m); }) {
    constexpr Eigen::Index r = G::kRows;
    double sum = 0;
    for (Eigen::Index j = 0; j < m.cols(); ++j) {
      const Eigen::Index top = j / r * r;  // column j's block starts at this row
      const auto column = m.col(j);
      sum += column.head(top).squaredNorm() + column.tail(m.rows() - top - r).squaredNorm() +
             (a.col(j) - column.segment(top, r)).squaredNorm();
    }
    return std::sqrt(sum);
  } else {
    return (program_matrix(group, a) - m).norm();
  }
}

// ||hat(vee(m)) - m||: how far a program's value m is from G's algebra (off the blocks of a system of bodies too).
template <class G>
double algebra_defect(const G& group, const Eigen::MatrixXd& m) {
  return program_distance(group, group.hat(group.vee(program_element(group, m))), m);
}

// Rounding's share of a defect: values built as u - u' are exactly skew, others to a few ulps of their size.
inline bool within_rounding(double defect, const Eigen::MatrixXd& m) {
  return defect <= 64 * std::numeric_limits<double>::epsilon() * m.norm();
}

}  // namespace lienewton

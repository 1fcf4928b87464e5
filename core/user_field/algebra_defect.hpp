#pragma once
// How far a user's value is from a group's algebra, and whether that is only rounding.
#include <Eigen/Dense>
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

// ||hat(vee(m)) - m||: how far a program's value m is from G's algebra (off the blocks of a system of bodies too).
template <class G>
double algebra_defect(const G& group, const Eigen::MatrixXd& m) {
  return (program_matrix(group, group.hat(group.vee(program_element(group, m)))) - m).norm();
}

// Rounding's share of a defect: values built as u - u' are exactly skew, others to a few ulps of their size.
inline bool within_rounding(double defect, const Eigen::MatrixXd& m) {
  return defect <= 64 * std::numeric_limits<double>::epsilon() * m.norm();
}

}  // namespace lienewton

#pragma once
// How far a user's value is from a group's algebra, and whether that is only rounding.
#include <Eigen/Dense>
#include <limits>

namespace lienewton {

// ||hat(vee(m)) - m||: how far the n x n matrix m is from G's algebra.
template <class G>
double algebra_defect(const G& group, const Eigen::MatrixXd& m) {
  return (group.matrix(group.hat(group.vee(group.element(m)))) - m).norm();
}

// Rounding's share of a defect: values built as u - u' are exactly skew, others to a few ulps of their size.
inline bool within_rounding(double defect, const Eigen::MatrixXd& m) {
  return defect <= 64 * std::numeric_limits<double>::epsilon() * m.norm();
}

}  // namespace lienewton

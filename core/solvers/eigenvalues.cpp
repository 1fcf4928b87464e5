#include "eigenvalues.hpp"

#include <Eigen/Eigenvalues>

namespace lienewton {

Eigen::VectorXcd eigenvalues_of(const Eigen::MatrixXd& a) { return a.eigenvalues(); }

}  // namespace lienewton

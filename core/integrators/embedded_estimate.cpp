#include "embedded_estimate.hpp"

#include <cmath>

namespace lienewton::integrators {

EmbeddedWeights embedded_weights(const Tableau& tab, double gamma0) {
  const int s = tab.stages();
  Eigen::MatrixXd vandermonde(s, s);
  Eigen::VectorXd rhs(s);
  for (int m = 0; m < s; ++m) {
    for (int j = 0; j < s; ++j) vandermonde(m, j) = std::pow(tab.c(j), m);
    rhs(m) = 1.0 / (m + 1) - (m == 0 ? gamma0 : 0.0);
  }
  const Eigen::VectorXd b_hat = vandermonde.fullPivLu().solve(rhs);
  EmbeddedWeights w;
  w.gamma0 = gamma0;
  w.e = tab.a.transpose().fullPivLu().solve(b_hat - tab.b);  // e^T = (b^ - b)^T A^-1
  w.order = s;
  return w;
}

}  // namespace lienewton::integrators

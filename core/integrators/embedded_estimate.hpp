#pragma once
// The embedded error estimate of an implicit RKMK step, Radau5's carried over to the group (Hairer & Wanner II,
// section IV.8, (8.19)-(8.20)). An RKMK step is the Runge-Kutta method applied to the chart's ODE
// Theta' = dexpinv_Theta(g(t, y_k exp Theta)), Theta(t_k) = 0, whose value at Theta = 0 is g(t_k, y_k); so the
// classical construction applies in the algebra unchanged. The embedded method adds the node 0 with weight gamma0:
//   Theta^ = h (gamma0 g(t_k, y_k) + sum_j b^_j K_j),  sum_j b^_j c_j^(m-1) = 1/m - gamma0 [m = 1],  m = 1 .. s,
// of order s, and the estimate is its difference from the step's Theta = h sum_j b_j K_j, filtered by the stiff
// part of the linearisation:
//   err = (I - h gamma0 J)^-1 (h gamma0 g(t_k, y_k) + sum_j e_j Theta_j),   e = (b^ - b)^T A^-1,
// with Theta_j = h sum_l a_jl K_l the stages. The filter keeps the estimate bounded as h |lambda| grows (an
// unfiltered one grows like h |lambda| on the stiff components); where err > 1 on the first step or right after a
// rejection, Radau5 evaluates g again at y_k exp(err) in place of g(t_k, y_k), which removes the -1 the filtered
// estimate still tends to on a stiff component away from its equilibrium (IV.8, after (8.20)).
#include <Eigen/Dense>

#include "tableau.hpp"

namespace lienewton::integrators {

struct EmbeddedWeights {
  double gamma0 = 0;
  Eigen::VectorXd e;  // (b^ - b)^T A^-1
  int order = 0;      // s: the estimate is O(h^(s+1)), and steps are chosen with the exponent 1/(s+1)
};

// For an implicit RKMK tableau with distinct nodes c and gamma0 (decoupling_of(tab).gamma0).
EmbeddedWeights embedded_weights(const Tableau& tab, double gamma0);

}  // namespace lienewton::integrators

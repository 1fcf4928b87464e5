#pragma once
// The chain on (SE(3) x R^6)^k (SE3xR6PowerGroup, requests' group "SExR^k" with n = k): k equal rigid links, the
// first hanging from the fixed point p0 = 0, neighbours joined at their ends by penalty spherical joints (a stiff
// spring k_s and a damper c between the two attachment points), under gravity gamma (chain_params.hpp).
//
// Link i has pose (R_i, x_i) (body to space, x_i its centre of mass) and body twist (w_i, v_i):
//   R_i' = R_i hat(w_i),  x_i' = R_i v_i,
// so y_i = diag([[R_i, x_i], [0, 1]], [[I, (w_i, v_i)], [0, 1]]) and g_i(y) = (w_i, v_i, w_i', v_i') in the
// algebra coordinates (SE(3)'s rotation then translation, then R^6's). Its joints sit at a_top = (0, 0, +L/2) and
// a_bottom = (0, 0, -L/2). Joint 0 joins p0 to link 1's top point, joint j (1 <= j < k) link j's bottom point
// P = x_j + R_j a_bottom to link j+1's top point Q = x_{j+1} + R_{j+1} a_top (links counted from 1 here). Its gap
// d = Q - P, with the rate d' = Q' - P' (a point's velocity is R (v + w x a)), pulls with
//   F = -k_s d - c d'
// on the lower link at Q and -F on the upper one at P. Newton-Euler in the body frame (e.g. Murray, Li & Sastry,
// "A Mathematical Introduction to Robotic Manipulation", 1994, section 4.4), J principal about the centre:
//   m v' = m (v x w) + R^T (F_total + m gamma),   J w' = (J w) x w + sum over its joints a x (R^T F_a).
// Its energy
//   E = sum_i [1/2 m |v_i|^2 + 1/2 w_i . J w_i - m gamma . x_i] + sum_j 1/2 k_s |d_j|^2
// changes as dE/dt = -c sum_j |d_j'|^2 (the springs' and gravity's work cancel the potentials' rates, the gyroscopic
// terms do no work): conserved exactly at c = 0, the only case it is reported as an invariant.
//
// dg couples a link with its neighbours only, through the joints: dg_matrix is block tridiagonal with 12 x 12
// blocks, assembled from each link's and each joint's local derivatives in O(k). They are exact: forward-mode
// automatic differentiation (Eigen's AutoDiff) of the same formulas g evaluates, seeded with the perturbation
// y_i exp(t e_j) to first order (R -> R (I + t hat(u_w)), x -> x + t R u_r, w -> w + t u_dw, v -> v + t u_dv),
// which is exact for a first derivative at t = 0 (chain.cpp).
#include <Eigen/Dense>

#include "chain_params.hpp"
#include "groups/mechanics_groups.hpp"

namespace lienewton {

class Chain {
 public:
  using Group = SE3xR6PowerGroup;
  using Element = Group::Element;
  static constexpr int kLinkDim = Group::kBodyDim;  // 12 coordinates per link

  explicit Chain(const ChainParams& p) : params_(p) {}
  const ChainParams& params() const { return params_; }

  // The field as the algebra element of the strip (VectorFieldOf takes its vee).
  Element g(const Element& y) const {
    const Group group(links(y));
    return group.hat(coordinates(y));
  }
  // dg_y(dir) from the exact matrix: one product with the block-tridiagonal dg (O(k)).
  Element dg(const Element& y, const Element& dir, const Element&) const {
    const Group group(links(y));
    return group.hat(dg_matrix(group, y) * group.vee(dir));
  }
  Eigen::VectorXd coordinates(const Element& y) const;
  Group::Operator dg_matrix(const Group& group, const Element& y) const;

  double energy(const Element& y) const;
  // The size the energy's drift is measured against: kinetic, the springs' and |gravity's potential| summed.
  double energy_scale(const Element& y) const;
  // Joint j's gap d_j and its rate d_j' (j = 0: the fixed point to link 1's top).
  Eigen::Vector3d gap(const Element& y, int j) const;
  Eigen::Vector3d gap_rate(const Element& y, int j) const;

  // The chain's time scale, a bound on the rates of its linearisation at rest for every k: a joint's angular
  // frequency sqrt(4 k_s s) and its damper's rate 4 c s, with s = 1/m + (L/2)^2 / J_across the compliance of a
  // link's end point (4 bounds a path graph's Laplacian), and the swing's sqrt(|gamma| / L) (soft joints).
  double rate() const;

  // y(0) of k links: straight, at rest, joints closed, turned by tilt about the space x axis from hanging along -z.
  Element start_strip(int k) const;
  Eigen::MatrixXd start(int k) const { return Group(k).matrix(start_strip(k)); }

  static int links(const Element& y) { return static_cast<int>(y.cols()) / Group::kRows; }

 private:
  ChainParams params_;
};

}  // namespace lienewton

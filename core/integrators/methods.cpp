#include "methods.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace lienewton::integrators {
namespace {

struct Row {
  Integrator integrator;
  Tableau tableau;
};

Eigen::MatrixXd matrix(std::initializer_list<std::initializer_list<double>> rows) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(rows.size()));
  Eigen::Index i = 0;
  for (const auto& row : rows) {
    Eigen::Index j = 0;
    for (double x : row) m(i, j++) = x;
    ++i;
  }
  return m;
}

Eigen::VectorXd vector(std::initializer_list<double> values) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double x : values) v(i++) = x;
  return v;
}

std::vector<Row> rows() {
  const double s3 = std::sqrt(3.0), s6 = std::sqrt(6.0), s15 = std::sqrt(15.0);
  // dirk-cg2's gamma = 1 - 1/sqrt(2) makes the 2-stage SDIRK L-stable; dirk-cg3's is the root of
  // 6 g^3 - 18 g^2 + 9 g - 1 of Alexander's L-stable SDIRK3.
  const double g2 = 1.0 - 0.70710678118654752440, g3 = 0.43586652150845899941;
  return {
      // Implicit Euler (1.1): one stage, a = b = 1.
      {Integrator::implicit_euler, {Form::dirk_crouch_grossman, 1, matrix({{1.0}}), vector({1.0})}},
      // dirk-cg2: the L-stable SDIRK with c = (gamma, 1), stiffly accurate. Order 2: for Crouch-Grossman methods
      // the conditions up to order 2 are the classical ones (those of the non-commutative setting start at 3:
      // Owren & Marthinsen, BIT 39 (1999)).
      {Integrator::dirk_cg2,
       {Form::dirk_crouch_grossman, 2, matrix({{g2, 0.0}, {1.0 - g2, g2}}), vector({1.0 - g2, g2})}},
      // Gauss-Legendre s = 1, 2, 3 and Radau IIA s = 2, 3: Hairer & Wanner, "Solving Ordinary Differential
      // Equations II", 2nd ed., section IV.5, Tables 5.1, 5.2, 5.5 and 5.6.
      {Integrator::rkmk_gauss1, {Form::implicit_rkmk, 2, matrix({{0.5}}), vector({1.0})}},
      {Integrator::rkmk_gauss2,
       {Form::implicit_rkmk, 4, matrix({{0.25, 0.25 - s3 / 6}, {0.25 + s3 / 6, 0.25}}), vector({0.5, 0.5})}},
      {Integrator::rkmk_gauss3,
       {Form::implicit_rkmk, 6,
        matrix({{5.0 / 36, 2.0 / 9 - s15 / 15, 5.0 / 36 - s15 / 30},
                {5.0 / 36 + s15 / 24, 2.0 / 9, 5.0 / 36 - s15 / 24},
                {5.0 / 36 + s15 / 30, 2.0 / 9 + s15 / 15, 5.0 / 36}}),
        vector({5.0 / 18, 4.0 / 9, 5.0 / 18})}},
      {Integrator::rkmk_radau2,
       {Form::implicit_rkmk, 3, matrix({{5.0 / 12, -1.0 / 12}, {0.75, 0.25}}), vector({0.75, 0.25})}},
      {Integrator::rkmk_radau3,
       {Form::implicit_rkmk, 5,
        matrix({{(88 - 7 * s6) / 360, (296 - 169 * s6) / 1800, (-2 + 3 * s6) / 225},
                {(296 + 169 * s6) / 1800, (88 + 7 * s6) / 360, (-2 - 3 * s6) / 225},
                {(16 - s6) / 36, (16 + s6) / 36, 1.0 / 9}}),
        vector({(16 - s6) / 36, (16 + s6) / 36, 1.0 / 9})}},
      // The classical RK4 in Munthe-Kaas form (Munthe-Kaas 1999): c = (0, 1/2, 1/2, 1).
      {Integrator::rkmk4,
       {Form::explicit_rkmk, 4, matrix({{0, 0, 0, 0}, {0.5, 0, 0, 0}, {0, 0.5, 0, 0}, {0, 0, 1, 0}}),
        vector({1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6})}},
      // dirk-cg3: a three-stage SDIRK solving the order-3 conditions of Crouch-Grossman methods (Owren & Marthinsen
      // 1999): the classical sum b_i = 1, sum b_i c_i = 1/2, sum b_i c_i^2 = 1/3, sum b_i a_ij c_j = 1/6, and the one
      // the non-commuting exponentials add, sum b_i^2 c_i + 2 sum_{i<j} b_i c_i b_j = 1/3. With three stages and
      // order 3 the stability function depends on gamma alone, and Alexander's gamma (SIAM J. Numer. Anal. 14
      // (1977)) makes it L-stable; c_2 = 1/5 picks, from the one-parameter family left, one with c in [0, 1] and no
      // coefficient above 0.62 in size, solved to rounding by Newton (docs/integrators.md). Not stiffly accurate.
      // Alexander's own tableau fails the last condition (its left side is 0.5017).
      {Integrator::dirk_cg3,
       {Form::dirk_crouch_grossman, 3,
        matrix({{g3, 0.0, 0.0}, {-0.235866521508459, g3, 0.0}, {-0.24071786516339652, 0.548838495713276, g3}}),
        vector({-0.13948593195334003, 0.5275228363001196, 0.6119630956532204})}},
      // Lobatto IIIC, s = 3 (Chipman, BIT 11 (1971); Hairer & Wanner II, section IV.5): order 2s - 2 = 4, L-stable
      // and stiffly accurate, c = (0, 1/2, 1).
      {Integrator::rkmk_lobatto3c,
       {Form::implicit_rkmk, 4,
        matrix({{1.0 / 6, -1.0 / 3, 1.0 / 6}, {1.0 / 6, 5.0 / 12, -1.0 / 12}, {1.0 / 6, 2.0 / 3, 1.0 / 6}}),
        vector({1.0 / 6, 2.0 / 3, 1.0 / 6})}},
  };
}

}  // namespace

const Tableau& tableau_of(Integrator integrator) {
  static const std::vector<Row> kRows = rows();
  for (const Row& row : kRows)
    if (row.integrator == integrator) return row.tableau;
  throw std::logic_error("no tableau for integrator " + std::to_string(static_cast<int>(integrator)));
}

}  // namespace lienewton::integrators

#pragma once
// The Butcher tableaus of the implicit Runge-Kutta-Munthe-Kaas integrators: the collocation methods Gauss-Legendre
// (s = 1, 2, 3: orders 2, 4, 6) and Radau IIA (s = 2, 3: orders 3, 5), as in Hairer & Wanner, "Solving Ordinary
// Differential Equations II", 2nd ed., section IV.5, Tables 5.1, 5.2, 5.5 and 5.6. With them each RKMK method
// truncates dexpinv (3.9) after ad^(p-2), p its order: the first term left out, ad_Theta^(p-1) K with
// Theta = O(h), changes K by O(h^(p-1)) and the step by O(h^p), and its leading part [g(y_k), g(y_k)] vanishes, so
// the local error stays O(h^(p+1)) (Munthe-Kaas, "High order Runge-Kutta methods on manifolds", Appl. Numer.
// Math. 29 (1999), section 4).
#include <cmath>
#include <optional>

#include "options.hpp"

namespace lienewton {

struct RkmkTableau {
  int stages;
  double a[3][3];
  double b[3];
  int dexpinv_degree = 0;  // the highest power of ad kept in dexpinv (3.9): order_of(integrator) - 2
  double c(int i) const { return a[i][0] + a[i][1] + a[i][2]; }
};

namespace rkmk_tableaus {

inline const double s3 = std::sqrt(3.0), s6 = std::sqrt(6.0), s15 = std::sqrt(15.0);

inline const RkmkTableau kGauss1{1, {{0.5, 0, 0}, {0, 0, 0}, {0, 0, 0}}, {1.0, 0, 0}};
inline const RkmkTableau kGauss2{
    2, {{0.25, 0.25 - s3 / 6, 0}, {0.25 + s3 / 6, 0.25, 0}, {0, 0, 0}}, {0.5, 0.5, 0}};
inline const RkmkTableau kGauss3{3,
                                 {{5.0 / 36, 2.0 / 9 - s15 / 15, 5.0 / 36 - s15 / 30},
                                  {5.0 / 36 + s15 / 24, 2.0 / 9, 5.0 / 36 - s15 / 24},
                                  {5.0 / 36 + s15 / 30, 2.0 / 9 + s15 / 15, 5.0 / 36}},
                                 {5.0 / 18, 4.0 / 9, 5.0 / 18}};
inline const RkmkTableau kRadau2{2, {{5.0 / 12, -1.0 / 12, 0}, {0.75, 0.25, 0}, {0, 0, 0}}, {0.75, 0.25, 0}};
inline const RkmkTableau kRadau3{3,
                                 {{(88 - 7 * s6) / 360, (296 - 169 * s6) / 1800, (-2 + 3 * s6) / 225},
                                  {(296 + 169 * s6) / 1800, (88 + 7 * s6) / 360, (-2 - 3 * s6) / 225},
                                  {(16 - s6) / 36, (16 + s6) / 36, 1.0 / 9}},
                                 {(16 - s6) / 36, (16 + s6) / 36, 1.0 / 9}};

}  // namespace rkmk_tableaus

// The tableau of an implicit RKMK integrator; nothing for the others.
inline std::optional<RkmkTableau> rkmk_tableau(Integrator integrator) {
  std::optional<RkmkTableau> t;
  switch (integrator) {
    case Integrator::rkmk_gauss1: t = rkmk_tableaus::kGauss1; break;
    case Integrator::rkmk_gauss2: t = rkmk_tableaus::kGauss2; break;
    case Integrator::rkmk_gauss3: t = rkmk_tableaus::kGauss3; break;
    case Integrator::rkmk_radau2: t = rkmk_tableaus::kRadau2; break;
    case Integrator::rkmk_radau3: t = rkmk_tableaus::kRadau3; break;
    default: return t;
  }
  t->dexpinv_degree = order_of(integrator) - 2;
  return t;
}

}  // namespace lienewton

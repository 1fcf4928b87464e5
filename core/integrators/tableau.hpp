#pragma once
// A Runge-Kutta method as data: its Butcher tableau (A, b; c_i = sum_j a_ij), its order, and the form in which it is
// lifted to a Lie group (section 6). One stepper per form takes any number of stages (steppers.hpp,
// rkmk_stages.hpp); the methods themselves are rows of one table (methods.cpp).
#include <Eigen/Dense>

namespace lienewton::integrators {

enum class Form {
  // Runge-Kutta-Munthe-Kaas, explicit (a_ij = 0 for j >= i): k_i = h dexpinv_{Theta_i}(g(y exp Theta_i)),
  // Theta_i = sum_{j<i} a_ij k_j with the exact dexpinv (3.9), y_k+1 = y_k exp(sum_i b_i k_i).
  explicit_rkmk,
  // Diagonally implicit, Crouch-Grossman (section 6): stage i solves Y_i = Z_i exp(h a_ii g(Y_i)),
  // Z_i = y_k exp(h a_i1 g(Y_1)) ... exp(h a_i,i-1 g(Y_i-1)), an equation of the kind of (1.1);
  // y_k+1 = y_k exp(h b_1 g(Y_1)) ... exp(h b_s g(Y_s)).
  dirk_crouch_grossman,
  // Runge-Kutta-Munthe-Kaas, implicit: the s coupled stages solved as one system in the algebra (rkmk_stages.hpp),
  // dexpinv (3.9) truncated after ad^(p-2).
  implicit_rkmk,
};

struct Tableau {
  Form form;
  int order;          // p of the global error O(h^p), which the order tests and the work-precision fits check
  Eigen::MatrixXd a;  // s x s
  Eigen::VectorXd b;  // s

  int stages() const { return static_cast<int>(b.size()); }
  // c_i = sum_j a_ij, summed left to right (every stepper sees the same rounding of the stage's time).
  double c(int i) const {
    double sum = 0.0;
    for (int j = 0; j < stages(); ++j) sum += a(i, j);
    return sum;
  }
  // b is A's last row, so y_k+1 is the last stage Y_s.
  bool stiffly_accurate() const { return b.transpose() == a.row(stages() - 1); }
  // The highest power of ad kept in an implicit RKMK method's dexpinv (3.9): p - 2 (Munthe-Kaas 1999, section 4:
  // the first term left out changes the step by O(h^p), its leading part vanishing).
  int dexpinv_degree() const { return order - 2; }
  bool solves_stages() const { return form != Form::explicit_rkmk; }
};

}  // namespace lienewton::integrators

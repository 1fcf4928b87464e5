#pragma once
// The stage system's simplified Newton matrix I - h A (x) J, J = dg_{y_k} (dexpinv ~ dexp ~ I, (3.10)/(3.16)), solved
// block by block instead of as one dense sq x sq system (Hairer & Wanner, "Solving Ordinary Differential Equations
// II", 2nd ed., section IV.8). With A^-1 = T Lambda T^-1,
//   I - h A (x) J = (A (x) I)(T (x) I)(Lambda (x) I - h I (x) J)(T^-1 (x) I),
// so the solution of (I - h A (x) J) dK = r is dK = (T (x) I) W with
//   (lambda_m I - h J) W_m = sum_j (T^-1 A^-1)_mj r_j,
// one q x q system per eigenvalue of A^-1. A conjugate pair is solved once, in complex arithmetic: its partner's W
// is the conjugate, and dK takes twice the real part. Radau IIA and Gauss with 3 stages: one real and one complex
// q x q LU instead of a 3q x 3q one.
#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <complex>
#include <vector>

#include "core/solvers/newton_step.hpp"
#include "tableau.hpp"

namespace lienewton::integrators {

// A^-1's eigen-decomposition, one entry per real eigenvalue or conjugate pair (the member with Im > 0).
struct StageDecoupling {
  std::vector<std::complex<double>> lambda;
  std::vector<bool> pair;
  Eigen::MatrixXcd t;  // s x m: the kept eigenvectors (columns of T)
  Eigen::MatrixXcd s;  // m x s: the matching rows of T^-1 A^-1
  // gamma0 of the embedded error estimate (embedded_estimate.hpp): 1 / the real eigenvalue of A^-1 where there is
  // one, so the estimate's filter (I - h gamma0 J) is that block up to the factor gamma0; else 1 / |lambda|.
  double gamma0 = 0;
  int real_block = -1;  // the index of that real eigenvalue, or -1
};

// Of a tableau whose A is invertible and diagonalizable (every implicit RKMK row; tableau_test checks it).
StageDecoupling decoupling_of(const Tableau& tab);

class DecoupledNewtonMatrix {
 public:
  explicit DecoupledNewtonMatrix(const Tableau& tab) : tab_(&tab), d_(decoupling_of(tab)) {}

  // Factors lambda_m I - h J for every block; false when one is singular. A sparse J (a system of bodies) keeps
  // the blocks sparse (sparse LU above kDenseLuMaxDim), each block's analysis reused across factorizations.
  bool factorize(double h, const Eigen::MatrixXd& j);
  bool factorize(double h, const Eigen::SparseMatrix<double>& j);
  // dK of (I - h A (x) J) dK = r, r and dK the stacked stages.
  Eigen::VectorXd solve(const Eigen::VectorXd& r) const;
  // (I - h gamma0 J)^-1 x: the embedded estimate's filter.
  Eigen::VectorXd filter(const Eigen::VectorXd& x) const;
  const StageDecoupling& decoupling() const { return d_; }
  double h() const { return h_; }
  // How the blocks were last factored.
  Factorization factorization() const { return factorization_; }

 private:
  template <class Matrix>
  bool factorize_blocks(double h, const Matrix& j);

  const Tableau* tab_;
  StageDecoupling d_;
  double h_ = 0;
  std::vector<detail::NewtonLu<double>> real_;
  std::vector<detail::NewtonLu<std::complex<double>>> complex_;
  detail::NewtonLu<double> filter_;  // where gamma0 has no real block of its own
  Factorization factorization_ = Factorization::dense_lu;
};

}  // namespace lienewton::integrators

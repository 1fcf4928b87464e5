#include "stage_decoupling.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

#include "core/solvers/newton_step.hpp"

namespace lienewton::integrators {
namespace {

// An eigenvalue whose imaginary part is below this (relative) is real: A's entries are exact to rounding.
constexpr double kRealTolerance = 1e-12;

}  // namespace

StageDecoupling decoupling_of(const Tableau& tab) {
  const Eigen::MatrixXd inverse = tab.a.inverse();
  const Eigen::EigenSolver<Eigen::MatrixXd> eigen(inverse);
  if (eigen.info() != Eigen::Success) throw std::logic_error("a tableau's A^-1 has no eigen-decomposition");
  const Eigen::MatrixXcd t = eigen.eigenvectors();
  const Eigen::MatrixXcd s = t.inverse() * inverse.cast<std::complex<double>>();
  StageDecoupling d;
  std::vector<Eigen::Index> kept;
  for (Eigen::Index m = 0; m < t.cols(); ++m) {
    const std::complex<double> l = eigen.eigenvalues()[m];
    const bool real = std::abs(l.imag()) <= kRealTolerance * std::abs(l);
    if (!real && l.imag() < 0.0) continue;  // its partner with Im > 0 stands for both
    if (real && d.real_block < 0) d.real_block = static_cast<int>(d.lambda.size());
    d.lambda.push_back(real ? std::complex<double>(l.real(), 0.0) : l);
    d.pair.push_back(!real);
    kept.push_back(m);
  }
  d.t.resize(t.rows(), static_cast<Eigen::Index>(kept.size()));
  d.s.resize(static_cast<Eigen::Index>(kept.size()), s.cols());
  for (std::size_t k = 0; k < kept.size(); ++k) {
    d.t.col(static_cast<Eigen::Index>(k)) = t.col(kept[k]);
    d.s.row(static_cast<Eigen::Index>(k)) = s.row(kept[k]);
  }
  d.gamma0 = d.real_block >= 0 ? 1.0 / d.lambda[static_cast<std::size_t>(d.real_block)].real()
                               : 1.0 / std::abs(d.lambda.front());
  return d;
}

namespace {

// lambda I - h J in J's form (dense or sparse), real or complex.
Eigen::MatrixXd shifted(double lambda, double h, const Eigen::MatrixXd& j) {
  return lambda * Eigen::MatrixXd::Identity(j.rows(), j.cols()) - h * j;
}
Eigen::MatrixXcd shifted(std::complex<double> lambda, double h, const Eigen::MatrixXd& j) {
  return lambda * Eigen::MatrixXcd::Identity(j.rows(), j.cols()) - h * j.cast<std::complex<double>>();
}
template <class Scalar>
Eigen::SparseMatrix<Scalar> shifted(Scalar lambda, double h, const Eigen::SparseMatrix<double>& j) {
  Eigen::SparseMatrix<Scalar> id(j.rows(), j.cols());
  id.setIdentity();
  return Eigen::SparseMatrix<Scalar>(lambda * id - Scalar(h) * j.cast<Scalar>());
}

}  // namespace

bool DecoupledNewtonMatrix::factorize(double h, const Eigen::MatrixXd& j) { return factorize_blocks(h, j); }
bool DecoupledNewtonMatrix::factorize(double h, const Eigen::SparseMatrix<double>& j) {
  return factorize_blocks(h, j);
}

template <class Matrix>
bool DecoupledNewtonMatrix::factorize_blocks(double h, const Matrix& j) {
  h_ = h;
  std::size_t pairs = 0;
  for (bool p : d_.pair) pairs += p;
  // Kept, not rebuilt: each block's sparse analysis survives its refactorizations.
  real_.resize(d_.lambda.size() - pairs);
  complex_.resize(pairs);
  bool ok = true;
  std::size_t real = 0, complex = 0;
  for (std::size_t m = 0; m < d_.lambda.size(); ++m) {
    if (d_.pair[m])
      ok = complex_[complex++].factorize(shifted(d_.lambda[m], h, j)) && ok;
    else
      ok = real_[real++].factorize(shifted(d_.lambda[m].real(), h, j)) && ok;
  }
  if (d_.real_block < 0) ok = filter_.factorize(shifted(1.0, h * d_.gamma0, j)) && ok;
  factorization_ = real_.empty() ? complex_.front().factorization() : real_.front().factorization();
  return ok;
}

Eigen::VectorXd DecoupledNewtonMatrix::solve(const Eigen::VectorXd& r) const {
  const Eigen::Index s = tab_->stages(), q = r.size() / s;
  Eigen::VectorXd dk = Eigen::VectorXd::Zero(r.size());
  std::size_t real = 0, complex = 0;
  for (std::size_t m = 0; m < d_.lambda.size(); ++m) {
    const Eigen::Index mi = static_cast<Eigen::Index>(m);
    Eigen::VectorXcd rhs = Eigen::VectorXcd::Zero(q);
    for (Eigen::Index i = 0; i < s; ++i) rhs += d_.s(mi, i) * r.segment(i * q, q).cast<std::complex<double>>();
    if (d_.pair[m]) {
      const Eigen::VectorXcd w = complex_[complex++].solve(rhs);
      for (Eigen::Index i = 0; i < s; ++i) dk.segment(i * q, q) += 2.0 * (d_.t(i, mi) * w).real();
    } else {
      const Eigen::VectorXd w = real_[real++].solve(Eigen::VectorXd(rhs.real()));
      for (Eigen::Index i = 0; i < s; ++i) dk.segment(i * q, q) += d_.t(i, mi).real() * w;
    }
  }
  return dk;
}

Eigen::VectorXd DecoupledNewtonMatrix::filter(const Eigen::VectorXd& x) const {
  if (d_.real_block < 0) return filter_.solve(x);
  // I - h gamma0 J = gamma0 (lambda I - h J) with lambda = 1 / gamma0.
  std::size_t index = 0;
  for (int m = 0; m < d_.real_block; ++m) index += !d_.pair[static_cast<std::size_t>(m)];
  return real_[index].solve(x) / d_.gamma0;
}

}  // namespace lienewton::integrators

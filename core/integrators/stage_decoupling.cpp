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

bool DecoupledNewtonMatrix::factorize(double h, const Eigen::MatrixXd& j) {
  h_ = h;
  real_.clear();
  complex_.clear();
  const Eigen::Index q = j.rows();
  bool ok = true;
  for (std::size_t m = 0; m < d_.lambda.size(); ++m) {
    if (d_.pair[m]) {
      complex_.emplace_back(Eigen::MatrixXcd(d_.lambda[m] * Eigen::MatrixXcd::Identity(q, q) -
                                             h * j.cast<std::complex<double>>()));
      ok = ok && detail::well_conditioned(complex_.back());
    } else {
      real_.emplace_back(d_.lambda[m].real() * Eigen::MatrixXd::Identity(q, q) - h * j);
      ok = ok && detail::well_conditioned(real_.back());
    }
  }
  if (d_.real_block < 0) {
    filter_.compute(Eigen::MatrixXd::Identity(q, q) - (h * d_.gamma0) * j);
    ok = ok && detail::well_conditioned(filter_);
  }
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

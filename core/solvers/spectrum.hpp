#pragma once
// What the stiff solvers ask of the eigenvalues mu of a Jacobian J = dg: how fast its fastest component decays
// (max -Re mu: is a step stiff, is it dissipative) and whether I - tau J stays regular over a step. The eigenvalues
// cost O(q^3) (a dense real Schur form, eigenvalues.hpp), so they are computed once per matrix, and only where
// ||J||_F, which bounds every |mu|, cannot answer alone.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "eigenvalues.hpp"

namespace lienewton {

class Spectrum {
 public:
  explicit Spectrum(Eigen::MatrixXd j) : j_(std::move(j)), norm_(j_.norm()) {}

  const Eigen::MatrixXd& matrix() const { return j_; }
  double norm() const { return norm_; }  // ||J||_F >= |mu| for every eigenvalue

  // Whether some component decays faster than rate: -Re mu > rate for an eigenvalue mu.
  bool decays_faster_than(double rate) const { return norm_ > rate && decay_rate() > rate; }
  // max(0, -Re mu) over the eigenvalues.
  double decay_rate() const { return std::max(0.0, -eigenvalues().real().minCoeff()); }
  // Whether I - tau J is regular for every tau in [0, h]: it is singular only where tau mu = 1 for a real positive
  // eigenvalue mu >= 1/h, so no eigenvalue with h |mu| >= 1 and Re mu > 0 suffices.
  bool stays_regular(double h) const {
    if (h * norm_ < 1.0) return true;
    const Eigen::VectorXcd& mu = eigenvalues();
    for (Eigen::Index i = 0; i < mu.size(); ++i)
      if (h * std::abs(mu[i]) >= 1.0 && mu[i].real() > 0.0) return false;
    return true;
  }

 private:
  const Eigen::VectorXcd& eigenvalues() const {
    if (!mu_) mu_ = eigenvalues_of(j_);
    return *mu_;
  }

  Eigen::MatrixXd j_;
  double norm_;
  mutable std::optional<Eigen::VectorXcd> mu_;
};

}  // namespace lienewton

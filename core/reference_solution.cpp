#include "reference_solution.hpp"

#include <cmath>

#include "cancellation.hpp"
#include "groups/with_group.hpp"
#include "problems.hpp"

namespace lienewton {
namespace {

// One RKMK4 step: stages in the algebra, each pulled back by dexpinv of its own offset.
template <class G>
typename G::Element rkmk4_step(const G& group, const VectorField<G>& field, const typename G::Element& y, double h) {
  using Vector = typename G::Vector;
  auto stage = [&](const Vector& offset) {
    const Vector g = field.g(group.times_exp(y, offset));
    return Vector(h * group.dexpinv(group.spectral(offset), g));
  };
  const Vector k1 = h * field.g(y);
  const Vector k2 = stage(0.5 * k1);
  const Vector k3 = stage(0.5 * k2);
  const Vector k4 = stage(k3);
  return group.times_exp(y, (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0);
}

template <class G>
Eigen::MatrixXd integrate_reference(const G& group, ProblemKind problem, const RigidBodyParams& rb,
                                    const Eigen::MatrixXd& y0, double t_end) {
  const auto field = make_field(group, problem, rb);
  const int steps = std::max(64, static_cast<int>(std::ceil(t_end * kReferenceStepsPerUnit)));
  const double h = t_end / steps;
  typename G::Element y = y0;
  for (int k = 0; k < steps; ++k) {
    throw_if_cancelled();
    y = rkmk4_step(group, *field, y, h);
  }
  return y;
}

}  // namespace

Eigen::MatrixXd reference_solution(ProblemKind problem, const RigidBodyParams& rb, const Eigen::MatrixXd& y0,
                                   double t_end) {
  return with_group(static_cast<int>(y0.rows()), [&](const auto& group) {
    return integrate_reference(group, problem, rb, y0, t_end);
  });
}

}  // namespace lienewton

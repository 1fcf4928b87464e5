#pragma once
// The test problems: vector fields g: G -> g of y' = y g(y) with their exact differentials
// dg_y(U) = d/dt g(y exp(tU)) at t = 0 (the tangent at y in direction U is y U).
// Each is written once on matrices; VectorFieldOf adapts it to a group's coordinates.
#include <Eigen/Dense>
#include <memory>

#include "lie_groups.hpp"
#include "solve.hpp"

namespace lienewton {

template <class G>
class VectorField {
 public:
  using Element = typename G::Element;
  using Vector = typename G::Vector;
  virtual ~VectorField() = default;
  virtual Vector g(const Element& y) const = 0;
  virtual Vector dg(const Element& y, const Vector& u) const = 0;
};

// g(y) = diag(diag(y,1),1) - diag(diag(y,1),-1); linear in y, so dg_y(U) = g(yU).
struct PaperLinear {
  template <class M>
  M g(const M& y) const {
    M out = M::Zero(y.rows(), y.cols());
    for (Eigen::Index i = 0; i + 1 < y.rows(); ++i) {
      out(i, i + 1) = y(i, i + 1);
      out(i + 1, i) = -y(i, i + 1);
    }
    return out;
  }
  template <class M>
  M dg(const M& y, const M& u) const {
    return g(M(y * u));
  }
};

// U = sin.(y) (2y - 5y^2), g(y) = U - U^T; dg by the product rule along y' = y U_dir.
struct PaperSine {
  template <class M>
  M g(const M& y) const {
    const M u = y.array().sin().matrix() * (2.0 * y - 5.0 * y * y);
    return u - u.transpose();
  }
  template <class M>
  M dg(const M& y, const M& dir) const {
    const M dy = y * dir;
    const M s = y.array().sin().matrix();
    const M ds = (y.array().cos() * dy.array()).matrix();
    const M p = 2.0 * y - 5.0 * y * y;
    const M dp = 2.0 * dy - 5.0 * (dy * y + y * dy);
    const M du = ds * p + s * dp;
    return du - du.transpose();
  }
};

// The free rigid body: y' = y hat(I^-1 y^T m), m the constant spatial angular momentum; the body momentum
// M = y^T m and the kinetic energy E = 1/2 M^T I^-1 M are conserved.
struct RigidBody {
  RigidBodyParams params;
  template <class M>
  M g(const M& y) const {
    return embed(body_velocity(Eigen::Matrix3d(y).transpose() * params.momentum));
  }
  template <class M>
  M dg(const M& y, const M& dir) const {  // d/dt of y^T m along y' = y dir is dir^T y^T m
    return embed(body_velocity(Eigen::Matrix3d(dir).transpose() * (Eigen::Matrix3d(y).transpose() * params.momentum)));
  }
  double energy(const Eigen::Matrix3d& y) const {
    const Eigen::Vector3d m = y.transpose() * params.momentum;
    return 0.5 * m.dot(body_velocity(m));
  }

 private:
  Eigen::Vector3d body_velocity(const Eigen::Vector3d& m) const { return m.cwiseQuotient(params.inertia); }
  static Eigen::Matrix3d embed(const Eigen::Vector3d& w) { return so3::hat(w); }
};

template <class G, class Problem>
class VectorFieldOf final : public VectorField<G> {
 public:
  using typename VectorField<G>::Element;
  using typename VectorField<G>::Vector;
  VectorFieldOf(G group, Problem problem) : group_(group), problem_(std::move(problem)) {}
  Vector g(const Element& y) const override { return group_.vee(problem_.g(y)); }
  Vector dg(const Element& y, const Vector& u) const override {
    return group_.vee(problem_.dg(y, Element(group_.hat(u))));
  }
  const Problem& problem() const { return problem_; }

 private:
  G group_;
  Problem problem_;
};

// The field of a request's problem on group G (rigid-body requires n = 3; validate() checks).
template <class G>
std::unique_ptr<VectorField<G>> make_field(const G& group, ProblemKind kind, const RigidBodyParams& rb) {
  switch (kind) {
    case ProblemKind::paper_linear: return std::make_unique<VectorFieldOf<G, PaperLinear>>(group, PaperLinear{});
    case ProblemKind::paper_sine: return std::make_unique<VectorFieldOf<G, PaperSine>>(group, PaperSine{});
    case ProblemKind::rigid_body: return std::make_unique<VectorFieldOf<G, RigidBody>>(group, RigidBody{rb});
  }
  return nullptr;
}

}  // namespace lienewton

#pragma once
// A user's program (program.hpp) as the vector field of a request on group G: g and dg evaluated on the
// group's matrices, each value checked to lie in G's algebra (hat(vee(g)) = g to rounding: skew on SO(n)).
// A value off the algebra is never projected behind the user's back: the field answers NaN, so the iteration
// stops as non_finite, and keeps the first defect for the result's reason.
#include <Eigen/Dense>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>

#include "../problem_spec.hpp"
#include "../problems.hpp"
#include "algebra_defect.hpp"
#include "program.hpp"

namespace lienewton {

template <class G>
class UserVectorField final : public VectorField<G> {
 public:
  using typename VectorField<G>::Element;
  using typename VectorField<G>::Vector;
  UserVectorField(G group, std::shared_ptr<const user_field::Program> program)
      : group_(std::move(group)), program_(std::move(program)) {}

  // The program reads t as it runs: an integrator sets each stage's time, a solve leaves it at 0.
  void set_time(double t) override { t_ = t; }
  Vector g(const Element& y) const override {
    return with_results([&](Eigen::MatrixXd& value, Eigen::MatrixXd&) {
      program_->eval(as_matrix(y), t_, value);
      return in_algebra(value);
    });
  }
  Vector dg(const Element& y, const Vector& u) const override {
    const Element dir = group_.hat(u);
    return with_results([&](Eigen::MatrixXd& value, Eigen::MatrixXd& tangent) {
      program_->eval_with_tangent(as_matrix(y), t_, as_matrix(Element(group_.tangent(y, dir))), value, tangent);
      return in_algebra(tangent);
    });
  }
  // dg_y's matrix on G's basis: the program's values once, then its tangents along y U for the basis elements U
  // a pass at a time (tangent(y, U) is y U on G's matrices), each formed when its pass asks for it, so that no
  // more than a pass's directions are held (on a system of k bodies a stack of all would be k^3 entries).
  typename G::Operator dg_matrix(const G& group, const Element& y) const override {
    OperatorColumns<G> columns(group);
    program_->eval_along(
        as_matrix(y), t_, group.dim(),
        [&](Eigen::Index d, Eigen::MatrixXd& dy) {
          dy = as_matrix(Element(group_.tangent(y, group_.hat(basis_vector(group_, static_cast<int>(d))))));
        },
        [&](Eigen::Index d, const Eigen::MatrixXd& derivative) {
          columns.set(static_cast<int>(d), in_algebra(derivative));
        });
    return columns.take();
  }
  // The first value found off the algebra (its defect; 0 while none was).
  double defect() const { return defect_.load(); }

 private:
  // y as the program reads it (program_matrix), in place where the Element is that matrix already (a square Eigen
  // matrix; a system of bodies' strip [y1 ... yk] is not: the program reads diag(y1, ..., yk)).
  decltype(auto) as_matrix(const Element& y) const {
    if constexpr (Element::RowsAtCompileTime == Element::ColsAtCompileTime &&
                  std::is_same_v<Element, Eigen::Matrix<double, Element::RowsAtCompileTime,
                                                         Element::ColsAtCompileTime>>)
      return (y);
    else
      return program_matrix(group_, y);
  }
  Vector in_algebra(const Eigen::MatrixXd& m) const {
    const Vector v = group_.vee(program_element(group_, m));
    const double defect = program_distance(group_, Element(group_.hat(v)), m);  // algebra_defect, vee taken once
    if (!std::isfinite(defect) || within_rounding(defect, m)) return v;
    double none = 0;
    defect_.compare_exchange_strong(none, defect);
    return Vector::Constant(v.size(), std::numeric_limits<double>::quiet_NaN());
  }

  // f(value, tangent) on matrices for the program's results: a small program's per thread, sized once (a solve
  // calls g and dg thousands of times); a larger one's the call's own, so no thread holds them after the request.
  template <class F>
  Vector with_results(F&& f) const {
    if (program_->kept_per_thread()) {
      thread_local Eigen::MatrixXd value, tangent;
      return f(value, tangent);
    }
    Eigen::MatrixXd value, tangent;
    return f(value, tangent);
  }

  G group_;
  std::shared_ptr<const user_field::Program> program_;
  mutable std::atomic<double> defect_{0};
  double t_ = 0;
};

// The field of a request's problem on G: the user's program g when given, else the built-in problem.
template <class G>
std::unique_ptr<VectorField<G>> make_field(const G& group, const ProblemSpec& problem) {
  if (problem.g)
    return std::make_unique<UserVectorField<G>>(group, problem.program());
  return make_field(group, problem.kind, problem.rigid_body, problem.heavy_top, problem.stiff_body,
                    problem.chain);
}

// Why a run of the user's field stopped as non_finite, when a value left the algebra: names g, the iteration
// and the defect's size. Empty otherwise.
template <class G>
std::string off_algebra_reason(const G& group, const VectorField<G>& field, int iteration) {
  const auto* user = dynamic_cast<const UserVectorField<G>*>(&field);
  if (!user || user->defect() == 0) return {};
  return "g(y) left the algebra of " + std::string(group.name()) + " at iteration " + std::to_string(iteration) +
         ": ||g - hat(vee(g))|| = " + std::to_string(user->defect()) + " (on SO(n) g must be skew: write g = u - u' or skew(u))";
}

}  // namespace lienewton

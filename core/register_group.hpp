#pragma once
// register_group<Family>(): a family of groups made available to every request under Family::kName, with the
// request code (requests_on_group.hpp) compiled for each of its groups here. A family is
//   struct Family {
//     static constexpr const char* kName = "SO";                       // as requests name it
//     template <class F> static decltype(auto) with_group(int n, F&& f);  // f(the group of index n)
//     static constexpr int kOnlyIndex = 3;  // optional: the index of its one member (absent: every n is one)
//     static constexpr int kMaxIndex = 128;  // optional: the largest n it takes (absent: fields::n's bound)
//   };
// and each group it hands to f satisfies LieGroup. Registering is one line beside the family:
//   inline const bool kMyGroupRegistered = register_group<MyFamily>();
#include <memory>

#include "group_registry.hpp"
#include "requests_on_group.hpp"

namespace lienewton {

template <class Family>
class FamilyOf final : public GroupFamily {
 public:
  std::string name() const override { return Family::kName; }
  std::string title(int n) const override {
    return Family::with_group(n, [](const auto& g) { return std::string(g.name()); });
  }
  std::optional<int> only_index() const override {
    if constexpr (requires { Family::kOnlyIndex; }) {
      return Family::kOnlyIndex;
    } else {
      return std::nullopt;
    }
  }
  std::optional<int> max_index() const override {
    if constexpr (requires { Family::kMaxIndex; }) {
      return Family::kMaxIndex;
    } else {
      return std::nullopt;
    }
  }
  MatrixShape matrix_shape(int n) const override {
    return Family::with_group(n, [](const auto& g) {
      const Eigen::MatrixXd m = g.matrix(g.identity());
      return MatrixShape{static_cast<int>(m.rows()), static_cast<int>(m.cols())};
    });
  }
  int algebra_dim(int n) const override {
    return Family::with_group(n, [](const auto& g) { return g.dim(); });
  }
  std::string algebra_dimension() const override {
    return Family::with_group(kSomeIndex, [](const auto& g) { return std::string(g.kAlgebraDimension); });
  }
  double log_radius() const override {
    return Family::with_group(kSomeIndex, [](const auto& g) { return double(g.kLogRadius); });
  }
  bool defines(ProblemKind kind, int n) const override {
    return Family::with_group(n, [&](const auto& g) { return defined_on(kind, g); });
  }
  Eigen::MatrixXd random(int n, std::uint64_t seed) const override {
    return Family::with_group(n, [&](const auto& g) { return g.matrix(g.random(seed)); });
  }
  std::string not_an_element(int n, const Eigen::MatrixXd& m, const std::string& what) const override {
    return Family::with_group(n, [&](const auto& g) { return g.not_an_element(m, what); });
  }
  std::string not_reachable(int n, const Eigen::MatrixXd& y0, const Eigen::MatrixXd& z) const override {
    return Family::with_group(n, [&](const auto& g) { return g.not_reachable(y0, z); });
  }
  Eigen::MatrixXd project(int n, const Eigen::MatrixXd& m) const override {
    return Family::with_group(n, [&](const auto& g) { return g.matrix(g.project(g.element(m))); });
  }
  bool same_root(int n, const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) const override {
    return Family::with_group(n, [&](const auto& g) { return lienewton::same_root(g, g.element(a), g.element(b)); });
  }
  Eigen::MatrixXd program_matrix(int n, const Eigen::MatrixXd& m) const override {
    return Family::with_group(n, [&](const auto& g) { return lienewton::program_matrix(g, g.element(m)); });
  }
  int program_size(int n) const override {
    return Family::with_group(n, [](const auto& g) {
      return static_cast<int>(lienewton::program_matrix(g, g.identity()).rows());
    });
  }
  double algebra_defect(int n, const Eigen::MatrixXd& m) const override {
    return Family::with_group(n, [&](const auto& g) { return lienewton::algebra_defect(g, m); });
  }

  std::vector<BodyFrame> body_frames(int n, const Eigen::MatrixXd& m) const override {
    return Family::with_group(n, [&](const auto& g) -> std::vector<BodyFrame> {
      if constexpr (requires { g.body_frames(g.element(m)); }) {
        return g.body_frames(g.element(m));
      } else if constexpr (requires { g.rotation(g.element(m)); }) {
        return {{g.rotation(g.element(m)), Eigen::Vector3d::Zero()}};
      } else {
        return {};
      }
    });
  }

  SolveResult solve(const SolveRequest& req, const TraceCallback& on_iteration) const override {
    return Family::with_group(req.problem.n, [&](const auto& g) { return solve_on(g, req, on_iteration); });
  }
  BasinResult basins(const BasinRequest& req, const BasinRowCallback& on_row, const WorkFarm* farm) const override {
    return Family::with_group(req.solve.problem.n, [&](const auto& g) { return basins_on(g, req, on_row, farm); });
  }
  IntegrateResult integrate(const IntegrateRequest& req, const Eigen::MatrixXd& y0,
                            const StepCallback& on_step) const override {
    return Family::with_group(req.problem.n, [&](const auto& g) { return integrate_on(g, req, y0, on_step); });
  }
  ReferenceSolution reference_solution(const ProblemSpec& problem, const Eigen::MatrixXd& y0,
                                       double t_end) const override {
    return Family::with_group(problem.n, [&](const auto& g) { return reference_on(g, problem, y0, t_end); });
  }
  double field_rate(const ProblemSpec& problem, const Eigen::MatrixXd& y) const override {
    return Family::with_group(problem.n, [&](const auto& g) { return field_rate_on(g, problem, y); });
  }

 private:
  // Facts every member of the family shares (the log radius, the formula of the dimension), read off one.
  static constexpr int kSomeIndex = 2;
};

template <class Family>
bool register_group() {
  add_group_family(std::make_unique<FamilyOf<Family>>());
  return true;
}

}  // namespace lienewton

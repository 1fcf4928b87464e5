// Defaults from each problem's time scale (core/time_scale.hpp): the stability map's default grid runs for every
// built-in problem (rigid-body, heavy-top and stiff-body fix n = 3, so their maps sweep h alone), and work-precision at its
// defaults (every integrator, the problem's step sizes) gives each integrator's nominal order within 0.2 or an
// honest null with its reason.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/integrate.hpp"
#include "core/integrators/methods.hpp"
#include "core/order_fit.hpp"
#include "core/problems.hpp"
#include "core/sweep.hpp"
#include "core/time_scale.hpp"
#include "core/work_precision.hpp"

namespace lienewton {
namespace {

ProblemSpec built_in(ProblemKind kind) {
  ProblemSpec p{.kind = kind};
  if (const auto group = required_group(kind)) p.group = *group;
  return p;
}

TEST(ProblemDefaults, StabilityMapDefaultsRunForEveryBuiltInProblem) {
  for (ProblemKind kind : kAllProblems) {
    SweepRequest req;
    req.problem = built_in(kind);
    const SweepRequest full = with_defaults(req);
    EXPECT_NO_THROW(validate(full)) << to_string(kind);
    const bool fixed = required_index(kind).has_value();
    EXPECT_EQ(full.n.size(), fixed ? 1u : 14u) << to_string(kind);
    if (!fixed) continue;
    EXPECT_EQ(full.n.front(), 3);
    req.h = {0.25, 1.0};  // two of the default h: the whole grid is the optimised build's
    const SweepResult r = sweep(req);
    EXPECT_EQ(r.cells.size(), req.methods.size() * 2) << to_string(kind);
  }
}

// The heavy top spins at 150 rad/s: its steps start where h |omega| is small, not at the rigid body's 2^-2.
TEST(ProblemDefaults, StepSizesFollowTheTimeScale) {
  const std::vector<double> body = default_step_sizes(built_in(ProblemKind::rigid_body), 1.0);
  const std::vector<double> top = default_step_sizes(built_in(ProblemKind::heavy_top), 1.0);
  ASSERT_EQ(body.size(), static_cast<std::size_t>(kDefaultStepCount));
  ASSERT_EQ(top.size(), 4u) << "2^-10 ... 2^-13: at most kMaxDefaultRunSteps steps per run to t = 1";
  EXPECT_EQ(default_step_sizes(built_in(ProblemKind::heavy_top), 0.125).size(),
            static_cast<std::size_t>(kDefaultStepCount));
  EXPECT_EQ(body.front(), kMaxDefaultStep);
  const double rate = field_rate(built_in(ProblemKind::heavy_top));
  EXPECT_GE(rate, 150.0) << "at least the spin";
  EXPECT_LE(top.front() * rate, 1.0);
  EXPECT_GT(2 * top.front() * rate, 1.0) << "the largest such power of two";
  for (std::size_t k = 1; k < top.size(); ++k) EXPECT_EQ(top[k], top[k - 1] / 2);
}

// integrate without h: 0.1 where h rho <= 1 allows it (the rigid body), the time scale's largest step where it does
// not (the heavy top: h rho <= 1 at 150 rad/s), never past t_end, and the run it gives converges.
TEST(ProblemDefaults, IntegrateStepFollowsTheTimeScale) {
  IntegrateRequest body{.problem = built_in(ProblemKind::rigid_body)};
  resolve_defaults(body);
  EXPECT_EQ(*body.h, kDefaultIntegrationStep);
  IntegrateRequest top{.problem = built_in(ProblemKind::heavy_top), .t_end = 0.25};
  resolve_defaults(top);
  const double rate = field_rate(top.problem);
  EXPECT_LE(*top.h * rate, 1.0);
  EXPECT_GT(2 * *top.h * rate, 1.0);
  const IntegrateResult run = integrate(top);
  EXPECT_EQ(run.status, Status::converged) << run.reason;
  EXPECT_EQ(run.steps.size(), static_cast<std::size_t>(std::llround(0.25 / *top.h)));
  IntegrateRequest short_run{.problem = built_in(ProblemKind::rigid_body), .t_end = 0.05};
  resolve_defaults(short_run);
  EXPECT_EQ(*short_run.h, 0.05) << "one step to t_end, not a refusal of h > t_end";
  IntegrateRequest given{.problem = built_in(ProblemKind::heavy_top), .h = 0.125};
  resolve_defaults(given);
  EXPECT_EQ(*given.h, 0.125) << "a given h is the request's";
}

#if !defined(LIENEWTON_SANITIZED)
// One test per problem: the stiff body's and the chain's defaults take most of the time, and ctest runs them side by
// side.
class WorkPrecisionDefaults : public ::testing::TestWithParam<ProblemKind> {};

TEST_P(WorkPrecisionDefaults, FitNominalOrdersOrSayWhyNot) {
  const ProblemKind kind = GetParam();
  WorkPrecisionRequest req;
  req.problem = built_in(kind);
  const WorkPrecisionResult res = work_precision(req);
  int fitted = 0;
  for (const WorkPrecisionSeries& s : res.series) {
    const int p = order_of(s.choice.integrator);
    std::printf("%s %s: p = %s (nominal %d): %s\n", std::string(to_string(kind)).c_str(),
                std::string(to_string(s.choice.integrator)).c_str(),
                s.fitted_order ? std::to_string(*s.fitted_order).c_str() : "null", p, s.fit_reason.c_str());
    if (s.fitted_order) {
      ++fitted;
      EXPECT_NEAR(*s.fitted_order, p, 0.2) << to_string(kind) << " " << to_string(s.choice.integrator);
    } else {
      EXPECT_FALSE(s.fit_reason.empty());
    }
    for (const WorkPrecisionPoint& pt : s.points) EXPECT_TRUE(pt.in_fit || !pt.excluded.empty());
  }
  EXPECT_GE(fitted, 1) << to_string(kind) << ": the defaults must show some order";
}

INSTANTIATE_TEST_SUITE_P(Problems, WorkPrecisionDefaults, ::testing::ValuesIn(kAllProblems),
                         [](const ::testing::TestParamInfo<ProblemKind>& info) {
                           std::string name(to_string(info.param));
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });
#endif

}  // namespace
}  // namespace lienewton

// Adaptive steps (rtol/atol, step doubling): the global error follows the tolerance against an independent
// reference, rejected tries are counted and reported, the minimum step and the bound on tries end the run with
// their own status naming t, bad tolerances are refused naming the field, and work-precision runs against
// tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <unsupported/Eigen/MatrixFunctions>

#include "core/integrate.hpp"
#include "core/problems.hpp"
#include "core/request_error.hpp"
#include "core/work_precision.hpp"
#include "matrix_ode_reference.hpp"

namespace lienewton {
namespace {

constexpr double kTEnd = 2.0;

IntegrateRequest adaptive(Integrator integrator, double tol, ProblemSpec problem = {.kind = ProblemKind::rigid_body}) {
  IntegrateRequest req{.problem = std::move(problem), .h = 0.1, .t_end = kTEnd, .integrator = integrator,
                       .reference = false};
  req.rtol = tol;
  req.solver.tol = 1e-15;
  return req;
}

// What every converged adaptive run must say of itself: its accepted steps tile [0, t_end], each with an error
// estimate at most 1, and the rejected tries add up.
void expect_honest_steps(const IntegrateResult& r, double t_end) {
  ASSERT_TRUE(r.adaptive);
  ASSERT_FALSE(r.steps.empty());
  double t = 0.0;
  int rejected = 0;
  for (const StepRecord& s : r.steps) {
    EXPECT_GT(s.h, 0.0);
    EXPECT_NEAR(s.t, t + s.h, 1e-12 * t_end);
    ASSERT_TRUE(s.error_estimate.has_value());
    EXPECT_LE(*s.error_estimate, 1.0);
    EXPECT_EQ(s.status, Status::converged);
    t = s.t;
    rejected += s.rejected;
  }
  EXPECT_EQ(r.steps.back().t, t_end);
  EXPECT_EQ(r.rejected, rejected);
}

// The global error at t = 2 on the rigid body, against RK4 on the matrix entries (matrix_ode_reference.hpp),
// follows the tolerance (rtol = atol): within a factor 100 of it either way, and smaller at every tighter tolerance,
// for the explicit baseline and an implicit RKMK method (non-stiff: both estimate by step doubling).
TEST(AdaptiveSteps, GlobalErrorFollowsTheTolerance) {
  const ProblemSpec problem{.kind = ProblemKind::rigid_body};
  const RigidBody body{problem.rigid_body};
  const Eigen::MatrixXd y_ref = test::matrix_ode_reference(
      [&](const Eigen::MatrixXd& y) { return Eigen::MatrixXd(body.g(Eigen::Matrix3d(y))); }, problem.start(), kTEnd);
  for (Integrator integrator : {Integrator::rkmk4, Integrator::rkmk_gauss2}) {
    double last_error = std::numeric_limits<double>::infinity();
    std::size_t last_steps = 0;
    for (double tol : {1e-4, 1e-6, 1e-8, 1e-10}) {
      const IntegrateResult r = integrate(adaptive(integrator, tol));
      ASSERT_EQ(r.status, Status::converged) << r.reason;
      expect_honest_steps(r, kTEnd);
      const double error = (r.y - y_ref).norm();
      EXPECT_LT(error, 100 * tol) << to_string(integrator) << " tol " << tol;
      EXPECT_GT(error, tol / 100) << to_string(integrator) << " tol " << tol;
      EXPECT_LT(error, last_error) << to_string(integrator) << " tol " << tol;
      EXPECT_GT(r.steps.size(), last_steps) << to_string(integrator) << " tol " << tol;
      last_error = error;
      last_steps = r.steps.size();
    }
  }
}

// A rotation about a fixed axis whose speed has a pulse at t = 1: y' = y w(t) A, w = 1 + 20 exp(-((t-1)/0.1)^2),
// solved exactly by y(0) exp(theta(t) A), theta(2) = 2 + 2 sqrt(pi) (the pulse's tails beyond [0, 2] are below
// 1e-40). Steps that run into the pulse are rejected and shorter ones taken; the error stays with tol.
TEST(AdaptiveSteps, RejectsStepsThatRunIntoAPulse) {
  ProblemSpec problem{.n = 3};
  problem.g = "(1 + 20*exp(-((t - 1)/0.1)^2)) * [0 1 0; -1 0 0; 0 0 0]";
  Eigen::Matrix3d a;
  a << 0, 1, 0, -1, 0, 0, 0, 0, 0;
  const double theta = 2.0 + 2.0 * std::sqrt(std::numbers::pi);
  const Eigen::MatrixXd exact = problem.start() * Eigen::Matrix3d(theta * a).exp();
  for (Integrator integrator : {Integrator::rkmk4, Integrator::dirk_cg3}) {
    std::vector<StepRecord> streamed;
    const IntegrateResult r = integrate(adaptive(integrator, 1e-7, problem), [&](const StepRecord& s) {
      streamed.push_back(s);
      return true;
    });
    ASSERT_EQ(r.status, Status::converged) << r.reason;
    expect_honest_steps(r, kTEnd);
    int rejected_after_first = 0;
    double h_in_pulse = kTEnd, h_before = 0.0;
    for (const StepRecord& s : r.steps) {
      if (s.step > 1) rejected_after_first += s.rejected;
      if (std::abs(s.t - 1.0) < 0.1) h_in_pulse = std::min(h_in_pulse, s.h);
      if (s.t < 0.8) h_before = std::max(h_before, s.h);
    }
    EXPECT_GT(rejected_after_first, 0) << to_string(integrator);
    EXPECT_LT(h_in_pulse, h_before / 10) << to_string(integrator);
    EXPECT_LT((r.y - exact).norm(), 1e-5) << to_string(integrator);
    ASSERT_EQ(streamed.size(), r.steps.size());
    EXPECT_EQ(streamed.back().rejected, r.steps.back().rejected);
    EXPECT_EQ(streamed.back().error_estimate, r.steps.back().error_estimate);
  }
}

// g = sqrt(0.5 - t) A is not finite past t = 0.5: every try across it fails, the step shrinks towards t = 0.5
// until it falls below the minimum step, and the run ends with min_step naming t, its y the last accepted state.
TEST(AdaptiveSteps, MinimumStepEndsTheRunNamingT) {
  ProblemSpec problem{.n = 3};
  problem.g = "sqrt(0.5 - t) * [0 1 0; -1 0 0; 0 0 0]";
  for (Integrator integrator : {Integrator::rkmk4, Integrator::rkmk_radau2}) {
    IntegrateRequest req = adaptive(integrator, 1e-6, problem);
    req.t_end = 1.0;
    req.reference = true;
    const IntegrateResult r = integrate(req);
    ASSERT_EQ(r.status, Status::min_step) << r.reason;
    const std::size_t at = r.reason.find("at t = ");
    ASSERT_NE(at, std::string::npos) << r.reason;
    EXPECT_NEAR(std::stod(r.reason.substr(at + 7)), 0.5, 1e-6) << r.reason;
    EXPECT_NE(r.reason.find("below the minimum step"), std::string::npos) << r.reason;
    ASSERT_FALSE(r.steps.empty());
    EXPECT_LE(r.steps.back().t, 0.5);
    EXPECT_GT(r.steps.back().t, 0.5 - 1e-6);
    EXPECT_TRUE(r.y.allFinite());
    EXPECT_FALSE(r.global_error.has_value());  // no error against t_end for a y that is not at t_end
  }
}

TEST(AdaptiveSteps, BoundOnTriesEndsTheRunNamingT) {
  IntegrateRequest req = adaptive(Integrator::rkmk4, 1e-10);
  req.max_steps = 5;
  const IntegrateResult r = integrate(req);
  ASSERT_EQ(r.status, Status::max_steps) << r.reason;
  EXPECT_LE(static_cast<int>(r.steps.size()) + r.rejected, 5);
  EXPECT_NE(r.reason.find("max_steps = 5"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("reached t = "), std::string::npos) << r.reason;
}

// With h = t_end the first try is far too long at tol 1e-8: it is rejected (and counted), as are failing stages.
TEST(AdaptiveSteps, FirstStepTooLongIsRejected) {
  IntegrateRequest req = adaptive(Integrator::rkmk_radau3, 1e-8);
  req.h = kTEnd;
  req.frames = 4;
  const IntegrateResult r = integrate(req);
  ASSERT_EQ(r.status, Status::converged) << r.reason;
  expect_honest_steps(r, kTEnd);
  EXPECT_GT(r.steps.front().rejected, 0);
  // Frames of adaptive steps: between frames and 2 frames states after y(0), the last at t_end.
  EXPECT_GE(r.frames.size(), 5u);
  EXPECT_LE(r.frames.size(), 9u);
  EXPECT_EQ(r.frame_times.back(), kTEnd);
  EXPECT_EQ(r.frame_steps.back(), static_cast<int>(r.steps.size()));
  EXPECT_LT((r.frames.back() - r.y).norm(), 1e-15);
}

// Fixed steps keep their meaning: every record's h is t_end / steps and has no error estimate.
TEST(AdaptiveSteps, FixedStepsReportTheirStep) {
  const IntegrateResult r = integrate(IntegrateRequest{.h = 0.25, .t_end = 1.0, .reference = false});
  ASSERT_EQ(r.status, Status::converged);
  EXPECT_FALSE(r.adaptive);
  for (const StepRecord& s : r.steps) {
    EXPECT_EQ(s.h, 0.25);
    EXPECT_FALSE(s.error_estimate.has_value());
  }
}

std::string unprocessable_field(const std::function<void()>& f) {
  try {
    f();
  } catch (const RequestError& e) {
    EXPECT_EQ(e.kind(), RequestError::Kind::unprocessable) << e.what();
    return e.field();
  }
  return "accepted";
}

TEST(AdaptiveSteps, BadTolerancesAreRefusedNamingTheField) {
  for (double bad : {-1e-6, 0.0, std::numeric_limits<double>::quiet_NaN(), 2.0,
                     std::numeric_limits<double>::infinity()}) {
    IntegrateRequest req = adaptive(Integrator::rkmk4, 1e-6);
    req.rtol = bad;
    EXPECT_EQ(unprocessable_field([&] { validate(req); }), "rtol") << bad;
    req.rtol = 1e-6;
    req.atol = bad;
    EXPECT_EQ(unprocessable_field([&] { validate(req); }), "atol") << bad;
    WorkPrecisionRequest wp{.choices = {{Integrator::rkmk4}}};
    wp.tolerances = {1e-3, bad};
    EXPECT_EQ(unprocessable_field([&] { validate(wp); }), "tolerances") << bad;
  }
  WorkPrecisionRequest both{.choices = {{Integrator::rkmk4}}, .h = {0.1}};
  both.tolerances = {1e-3};
  EXPECT_EQ(unprocessable_field([&] { validate(both); }), "tolerances");
}

// Work-precision against tolerance: each point an adaptive run at rtol = atol = its tolerance, no fitted order.
TEST(AdaptiveSteps, WorkPrecisionAgainstTolerance) {
  WorkPrecisionRequest req{.t_end = kTEnd, .choices = {{Integrator::rkmk4}, {Integrator::rkmk_gauss2}}};
  req.solver.tol = 1e-15;
  req.tolerances = {1e-5, 1e-8, 1e-11};
  const WorkPrecisionResult r = work_precision(req);
  ASSERT_EQ(r.series.size(), 2u);
  for (const WorkPrecisionSeries& s : r.series) {
    EXPECT_FALSE(s.fitted_order.has_value());
    ASSERT_EQ(s.points.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
      const WorkPrecisionPoint& p = s.points[k];
      ASSERT_EQ(p.status, Status::converged);
      EXPECT_EQ(p.tolerance, req.tolerances[k]);
      EXPECT_FALSE(p.in_fit);
      EXPECT_FALSE(p.excluded.empty());
      EXPECT_LT(p.error, 100 * req.tolerances[k]);
      if (k > 0) {
        EXPECT_LT(p.error, s.points[k - 1].error);
        EXPECT_LT(p.h, s.points[k - 1].h);  // the mean accepted step shrinks with the tolerance
      }
    }
  }
}

}  // namespace
}  // namespace lienewton

#pragma once
// A problem's time scale, read off its field at the start: the rate rho = max(||g(z)||, ||dg_z||_F) in algebra
// coordinates (the speed of the flow and how fast g itself changes: the rigid body's ~1, the heavy top's spin of
// 150 rad/s and its nutation, a stiff field's -1e4), and the default step sizes of a work-precision diagram taken
// from it, so that every integrator starts inside its asymptotic regime (h rho <= 1) instead of at steps that turn
// the state by many radians. The chain has its own (Chain::rate: its joints' and swing's rates).
#include <vector>

#include "problem_spec.hpp"

namespace lienewton {

// The rate of the (validated) problem's field at its start point.
double field_rate(const ProblemSpec& problem);

// Step sizes halving from the largest power of two h <= kMaxDefaultStep with h rho <= 1: kDefaultStepCount of them,
// fewer where a run to t_end would take more than kMaxDefaultRunSteps steps (the heavy top: 2^-10 ... 2^-13, so that
// every integrator's runs fit a server's step budget), never fewer than kMinDefaultStepCount. Where those would
// take more than kMaxRunSteps, the limit of one integration, they start that much higher instead (the stiff body,
// rho ~ 2e4 from its damper: 2^-14 ... 2^-16 at t_end = 1, h rho up to 1.1).
inline constexpr int kDefaultStepCount = 6;
inline constexpr int kMinDefaultStepCount = 3;
inline constexpr double kMaxDefaultRunSteps = 8192;
inline constexpr double kMaxDefaultStep = 0.25;
inline constexpr double kMaxRunSteps = 1e5;
std::vector<double> default_step_sizes(const ProblemSpec& problem, double t_end);

// The default step of one integration to t_end: kDefaultIntegrationStep where that is inside the asymptotic regime
// (h rho <= 1), else the largest default step size, and never more than max_steps steps or a step past t_end.
inline constexpr double kDefaultIntegrationStep = 0.1;
double default_step(const ProblemSpec& problem, double t_end, double max_steps);

}  // namespace lienewton

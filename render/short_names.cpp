#include "render/short_names.hpp"

namespace lienewton::render {

std::string_view short_name(Integrator integrator) {
  switch (integrator) {
    case Integrator::implicit_euler: return "Euler";
    case Integrator::dirk_cg2: return "DIRK-CG2";
  }
  return "?";
}

std::string_view short_name(Method method) {
  switch (method) {
    case Method::fixed_point: return "fixed point";
    case Method::newton_group: return "Newton group";
    case Method::newton_algebra: return "Newton algebra";
  }
  return "?";
}

std::string_view short_name(Differential differential) {
  switch (differential) {
    case Differential::finite_difference: return "FD";
    case Differential::dexpinv_0: return "order 0";
    case Differential::dexpinv_1: return "order 1";
    case Differential::exact: return "exact";
  }
  return "?";
}

std::string_view short_name(Status status) {
  switch (status) {
    case Status::converged: return "converged";
    case Status::max_iterations: return "max iterations";
    case Status::diverged: return "diverged";
    case Status::non_finite: return "non-finite";
    case Status::left_log_domain: return "left log domain";
    case Status::singular_differential: return "singular differential";
    case Status::stagnated: return "stagnated";
    case Status::off_branch: return "off branch";
    case Status::local_minimum: return "local minimum";
    case Status::no_descent: return "no descent";
    case Status::cancelled: return "cancelled";
  }
  return "?";
}

std::string series_name(Method method, Differential differential) {
  std::string name(short_name(method));
  if (method != Method::fixed_point) name += ", " + std::string(short_name(differential));
  return name;
}

std::string series_name(Integrator integrator, Method method, Differential differential) {
  return std::string(short_name(integrator)) + ", " + series_name(method, differential);
}

}  // namespace lienewton::render

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

std::string series_name(Method method, Differential differential) {
  std::string name(short_name(method));
  if (method != Method::fixed_point) name += ", " + std::string(short_name(differential));
  return name;
}

std::string series_name(Integrator integrator, Method method, Differential differential) {
  return std::string(short_name(integrator)) + ", " + series_name(method, differential);
}

}  // namespace lienewton::render

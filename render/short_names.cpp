#include "render/short_names.hpp"

#include "core/integrators/methods.hpp"

namespace lienewton::render {

std::string series_name(Method method, Differential differential) {
  std::string name(short_name(method));
  if (uses_differential(method)) name += ", " + std::string(short_name(differential));
  return name;
}

std::string series_name(Integrator integrator, Method method, Differential differential) {
  if (!solves_stages(integrator)) return std::string(short_name(integrator));  // no equation, no method
  return std::string(short_name(integrator)) + ", " + series_name(method, differential);
}

}  // namespace lienewton::render

#pragma once
// Compact ASCII names for chart legends (the render font is ASCII): "Euler, Newton group, exact".
#include <string>
#include <string_view>

#include "core/options.hpp"
#include "core/status.hpp"

namespace lienewton::render {

std::string_view short_name(Integrator integrator);      // "Euler" | "DIRK-CG2"
std::string_view short_name(Method method);              // "fixed point" | "Newton group" | "Newton algebra"
std::string_view short_name(Differential differential);  // "FD" | "order 0" | "order 1" | "exact"
std::string_view short_name(Status status);              // "max iterations", "left log domain", ...
// "Newton group, FD"; the fixed point iteration (1.2) forms no differential, so it is named alone.
std::string series_name(Method method, Differential differential);
std::string series_name(Integrator integrator, Method method, Differential differential);

}  // namespace lienewton::render

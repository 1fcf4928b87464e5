#pragma once
// Compact ASCII names for chart legends (the render font is ASCII): the vocabulary's short labels
// (core/vocabulary.cpp), the same words the dashboard shows, put together as "Euler, Newton group, exact".
#include <string>
#include <string_view>

#include "core/vocabulary.hpp"

namespace lienewton::render {

// "Euler", "Newton group", "FD", "max iterations", ...
template <class Enum>
std::string_view short_name(Enum value) {
  return words(value).short_label;
}
// "Newton group, FD"; a method that uses no differential (the fixed point) is named alone.
std::string series_name(Method method, Differential differential);
std::string series_name(Integrator integrator, Method method, Differential differential);

}  // namespace lienewton::render

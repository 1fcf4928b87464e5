#pragma once
// Every integrator's tableau, order and form: one row each in methods.cpp. Adding an integrator is its Integrator
// value (core/options.hpp), its row there and its vocabulary row (core/vocabulary.cpp).
#include "core/options.hpp"
#include "tableau.hpp"

namespace lienewton {

namespace integrators {
const Tableau& tableau_of(Integrator integrator);
}  // namespace integrators

// The order p of an integrator's global error O(h^p).
inline int order_of(Integrator integrator) { return integrators::tableau_of(integrator).order; }
// Whether an integrator's steps solve implicit stages: the method, the differential and the solver's options matter
// only then.
inline bool solves_stages(Integrator integrator) { return integrators::tableau_of(integrator).solves_stages(); }

}  // namespace lienewton

#pragma once
// The paper's Figures 5.1 and 5.2 as Markdown tables: iterations (or the failure class) and the rate r for
// every (N, h) cell of the default sweep, one table per method and problem.
#include <string>

#include "core/sweep.hpp"

namespace lienewton {

// One-letter codes of the failure classes in the tables; converged cells show their iteration count.
char status_code(Status status);
std::string figure_tables(const SweepResult& sweep, ProblemKind problem, Differential differential);

}  // namespace lienewton

#pragma once
// A solve request for one of the paper's problems (section 5) at the default start y0 = z, as the JSON API
// builds it from {"problem", "n", "h", "method", "differential", "globalization"}.
#include "core/solve.hpp"

namespace lienewton {

inline SolveRequest paper_request(ProblemKind problem, int n, double h, Method method, Differential d,
                                  Globalization g = Globalization::none) {
  SolveRequest req;
  req.problem.kind = problem;
  req.problem.n = n;
  req.h = h;
  req.solver.method = method;
  req.solver.differential = d;
  req.solver.globalization = g;
  return req;
}

}  // namespace lienewton

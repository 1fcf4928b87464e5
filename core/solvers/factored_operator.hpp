#pragma once
// The Newton matrix as D = A P^T with P orthogonal (absent: A = D): D u = -f is solved as A w = -f, u = P w
// (newton_step.hpp). A has D's singular values, so the singularity test reads the same.
#include <optional>

namespace lienewton {

template <class Operator>
struct FactoredOperator {
  Operator a;
  std::optional<Operator> basis;
};

}  // namespace lienewton

#pragma once
// The one place that picks a group for a matrix size: SO(3) takes the closed forms on fixed-size types,
// every other N the spectral path.
#include "so3_group.hpp"
#include "son_group.hpp"

namespace lienewton {

template <class F>
decltype(auto) with_group(int n, F&& f) {
  if (n == 3) return f(SO3Group{});
  return f(SONGroup(n));
}

}  // namespace lienewton

#pragma once
// The family SO: the one place that picks a rotation group for an index n. SO(3) takes the closed forms on
// fixed-size types, every other N the spectral path. Requests reach it by name, through the group registry
// (core/group_registry.cpp registers SOFamily).
#include <utility>

#include "so3_group.hpp"
#include "son_group.hpp"

namespace lienewton {

template <class F>
decltype(auto) with_group(int n, F&& f) {
  if (n == 3) return f(SO3Group{});
  return f(SONGroup(n));
}

struct SOFamily {
  static constexpr const char* kName = "SO";
  template <class F>
  static decltype(auto) with_group(int n, F&& f) {
    return lienewton::with_group(n, std::forward<F>(f));
  }
};

}  // namespace lienewton

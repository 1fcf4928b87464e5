#pragma once
// A family with one member (register_group.hpp): the group G at index Index, as requests name it ("group": Name,
// "n": Index; validation refuses any other n before a request reaches with_group). SE(3) and the products of
// mechanics_groups.hpp are such families.
#include <algorithm>
#include <cstddef>

#include "lie_group.hpp"

namespace lienewton {

// A string literal as a template argument: the family's name.
template <std::size_t N>
struct FamilyName {
  char text[N];
  constexpr FamilyName(const char (&name)[N]) { std::copy_n(name, N, text); }
};

template <FamilyName Name, LieGroup G, int Index>
struct SingleGroupFamily {
  static constexpr const char* kName = Name.text;
  static constexpr int kOnlyIndex = Index;
  template <class F>
  static decltype(auto) with_group(int, F&& f) {
    return f(G{});
  }
};

}  // namespace lienewton

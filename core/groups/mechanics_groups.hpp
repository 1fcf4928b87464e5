#pragma once
// The configuration-velocity spaces of mechanics as direct products with R^k (product_group.hpp): SO(3) x R^3 (a
// rotation and an angular velocity: the heavy top's state) and SE(3) x R^6 (a rigid motion and its twist), and
// their families, each with its one member at n = 3: requests name them "SOxR" and "SExR". Their matrices are
// block diagonal, [[R, 0], [0, [[I, w], [0, 1]]]] (7 x 7) and [[T, 0], [0, [[I, v], [0, 1]]]] (11 x 11).
#include "product_group.hpp"
#include "se3_group.hpp"
#include "so3_group.hpp"
#include "translation_group.hpp"

namespace lienewton {

using SO3xR3Group = ProductGroup<SO3Group, TranslationGroup<3>>;
using SE3xR6Group = ProductGroup<SE3Group, TranslationGroup<6>>;
static_assert(LieGroup<SO3xR3Group>);
static_assert(LieGroup<SE3xR6Group>);

struct SOxRFamily {
  static constexpr const char* kName = "SOxR";
  static constexpr int kOnlyIndex = 3;
  template <class F>
  static decltype(auto) with_group(int, F&& f) {
    return f(SO3xR3Group{});
  }
};

struct SExRFamily {
  static constexpr const char* kName = "SExR";
  static constexpr int kOnlyIndex = 3;
  template <class F>
  static decltype(auto) with_group(int, F&& f) {
    return f(SE3xR6Group{});
  }
};

}  // namespace lienewton

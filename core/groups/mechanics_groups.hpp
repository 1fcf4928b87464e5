#pragma once
// The configuration-velocity spaces of mechanics as direct products with R^k (product_group.hpp): SO(3) x R^3 (a
// rotation and an angular velocity: the heavy top's state) and SE(3) x R^6 (a rigid motion and its twist), and
// their families, each with its one member at n = 3: requests name them "SOxR" and "SExR". Their matrices are
// block diagonal, [[R, 0], [0, [[I, w], [0, 1]]]] (7 x 7) and [[T, 0], [0, [[I, v], [0, 1]]]] (11 x 11).
// SO(3) x SO(3) x R^6, two rigid bodies' rotations and angular velocities (13 x 13), is formed here but has no
// family yet: registering one compiles every solver on it. (SO(3) x R^3)^k, k rigid bodies for k known at run time
// (power_group.hpp), has none yet; (SE(3) x R^6)^k has SExR^k.
#include "power_group.hpp"
#include "product_group.hpp"
#include "se3_group.hpp"
#include "single_group_family.hpp"
#include "so3_group.hpp"
#include "translation_group.hpp"

namespace lienewton {

using SO3xR3Group = ProductGroup<SO3Group, TranslationGroup<3>>;
using SE3xR6Group = ProductGroup<SE3Group, TranslationGroup<6>>;
static_assert(LieGroup<SO3xR3Group>);
static_assert(LieGroup<SE3xR6Group>);
using SO3xSO3xR6Group = ProductGroup<SO3Group, SO3Group, TranslationGroup<6>>;
static_assert(LieGroup<SO3xSO3xR6Group>);
using SO3xR3PowerGroup = PowerGroup<SO3xR3Group>;
static_assert(LieGroup<SO3xR3PowerGroup>);
using SE3xR6PowerGroup = PowerGroup<SE3xR6Group>;
static_assert(LieGroup<SE3xR6PowerGroup>);

using SOxRFamily = SingleGroupFamily<"SOxR", SO3xR3Group, 3>;
using SExRFamily = SingleGroupFamily<"SExR", SE3xR6Group, 3>;
// k rigid bodies' poses and twists, "group": "SExR^k" with n = k (docs/many_bodies.md).
using SExRPowerFamily = PowerFamily<"SExR^k", SE3xR6Group, 128>;

}  // namespace lienewton

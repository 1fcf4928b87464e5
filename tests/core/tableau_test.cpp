// The integrators' tableaus as data (core/integrators/methods.cpp): every Integrator has its row, each row is of its
// form's shape, and its A and b satisfy the classical order conditions (Butcher's rooted trees) up to its order, at
// most 4 here: conditions an RKMK method needs and, with the exponential's own from order 3 on, a Crouch-Grossman
// method too (Owren & Marthinsen 1999). Computed from A and b alone, in long double, not from the stepper.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/integrators/methods.hpp"

namespace lienewton {
namespace {

using integrators::Form;
using integrators::Tableau;

// The residuals of the classical order conditions of order k, each left side minus its 1/gamma(tree).
std::vector<long double> conditions(const Tableau& t, int k) {
  const int s = t.stages();
  std::vector<long double> c(static_cast<std::size_t>(s)), ac(static_cast<std::size_t>(s)),
      ac2(static_cast<std::size_t>(s)), aac(static_cast<std::size_t>(s));
  for (int i = 0; i < s; ++i) {
    long double sum = 0;
    for (int j = 0; j < s; ++j) sum += t.a(i, j);
    c[static_cast<std::size_t>(i)] = sum;
  }
  for (int i = 0; i < s; ++i) {
    long double x = 0, y = 0;
    for (int j = 0; j < s; ++j) {
      x += t.a(i, j) * c[static_cast<std::size_t>(j)];
      y += t.a(i, j) * c[static_cast<std::size_t>(j)] * c[static_cast<std::size_t>(j)];
    }
    ac[static_cast<std::size_t>(i)] = x;
    ac2[static_cast<std::size_t>(i)] = y;
  }
  for (int i = 0; i < s; ++i) {
    long double x = 0;
    for (int j = 0; j < s; ++j) x += t.a(i, j) * ac[static_cast<std::size_t>(j)];
    aac[static_cast<std::size_t>(i)] = x;
  }
  const auto sum_b = [&](auto term) {
    long double sum = 0;
    for (int i = 0; i < s; ++i) sum += t.b(i) * term(static_cast<std::size_t>(i));
    return sum;
  };
  switch (k) {
    case 1: return {sum_b([](std::size_t) { return 1.0L; }) - 1.0L};
    case 2: return {sum_b([&](std::size_t i) { return c[i]; }) - 0.5L};
    case 3: return {sum_b([&](std::size_t i) { return c[i] * c[i]; }) - 1.0L / 3,
                    sum_b([&](std::size_t i) { return ac[i]; }) - 1.0L / 6};
    case 4: return {sum_b([&](std::size_t i) { return c[i] * c[i] * c[i]; }) - 1.0L / 4,
                    sum_b([&](std::size_t i) { return c[i] * ac[i]; }) - 1.0L / 8,
                    sum_b([&](std::size_t i) { return ac2[i]; }) - 1.0L / 12,
                    sum_b([&](std::size_t i) { return aac[i]; }) - 1.0L / 24};
  }
  return {};
}

TEST(Tableau, EveryIntegratorHasARowOfItsFormsShape) {
  for (Integrator integrator : kAllIntegrators) {
    const std::string name(to_string(integrator));
    const Tableau& t = integrators::tableau_of(integrator);
    ASSERT_EQ(t.a.rows(), t.stages()) << name;
    ASSERT_EQ(t.a.cols(), t.stages()) << name;
    EXPECT_GE(t.order, 1) << name;
    for (int i = 0; i < t.stages(); ++i)
      for (int j = i; j < t.stages(); ++j) {
        const bool zero = t.form == Form::explicit_rkmk || (t.form == Form::dirk_crouch_grossman && j > i);
        if (zero) {
          EXPECT_EQ(t.a(i, j), 0.0) << name << " a" << i << j;
        } else if (t.form == Form::dirk_crouch_grossman) {
          EXPECT_GT(t.a(i, i), 0.0) << name << " a" << i << i;
        }
      }
    EXPECT_EQ(t.solves_stages(), integrator != Integrator::rkmk4) << name;
  }
}

TEST(Tableau, ClassicalOrderConditionsHoldUpToTheOrder) {
  for (Integrator integrator : kAllIntegrators) {
    const Tableau& t = integrators::tableau_of(integrator);
    for (int k = 1; k <= std::min(t.order, 4); ++k)
      for (long double r : conditions(t, k))
        EXPECT_LE(std::fabs(static_cast<double>(r)), 1e-14) << to_string(integrator) << " order " << k;
    // And the order is no higher than the row says: the first condition past it fails (below order 5).
    if (t.order < 4) {
      double worst = 0;
      for (long double r : conditions(t, t.order + 1)) worst = std::max(worst, std::fabs(static_cast<double>(r)));
      EXPECT_GT(worst, 1e-3) << to_string(integrator);
    }
  }
}

TEST(Tableau, StiffAccuracyIsReadOffTheRows) {
  EXPECT_TRUE(integrators::tableau_of(Integrator::implicit_euler).stiffly_accurate());
  EXPECT_TRUE(integrators::tableau_of(Integrator::dirk_cg2).stiffly_accurate());
  EXPECT_TRUE(integrators::tableau_of(Integrator::rkmk_radau3).stiffly_accurate());
  EXPECT_TRUE(integrators::tableau_of(Integrator::rkmk_lobatto3c).stiffly_accurate());
  EXPECT_FALSE(integrators::tableau_of(Integrator::dirk_cg3).stiffly_accurate());
  EXPECT_FALSE(integrators::tableau_of(Integrator::rkmk_gauss2).stiffly_accurate());
}

}  // namespace
}  // namespace lienewton

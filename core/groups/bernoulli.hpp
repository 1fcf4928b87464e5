#pragma once
// |B_2k| / (2k)!, k = 1..18, the coefficients of dexpinv (3.9): B_2k / (2k)! = (-1)^(k+1) |B_2k| / (2k)!, and
// (1 - (t/2) cot(t/2)) / t^2 = sum_k |B_2k| / (2k)! t^(2k-2).
#include <array>

namespace lienewton {

inline constexpr std::array<double, 18> kBernoulliOverFactorial = {
    0.083333333333333329,  0.0013888888888888889,  3.3068783068783071e-05, 8.2671957671957675e-07,
    2.08767569878681e-08,  5.2841901386874932e-10, 1.3382536530684679e-11, 3.3896802963225827e-13,
    8.5860620562778452e-15, 2.1748686985580619e-16, 5.5090028283602295e-18, 1.3954464685812522e-19,
    3.5347070396294673e-21, 8.9535174270375463e-23, 2.2679524523376829e-24, 5.7447906688722025e-26,
    1.455172475614865e-27, 3.6859949406653103e-29};

// B_2k / (2k)!, signed.
constexpr double bernoulli_over_factorial(int k) {
  return (k % 2 == 1 ? 1.0 : -1.0) * kBernoulliOverFactorial[static_cast<std::size_t>(k - 1)];
}

}  // namespace lienewton

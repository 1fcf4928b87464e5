#pragma once
// The domain of the principal logarithm on the rotation groups: log was asked for a matrix outside it (not
// orthogonal, det -1, non-finite, or an angle within kLogDomainMargin of pi). angle() reports the largest
// rotation angle found, or NaN if none.
#include <stdexcept>
#include <string>

namespace lienewton {

// Angles closer than this to pi are refused: there the logarithm is not unique (exactly pi) and its branch
// flips under rounding, so a "solution" would be meaningless.
inline constexpr double kLogDomainMargin = 1e-10;

class LogDomainError : public std::domain_error {
 public:
  LogDomainError(const std::string& what, double angle) : std::domain_error(what), angle_(angle) {}
  double angle() const { return angle_; }

 private:
  double angle_;
};

}  // namespace lienewton

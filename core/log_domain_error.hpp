#pragma once
// log was asked for a matrix outside its domain: not orthogonal, det -1, non-finite, or (SO(N)) an angle within
// the domain margin of pi. angle() reports the largest rotation angle found, or NaN if none.
#include <stdexcept>
#include <string>

namespace lienewton {

class LogDomainError : public std::domain_error {
 public:
  LogDomainError(const std::string& what, double angle) : std::domain_error(what), angle_(angle) {}
  double angle() const { return angle_; }

 private:
  double angle_;
};

}  // namespace lienewton

#include "fields.hpp"

#include <algorithm>
#include <charconv>

namespace lienewton::fields {

std::string format_bound(double x) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
  std::string s(buf, end);
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  std::string exponent = s.substr(e + 1);
  const bool negative = exponent.front() == '-';
  exponent.erase(0, exponent.find_first_not_of("+-0"));
  return s.substr(0, e + 1) + (negative ? "-" : "") + exponent;
}

std::string NumberField::range_text() const {
  return std::string(min_exclusive ? "(" : "[") + format_bound(min) + ", " + format_bound(max) + "]";
}

std::string NumberField::message(const std::string& path) const {
  return path + " must be a finite number in " + range_text();
}

std::string IntegerField::message(const std::string& path, long long cap) const {
  return path + " must be an integer in [" + std::to_string(min) + ", " + std::to_string(std::min(max, cap)) + "]";
}

}  // namespace lienewton::fields

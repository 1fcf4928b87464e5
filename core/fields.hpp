#pragma once
// One row per bounded request field: its name, bounds, default and description. Core validation, the codec's
// error messages and the OpenAPI schemas all read these rows, so a bound cannot disagree with itself.
#include <limits>
#include <string>

namespace lienewton::fields {

inline constexpr double kNoDefault = std::numeric_limits<double>::quiet_NaN();

struct NumberField {
  const char* name;
  double min;
  double max;
  bool min_exclusive;  // (min, max] instead of [min, max]
  double default_value;  // kNoDefault when the field has none
  const char* description;

  bool contains(double x) const { return (min_exclusive ? x > min : x >= min) && x <= max; }  // false for NaN
  std::string range_text() const;  // "(0, 1e6]"
  // "<path> must be a finite number in (0, 1e6]"; path is name, or e.g. "cells[3].h" inside an array.
  std::string message(const std::string& path) const;
};

struct IntegerField {
  const char* name;
  long long min;
  long long max;  // the core's bound; a server may cap it lower (--max-n, --max-iterations)
  long long default_value;
  const char* description;

  bool contains(long long x) const { return x >= min && x <= max; }
  // "<path> must be an integer in [min, cap]", cap = min(max, server cap).
  std::string message(const std::string& path, long long cap = std::numeric_limits<long long>::max()) const;
};

inline constexpr NumberField h{"h", 0.0, 1e6, true, kNoDefault, "step size"};
inline constexpr NumberField tol{"tol", 1e-16, 1.0, false, 1e-13, "absolute tolerance on ||f||"};
inline constexpr NumberField t_end{"t_end", 0.0, 100.0, true, 1.0, "end time"};
inline constexpr IntegerField n{"n", 2, 100000, 3, "matrix size N (capped by --max-n)"};  // 1e5: beyond any memory
inline constexpr IntegerField max_iterations{"max_iterations", 1, 100000, 100, "capped by --max-iterations"};

inline constexpr const NumberField* kNumberFields[] = {&h, &tol, &t_end};
inline constexpr IntegerField restarts{"restarts", 0, 10000, 0,
                                      "continuation only: solves at h from seeded starts after its paths fail"};

inline constexpr const IntegerField* kIntegerFields[] = {&n, &max_iterations, &restarts};

// A bound as a person writes it: 1e6, 1e-16, 100, 0.5 (shortest round-trip, no "e+06").
std::string format_bound(double x);

}  // namespace lienewton::fields

#pragma once
// How GoogleTest names the options in parameterised tests' names and failure messages: by their API names
// (found by argument-dependent lookup), instead of "4-byte object <01-00 00-00>".
#include <ostream>

#include "core/options.hpp"

namespace lienewton {

inline void PrintTo(ProblemKind v, std::ostream* os) { *os << to_string(v); }
inline void PrintTo(Method v, std::ostream* os) { *os << to_string(v); }
inline void PrintTo(Differential v, std::ostream* os) { *os << to_string(v); }
inline void PrintTo(Integrator v, std::ostream* os) { *os << to_string(v); }
inline void PrintTo(Globalization v, std::ostream* os) { *os << to_string(v); }
inline void PrintTo(Predictor v, std::ostream* os) { *os << to_string(v); }

}  // namespace lienewton

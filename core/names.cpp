// The JSON names of the enums, read from their rows in the vocabulary (core/vocabulary.cpp).
#include "core/vocabulary.hpp"

namespace lienewton {

std::string_view to_string(Status v) { return words(v).api; }
std::string_view to_string(ProblemKind v) { return words(v).api; }
std::string_view to_string(Method v) { return words(v).api; }
std::string_view to_string(Differential v) { return words(v).api; }
std::string_view to_string(Integrator v) { return words(v).api; }
std::string_view to_string(LinearSolver v) { return words(v).api; }
std::string_view to_string(Factorization v) { return words(v).api; }
std::string_view to_string(Stopping v) { return words(v).api; }
std::string_view to_string(Globalization v) { return words(v).api; }
std::string_view to_string(Predictor v) { return words(v).api; }
std::string_view to_string(Branch v) { return words(v).api; }
std::string_view to_string(Search v) { return words(v).api; }
std::string_view to_string(PathPointKind v) { return words(v).api; }
std::string_view to_string(Invariant v) { return words(v).api; }
std::optional<Status> status_from_string(std::string_view s) { return from_api_name(kAllStatuses, s); }
std::optional<Method> method_from_string(std::string_view s) { return from_api_name(kAllMethods, s); }
std::optional<Differential> differential_from_string(std::string_view s) {
  return from_api_name(kAllDifferentials, s);
}

}  // namespace lienewton

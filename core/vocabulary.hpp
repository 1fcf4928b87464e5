#pragma once
// The words for every value of the API's enums, one row per value: the JSON name that requests and answers
// spell, and what a reader is shown for it. to_string and the *_from_string parsers (core/names.cpp), the PNG
// legends (render/short_names.hpp) and the "x-lienewton" catalog of /openapi.json, which the dashboard reads,
// all take their words from here. Each words() switches over its enum without a default, so a new enum value
// without its row fails to compile (-Wswitch under -Werror).
#include <cstddef>
#include <optional>
#include <string_view>

#include "core/options.hpp"
#include "core/status.hpp"

namespace lienewton {

struct Words {
  std::string_view api;          // the JSON name
  std::string_view label;        // a select's option, a checkbox, a row of a table
  std::string_view short_label;  // ASCII (the PNG font is ASCII): a column head, a PNG legend, a series name
  std::string_view sentence;     // one line: a tooltip, a legend, the reason when an answer gives none
  std::string_view explanation;  // "What is this?": the longer account with the paper's equation numbers;
                                 // empty where the sentence says enough
};

Words words(ProblemKind);
Words words(Method);
Words words(Differential);
Words words(Integrator);
Words words(LinearSolver);
Words words(Factorization);
Words words(Stopping);
Words words(Globalization);
Words words(Predictor);
Words words(Branch);
Words words(Search);
Words words(PathPointKind);
Words words(Invariant);
Words words(Status);

// The value of all whose API name is name (words() found by argument-dependent lookup, so that an enum
// outside core with its own words() parses the same way).
template <class Enum, std::size_t K>
std::optional<Enum> from_api_name(const Enum (&all)[K], std::string_view name) {
  for (Enum e : all)
    if (words(e).api == name) return e;
  return std::nullopt;
}

}  // namespace lienewton

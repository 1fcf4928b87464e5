#pragma once
// The request examples /openapi.json shows for each request schema: the README's requests, so that a reader of
// the reference page and of the README sees the same ones (tests/replay/validate_answers.py checks that every
// README request is among them, that each is valid by its schema, and that the server answers each as documented).
#include <nlohmann/json.hpp>
#include <string>

namespace lienewton::service {

// {"name": {"summary", "value"}, ...} for a request schema (SolveRequest, RenderFramesRequest, ...); empty when it
// has none.
nlohmann::json request_examples(const std::string& schema);

}  // namespace lienewton::service

// libFuzzer harness over request parsing and validation: any byte string, read as the body of each POST
// route (and as a GET query), must end in a result or a RequestError -- never a crash, hang, UB or another
// exception -- and whatever is serialised back must parse as JSON again.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/integrate.hpp"
#include "core/solve.hpp"
#include "core/sweep.hpp"
#include "core/work_precision.hpp"
#include "server/json_codec.hpp"
#include "server/query_params.hpp"

using namespace lienewton;
using namespace lienewton::service;

namespace {

template <class Parse>
void guarded(Parse parse) {
  try {
    parse();
  } catch (const RequestError&) {
    // the expected refusal
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  json body;
  try {
    body = parse_body(text);
  } catch (const RequestError&) {
    return 0;
  }
  const Limits limits;  // the server's defaults
  guarded([&] {
    const SolveRequest r = solve_request_from_json(body, limits);
    validate(r);
  });
  guarded([&] {
    const SweepRequest r = sweep_request_from_json(body, limits);
    validate(r);
  });
  guarded([&] {
    const IntegrateRequest r = integrate_request_from_json(body, limits);
    validate(r);
  });
  guarded([&] {
    const WorkPrecisionRequest r = work_precision_request_from_json(body, limits);
    validate(r);
  });
  guarded([&] {
    const SweepResult r = sweep_result_from_json(body, limits);
    // What we write back must parse again (no NaN/Inf tokens, valid UTF-8 after replacement).
    (void)json::parse(dump(to_json(r)));
  });
  // The same document as GET query parameters (each top-level value as its text).
  if (body.is_object()) {
    std::multimap<std::string, std::string> params;
    for (const auto& [key, value] : body.items()) params.emplace(key, value.is_string() ? value.get<std::string>() : dump(value));
    guarded([&] { solve_request_from_json(query_to_json(params), limits); });
    guarded([&] { sweep_request_from_json(query_to_json(params, list_fields(fields::sweep)), limits); });
  }
  return 0;
}

#include "server/openapi_examples.hpp"

#include <utility>
#include <vector>

namespace lienewton::service {
namespace {

using nlohmann::json;

struct Example {
  const char* schema;
  const char* name;
  const char* summary;
  const char* body;  // JSON text, as the README sends it
};

constexpr Example kExamples[] = {
    {"SolveRequest", "readme", "Version 1 with the exact differential on the paper's linear problem",
     R"({"problem":"paper-linear","n":3,"h":0.5,"method":"newton-group","differential":"exact","seed":1})"},
    {"SolveRequest", "continuation", "the root continued from y = z (compare continuation false)",
     R"({"problem":"paper-sine","n":5,"h":0.0625,"continuation":true})"},
    {"SolveRequest", "fixed-point", "the fixed point at a large h (stream it with Accept: application/x-ndjson)",
     R"({"problem":"paper-sine","n":8,"h":2,"method":"fixed-point"})"},
    {"SolveRequest", "rigid-body", "Version 2 on the rigid body (the SSE example's query)",
     R"({"problem":"rigid-body","n":3,"h":0.5,"method":"newton-algebra"})"},
    {"SolveRequest", "user-field", "your own field g in MATLAB notation",
     R"({"g":"u = sin(y)*(2*y - 5*y^2); g = u - u'","n":4,"h":0.5})"},
    {"SweepRequest", "readme", "a small stability map",
     R"({"problem":"paper-linear","n":[3],"h":[0.5,8],"differential":"exact"})"},
    {"BasinRequest", "readme", "a 32 x 32 basin map",
     R"({"problem":"paper-linear","n":3,"h":0.5,"size":32})"},
    {"IntegrateRequest", "readme", "the rigid body with a Crouch-Grossman DIRK",
     R"({"problem":"rigid-body","integrator":"dirk-cg2","h":0.125})"},
    {"IntegrateRequest", "user-field", "a rigid body written as your own field with parameters",
     R"({"g":"w = J \\ (transpose(y)*m); g = [0 -w(3) w(2); w(3) 0 -w(1); -w(2) w(1) 0]","h":0.1,"t_end":1,)"
     R"("parameters":{"J":[[1,0,0],[0,2,0],[0,0,3]],"m":[[0.6],[0.8],[0.5]]}})"},
    {"WorkPrecisionRequest", "readme", "two integrators against each other",
     R"({"problem":"rigid-body","choices":[{"integrator":"implicit-euler"},{"integrator":"dirk-cg2"}]})"},
    {"RenderFramesRequest", "readme", "the iterates of a rigid-body solve", R"({"problem":"rigid-body","h":0.5})"},
    {"RenderMotionRequest", "animation", "the heavy-top benchmark's first half second as an animated WebP",
     R"({"problem":"heavy-top","t_end":0.5,"frames":20,"width":256,"height":256})"},
    {"RenderMotionRequest", "still", "the rigid body's momentum on its sphere at t = 10, as a PNG",
     R"({"problem":"rigid-body","t_end":10,"format":"png"})"},
    {"RenderHeatmapRequest", "readme", "the stability map of paper-linear",
     R"({"problem":"paper-linear","differential":"exact","n":[2,3,4,5,6],"h":[0.25,1,4,16]})"},
    {"RenderBasinsRequest", "readme", "a 64 x 64 basin map at h = 4",
     R"({"problem":"paper-linear","n":3,"h":4,"size":64})"},
    {"RenderWorkPrecisionRequest", "readme", "two integrators against each other",
     R"({"problem":"rigid-body","choices":[{"integrator":"implicit-euler"},{"integrator":"dirk-cg2"}]})"},
    {"RenderResidualsRequest", "readme", "every method x differential of one equation",
     R"({"problem":"paper-linear","n":8,"h":2})"},
    {"RenderInvariantsRequest", "rigid-body", "the rigid body's energy and momentum drift",
     R"({"problem":"rigid-body","integrator":"dirk-cg2","h":0.125})"},
};

}  // namespace

json request_examples(const std::string& schema) {
  json out = json::object();
  for (const Example& e : kExamples)
    if (schema == e.schema) out[e.name] = json{{"summary", e.summary}, {"value", json::parse(e.body)}};
  return out;
}

}  // namespace lienewton::service

#pragma once
// The words and colours a client shows for the API's values, published in /openapi.json as the "x-lienewton"
// extension so that the dashboard reads them instead of keeping copies:
//   enums.<name>: [{value, label, short, description, explanation?, ...}] in the server's order: each value's
//                 row of the vocabulary (core/vocabulary.hpp; description is its sentence, explanation the
//                 longer account where it has one), for problem, method (+ uses_differential), differential,
//                 integrator, linear_solver, globalization, stopping, predictor, branch, found_by, path_point, status (+ color)
//                 and heatmap_metric;
//   colors: {no_value, viridis: [[r,g,b] x 256]}, the heatmap renderer's own colours (render/colormap.cpp);
//   output_limits: this server's caps (its flags, not the defaults), which a client plans a request with: numbers
//                 per result and a basin pixel's share of them, pixels per image, cells per grid, and the seconds
//                 a request (sweep_seconds: a sweep, basin map or heatmap) may run before 504.
#include <nlohmann/json.hpp>

#include "server/server_options.hpp"

namespace lienewton::service {

nlohmann::json openapi_labels(const ServerOptions& options);

}  // namespace lienewton::service

#pragma once
// The words and colours a client shows for the API's values, published in /openapi.json as the "x-lienewton"
// extension so that the dashboard reads them instead of keeping copies:
//   enums.<name>: [{value, label, short, description, explanation?, ...}] in the server's order: each value's
//                 row of the vocabulary (core/vocabulary.hpp; description is its sentence, explanation the
//                 longer account where it has one), for problem, method (+ uses_differential), differential,
//                 integrator, linear_solver, globalization, stopping, predictor, stage_start, status (+ color)
//                 and heatmap_metric;
//   colors: {no_value, viridis: [[r,g,b] x 256]}, the heatmap renderer's own colours (render/colormap.cpp).
#include <nlohmann/json.hpp>

namespace lienewton::service {

nlohmann::json openapi_labels();

}  // namespace lienewton::service

#pragma once
// `lienewton --format csv|table`: a result's records as rows, one column per scalar field (by name; matrices and
// nested objects left out, they stay in the JSON): a solve's trace, a sweep's cells, an integration's steps, the
// work-precision points (after their choice's integrator, method and differential; without the deprecated
// error, which global_error repeats), a basin map's per-method summary.
#include <nlohmann/json.hpp>
#include <string>

namespace lienewton::cli {

enum class Format { json, csv, table };

// The rows of `command`'s result (a command without rows: one row, the result's scalars).
nlohmann::ordered_json result_rows(const std::string& command, const nlohmann::json& result);

// CSV (RFC 4180: a header line, numbers as JSON writes them, null as an empty cell) or a table aligned for a
// terminal (numbers to 6 significant digits, null as -).
std::string format_rows(const nlohmann::ordered_json& rows, Format format);

}  // namespace lienewton::cli

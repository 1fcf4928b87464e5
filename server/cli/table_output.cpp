#include "server/cli/table_output.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <vector>

#include "server/json_codec.hpp"

namespace lienewton::cli {
namespace {

using nlohmann::json;
using nlohmann::ordered_json;

// The scalars of `record`, after `prefix` (a work-precision point's choice), less the `skip` field.
ordered_json flat(const json& record, ordered_json prefix = ordered_json::object(), const std::string& skip = "") {
  for (const auto& [key, value] : record.items())
    if (value.is_primitive() && key != skip) prefix[key] = value;
  return prefix;
}

std::string csv_cell(const ordered_json& v) {
  if (v.is_null()) return "";
  std::string text = v.is_string() ? v.get<std::string>() : service::dump(v);
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string table_cell(const ordered_json& v) {
  if (v.is_null()) return "-";
  if (v.is_number_float()) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", v.get<double>());
    return buffer;
  }
  return v.is_string() ? v.get<std::string>() : service::dump(v);
}

}  // namespace

ordered_json result_rows(const std::string& command, const json& result) {
  ordered_json rows = ordered_json::array();
  const auto each = [&](const char* key) {
    for (const json& record : result.value(key, json::array())) rows.push_back(flat(record));
  };
  if (command == "solve") each("trace");
  else if (command == "sweep") each("cells");
  else if (command == "integrate") each("steps");
  else if (command == "basins") each("methods");
  else if (command == "work-precision") {
    for (const json& series : result.value("series", json::array())) {
      ordered_json choice = ordered_json::object();
      for (const char* key : {"integrator", "method", "differential"}) choice[key] = series["choice"].value(key, "");
      for (const json& point : series.value("points", json::array())) rows.push_back(flat(point, choice, "error"));
    }
  } else {
    rows.push_back(flat(result));
  }
  return rows;
}

std::string format_rows(const ordered_json& rows, Format format) {
  std::vector<std::string> columns;  // every row's keys, in order of first appearance
  for (const ordered_json& row : rows)
    for (const auto& [key, _] : row.items())
      if (std::find(columns.begin(), columns.end(), key) == columns.end()) columns.push_back(key);
  std::vector<std::vector<std::string>> cells{columns};
  std::vector<bool> numeric(columns.size(), true);  // every value a number or null: right-aligned
  for (const ordered_json& row : rows) {
    std::vector<std::string> line;
    for (std::size_t i = 0; i < columns.size(); ++i) {
      const ordered_json v = row.contains(columns[i]) ? row[columns[i]] : ordered_json(nullptr);
      if (!v.is_number() && !v.is_null()) numeric[i] = false;
      line.push_back(format == Format::csv ? csv_cell(v) : table_cell(v));
    }
    cells.push_back(std::move(line));
  }
  std::ostringstream out;
  if (format == Format::csv) {
    for (const auto& line : cells) {
      for (std::size_t i = 0; i < line.size(); ++i) out << (i ? "," : "") << line[i];
      out << "\n";
    }
    return out.str();
  }
  std::vector<std::size_t> width(columns.size(), 0);
  for (const auto& line : cells)
    for (std::size_t i = 0; i < line.size(); ++i) width[i] = std::max(width[i], line[i].size());
  for (const auto& line : cells) {
    std::string text;
    for (std::size_t i = 0; i < line.size(); ++i) {
      // Numbers right-aligned, text left-aligned; the header follows its column.
      const std::string pad(width[i] - line[i].size(), ' ');
      text += (i ? "  " : "") + (numeric[i] ? pad + line[i] : line[i] + pad);
    }
    text.erase(text.find_last_not_of(' ') + 1);
    out << text << "\n";
  }
  return out.str();
}

}  // namespace lienewton::cli

#include "server/query_params.hpp"

#include "server/render_requests.hpp"

namespace lienewton::service {
namespace {

// A scalar: a JSON number or boolean when it parses as one, else the raw string.
json scalar(const std::string& text) {
  if (text == "true") return true;
  if (text == "false") return false;
  if (!text.empty() && (text[0] == '-' || (text[0] >= '0' && text[0] <= '9'))) {
    try {
      json parsed = json::parse(text);
      if (parsed.is_number()) return parsed;
    } catch (const json::exception&) {
      // not a number (or one that overflows a double): the codec reports it as the field's type error
    }
  }
  return text;
}

// A text field (the program g): its value is the text as typed, commas, brackets and all. Split at its commas, a
// program such as "R = y(1:3,1:3); ..." became a list and was refused as "g must be a string".
bool text_field(const std::string& key) {
  for (const fields::Field& f : fields::request_fields())
    if (f.name == key && f.type == fields::Type::string && !f.array) return true;
  return false;
}

}  // namespace

std::set<std::string> list_fields(fields::Routes routes) {
  std::set<std::string> out;
  for (const auto* rows : {&fields::request_fields(), &picture_fields()})
    for (const fields::Field& f : *rows)
      if (f.array && (f.routes & routes)) out.insert(f.name);
  return out;
}

json query_to_json(const std::multimap<std::string, std::string>& params, const std::set<std::string>& list_fields) {
  json out = json::object();
  for (const auto& [key, value] : params) {
    if (out.contains(key)) throw FieldError("duplicate_field", key, "duplicate parameter " + key);
    if (text_field(key)) {
      out[key] = value;
    } else if (!value.empty() && (value[0] == '[' || value[0] == '{')) {
      try {
        out[key] = parse_body(value);
      } catch (const FieldError&) {
        throw FieldError("invalid_field", key, key + " is not valid JSON");
      }
    } else if (value.find(',') != std::string::npos) {
      json list = json::array();
      std::size_t start = 0;
      while (true) {
        const auto comma = value.find(',', start);
        list.push_back(scalar(value.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
        if (comma == std::string::npos) break;
        start = comma + 1;
      }
      out[key] = std::move(list);
    } else if (list_fields.count(key)) {
      out[key] = json::array({scalar(value)});
    } else {
      out[key] = scalar(value);
    }
  }
  return out;
}

}  // namespace lienewton::service

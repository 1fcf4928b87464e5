#include "server/cli/command_help.hpp"

#include <sstream>
#include <variant>

namespace lienewton::cli {

namespace {

std::string type_text(const fields::Field& f) {
  std::string t;
  switch (f.type) {
    case fields::Type::number: t = "NUMBER"; break;
    case fields::Type::integer: t = "INTEGER"; break;
    case fields::Type::boolean: t = "true|false"; break;
    case fields::Type::string: t = f.values.empty() ? "TEXT" : "NAME"; break;
    case fields::Type::object: t = "JSON"; break;
    case fields::Type::matrix: t = "MATRIX"; break;
  }
  return f.array ? t + ",..." : t;
}

std::string default_text(const fields::Field& f) {
  return std::visit(
      [](const auto& v) -> std::string {
        using V = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<V, std::monostate>) return "";
        else if constexpr (std::is_same_v<V, double>) return fields::format_bound(v);
        else if constexpr (std::is_same_v<V, long long>) return std::to_string(v);
        else if constexpr (std::is_same_v<V, bool>) return v ? "true" : "false";
        else return v;
      },
      f.default_value);
}

// "one of a, b, c", "in (0, 1e6]", or nothing.
std::string values_text(const fields::Field& f) {
  if (!f.values.empty()) {
    std::string s = "one of ";
    for (std::size_t i = 0; i < f.values.size(); ++i) s += (i ? ", " : "") + f.values[i];
    return s;
  }
  if (!f.minimum && !f.maximum) return "";
  const std::string lo = f.minimum ? fields::format_bound(*f.minimum) : "-inf";
  const std::string hi = f.maximum ? fields::format_bound(*f.maximum) : "inf";
  return "in " + std::string(f.exclusive_minimum ? "(" : "[") + lo + ", " + hi + "]";
}

}  // namespace

std::string command_help(const std::string& command, const std::vector<const fields::Field*>& fields) {
  std::ostringstream out;
  out << "usage: lienewton " << command << " [--FIELD VALUE ...] [--pretty] [< request.json]\n\n"
      << "Fields (as flags, - or _ alike, or as the JSON object on stdin; absent ones take their defaults):\n";
  for (const fields::Field* f : fields) {
    std::string flag = f->name;
    for (char& c : flag) c = c == '_' ? '-' : c;
    out << "  --" << flag << " " << type_text(*f) << "\n";
    std::string about = f->description;
    const std::string values = values_text(*f), fallback = default_text(*f);
    if (!values.empty()) about += (about.empty() ? "" : "; ") + values;
    if (!fallback.empty()) about += (about.empty() ? "" : "; ") + std::string("default ") + fallback;
    if (!about.empty()) out << "      " << about << "\n";
  }
  out << "\nlienewton --help lists the commands; /openapi.json has the same fields as a schema.\n";
  return out.str();
}

}  // namespace lienewton::cli

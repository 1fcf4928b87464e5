#include "server/json_codec.hpp"

#include "core/fields.hpp"
#include "core/group_registry.hpp"
#include "core/problems.hpp"
#include "core/user_field/program.hpp"
#include "core/user_field/syntax.hpp"
#include "core/validation.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

namespace lienewton::service {
namespace {

constexpr int kMaxDepth = 32;  // deepest legal request is 4 levels; deeper input is an attack or a mistake

[[noreturn]] void fail(const std::string& field, const std::string& message) {
  throw FieldError("invalid_field", field, message);
}

std::vector<std::string_view> names_of(const std::vector<const fields::Field*>& rows) {
  std::vector<std::string_view> out;
  for (const fields::Field* row : rows) out.emplace_back(row->name);
  return out;
}

std::vector<std::string_view> names_of(const std::vector<fields::Field>& rows) {
  std::vector<std::string_view> out;
  for (const fields::Field& row : rows) out.emplace_back(row.name);
  return out;
}

// An object whose keys must all be known; null values count as absent so clients may send explicit nulls.
class Fields {
 public:
  Fields(const json& value, std::string prefix, std::vector<std::string_view> allowed)
      : object_(value), prefix_(std::move(prefix)) {
    if (!value.is_object()) {
      fail(prefix_.empty() ? std::string() : prefix_.substr(0, prefix_.size() - 1),
           prefix_.empty() ? "the request must be a JSON object" : prefix_.substr(0, prefix_.size() - 1) + " must be an object");
    }
    for (const auto& [key, _] : value.items()) {
      bool known = false;
      for (auto name : allowed) known = known || key == name;
      if (!known) throw FieldError("unknown_field", prefix_ + key, "unknown field " + prefix_ + key);
    }
  }
  Fields(const json& value, std::string prefix, std::initializer_list<std::string_view> allowed)
      : Fields(value, std::move(prefix), std::vector<std::string_view>(allowed)) {}
  const json* operator[](std::string_view name) const {
    auto it = object_.find(name);
    if (it == object_.end() || it->is_null()) return nullptr;
    return &*it;
  }
  std::string path(std::string_view name) const { return prefix_ + std::string(name); }

 private:
  const json& object_;
  std::string prefix_;
};

std::string range_text(long long lo, long long hi) {
  // Built by appending: GCC 12 reports a false -Wrestrict on "[" + std::to_string(...).
  std::string out("[");
  out.append(std::to_string(lo)).append(", ").append(std::to_string(hi)).append("]");
  return out;
}

// Integers must be JSON integers (no 3.0, no 1e300) and in range *before* conversion: get<int> wraps silently.
int read_int(const json& v, const std::string& field, long long lo, long long hi) {
  const std::string message = field + " must be an integer in " + range_text(lo, hi);
  if (!v.is_number_integer()) fail(field, message);
  if (v.is_number_unsigned()) {
    const auto u = v.get<std::uint64_t>();
    if (hi < 0 || u > static_cast<std::uint64_t>(hi) || static_cast<long long>(u) < lo) fail(field, message);
    return static_cast<int>(u);
  }
  const auto s = v.get<std::int64_t>();
  if (s < lo || s > hi) fail(field, message);
  return static_cast<int>(s);
}

std::uint64_t read_u64(const json& v, const std::string& field) {
  if (v.is_number_unsigned()) return v.get<std::uint64_t>();
  if (v.is_number_integer() && v.get<std::int64_t>() >= 0) return static_cast<std::uint64_t>(v.get<std::int64_t>());
  fail(field, field + " must be an unsigned 64-bit integer");
}

double read_number(const json& v, const std::string& field, const std::string& message) {
  if (!v.is_number()) fail(field, message);
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(field, message);
  return d;
}

// A finite number within the field's bounds (core/fields.hpp), named by its path in the error.
double read_field(const json& v, const fields::NumberField& field, const std::string& path) {
  const double x = read_number(v, path, field.message(path));
  if (!field.contains(x)) fail(path, field.message(path));
  return x;
}

// An integer within the field's bounds, capped by the server's limit (--max-n).
int read_field(const json& v, const fields::IntegerField& field, const std::string& path, long long cap) {
  return read_int(v, path, field.min, std::min(field.max, cap));
}

double read_h(const json& v, const std::string& path) { return read_field(v, fields::h, path); }

bool read_bool(const json& v, const std::string& field) {
  if (!v.is_boolean()) fail(field, field + " must be true or false");
  return v.get<bool>();
}

template <class Enum, std::size_t K>
Enum read_enum(const json& v, const std::string& field, std::optional<Enum> (*from_string)(std::string_view),
               const Enum (&all)[K]) {
  std::string names;
  for (auto e : all) names += (names.empty() ? "" : ", ") + std::string(to_string(e));
  const std::string message = field + " must be one of " + names;
  if (!v.is_string()) fail(field, message);
  auto parsed = from_string(v.get_ref<const std::string&>());
  if (!parsed) fail(field, message);
  return *parsed;
}

const json& read_array(const json& v, const std::string& field, std::size_t min_size, std::size_t max_size,
                       const std::string& what) {
  if (!v.is_array() || v.size() < min_size || v.size() > max_size) {
    fail(field, field + " must be an array of " + what + " with " + std::to_string(min_size) + " to " +
                    std::to_string(max_size) + " elements");
  }
  return v;
}

Eigen::MatrixXd read_matrix(const json& v, const std::string& field, MatrixShape shape, const std::string& message) {
  if (!v.is_array() || v.size() != static_cast<std::size_t>(shape.rows)) fail(field, message);
  Eigen::MatrixXd m(shape.rows, shape.cols);
  for (int i = 0; i < shape.rows; ++i) {
    const json& row = v[static_cast<std::size_t>(i)];
    if (!row.is_array() || row.size() != static_cast<std::size_t>(shape.cols)) fail(field, message);
    for (int j = 0; j < shape.cols; ++j) m(i, j) = read_number(row[static_cast<std::size_t>(j)], field, message);
  }
  return m;
}
Eigen::MatrixXd read_matrix(const json& v, const std::string& field, int n, const std::string& message) {
  return read_matrix(v, field, MatrixShape{n, n}, message);
}

Eigen::MatrixXd read_matrix(const json& v, const std::string& field, int n) {
  return read_matrix(v, field, n,
                     field + " must be an n x n array of rows of finite numbers (n = " + std::to_string(n) + ")");
}

// ---- Reading a request by the rows of core/fields.hpp --------------------------------------------------------

// The server's limit on top of a row's bound.
long long cap_of(fields::Cap cap, const Limits& limits) {
  switch (cap) {
    case fields::Cap::n: return limits.max_n;
    case fields::Cap::iterations: return limits.max_iterations;
    case fields::Cap::threads: return limits.max_threads;
    case fields::Cap::frames: return limits.max_frames;
    case fields::Cap::grid_axis:
      return static_cast<long long>(std::min<std::size_t>(limits.max_grid_cells, LLONG_MAX));
    case fields::Cap::none: break;
  }
  return LLONG_MAX;
}

// What one request's reading knows besides the row: the server's limits and the problem's n so far (matrices
// and algebra coordinates are sized by it).
struct Reading {
  const Limits& limits;
  int* n = nullptr;       // the request's ProblemSpec::n
  const std::string* group = nullptr;  // the request's ProblemSpec::group (algebra coordinates are its group's)
  bool n_given = false;   // the request names n (else a z names it)
  bool family_bounds_n = false;  // the group's family bounds n itself (max_index), not --max-n
};

// The enums' lists, for parsing a name by its place in the row's values.
const auto& all_of(std::type_identity<ProblemKind>) { return kAllProblems; }
const auto& all_of(std::type_identity<Method>) { return kAllMethods; }
const auto& all_of(std::type_identity<Differential>) { return kAllDifferentials; }
const auto& all_of(std::type_identity<LinearSolver>) { return kAllLinearSolvers; }
const auto& all_of(std::type_identity<Stopping>) { return kAllStoppings; }
const auto& all_of(std::type_identity<Globalization>) { return kAllGlobalizations; }
const auto& all_of(std::type_identity<Integrator>) { return kAllIntegrators; }
const auto& all_of(std::type_identity<Predictor>) { return kAllPredictors; }

template <class T>
using Tag = std::type_identity<T>;

double read_value(const json& v, const fields::Field& row, const std::string& path, Reading&, Tag<double>) {
  const double x = read_number(v, path, row.number_message(path));
  if (!row.contains(x)) fail(path, row.number_message(path));
  return x;
}

// A number whose absence means "the default of the request's group" (basins' r).
std::optional<double> read_value(const json& v, const fields::Field& row, const std::string& path, Reading& r,
                                 Tag<std::optional<double>>) {
  return read_value(v, row, path, r, Tag<double>{});
}

int read_value(const json& v, const fields::Field& row, const std::string& path, Reading& r, Tag<int>) {
  const long long lo = row.minimum ? static_cast<long long>(*row.minimum) : INT_MIN;
  const long long hi = row.maximum ? static_cast<long long>(*row.maximum) : INT_MAX;
  const long long cap = row.cap == fields::Cap::n && r.family_bounds_n ? LLONG_MAX : cap_of(row.cap, r.limits);
  return read_int(v, path, lo, std::min(hi, cap));
}

bool read_value(const json& v, const fields::Field&, const std::string& path, Reading&, Tag<bool>) {
  return read_bool(v, path);
}

std::uint64_t read_value(const json& v, const fields::Field&, const std::string& path, Reading&, Tag<std::uint64_t>) {
  return read_u64(v, path);
}

// A name; whether it names something (a registered group) is the core's question (422).
std::string read_value(const json& v, const fields::Field&, const std::string& path, Reading&, Tag<std::string>) {
  if (!v.is_string()) fail(path, path + " must be a string");
  return v.get<std::string>();
}

// A user's program (g); whether it compiles is the core's question (422 with line and column).
std::optional<std::string> read_value(const json& v, const fields::Field& row, const std::string& path, Reading& r,
                                      Tag<std::optional<std::string>>) {
  return read_value(v, row, path, r, Tag<std::string>{});
}

// A program's named values: each a number (1 x 1), an array of numbers (a row) or an array of rows (a matrix).
user_field::Parameters read_value(const json& v, const fields::Field&, const std::string& path, Reading&,
                                  Tag<user_field::Parameters>) {
  if (!v.is_object()) fail(path, path + " must be an object of named numbers and matrices");
  user_field::Parameters out;
  for (const auto& [name, x] : v.items()) {
    const std::string at = path + "." + name;
    const std::string message = at + " must be a finite number, an array of them, an array of equal-length rows "
                                     "or an expression of constants as text (\"pi/4\", \"0.1*eye(3)\")";
    if (x.is_string()) {  // the core evaluates it (422 naming the parameter, with its line and column)
      out[name] = user_field::constant_value(x.get_ref<const std::string&>(), at);
      continue;
    }
    if (x.is_number()) {
      out[name] = Eigen::MatrixXd::Constant(1, 1, read_number(x, at, message));
      continue;
    }
    if (!x.is_array() || x.empty()) fail(at, message);
    const bool rows = x[0].is_array();
    const std::size_t r = rows ? x.size() : 1, c = rows ? x[0].size() : x.size();
    if (double(r) * double(c) > user_field::kMaxElements) fail(at, at + " is too large");
    Eigen::MatrixXd m(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c));
    for (std::size_t i = 0; i < r; ++i) {
      const json& row = rows ? x[i] : x;
      if (!row.is_array() || row.size() != c) fail(at, message);
      for (std::size_t j = 0; j < c; ++j)
        m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = read_number(row[j], at, message);
    }
    out[name] = std::move(m);
  }
  return out;
}

template <class E>
  requires std::is_enum_v<E>
E read_value(const json& v, const fields::Field& row, const std::string& path, Reading&, Tag<E>) {
  std::string names;
  for (const auto& name : row.values) names += (names.empty() ? "" : ", ") + name;
  const std::string message = path + " must be one of " + names;
  if (!v.is_string()) fail(path, message);
  const auto& all = all_of(Tag<E>{});
  for (std::size_t i = 0; i < row.values.size(); ++i)
    if (row.values[i] == v.get_ref<const std::string&>()) return all[i];
  fail(path, message);
}

// A matrix of the request's group's shape (n x n on SO(n), (n + 1) x (n + 1) on SE(n), 11 x 11k on k bodies); an
// unknown group is refused here with the registry's 422.
std::optional<Eigen::MatrixXd> read_value(const json& v, const fields::Field&, const std::string& path, Reading& r,
                                          Tag<std::optional<Eigen::MatrixXd>>) {
  const GroupFamily& family = group_family(*r.group);
  const MatrixShape shape = family.matrix_shape(*r.n);
  if (shape == MatrixShape{*r.n, *r.n}) return read_matrix(v, path, *r.n);
  return read_matrix(v, path, shape, path + " must be a " + shape.text() + " array of rows of finite numbers (an "
                                         "element of " + family.title(*r.n) + ")");
}

// A fixed-length vector of numbers within the row's bounds (rigid_body.inertia: positive).
Eigen::Vector3d read_value(const json& v, const fields::Field& row, const std::string& path, Reading&,
                           Tag<Eigen::Vector3d>) {
  const std::string message = path + " must be an array of " + row.items;
  if (!v.is_array() || v.size() != 3) fail(path, message);
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i) {
    out[i] = read_number(v[static_cast<std::size_t>(i)], path, message);
    if (!row.contains(out[i])) fail(path, message);
  }
  return out;
}

// A 3 x 3 matrix of finite numbers (heavy_top.rotation, stiff_body.rotation; whether it is a rotation is the
// core's question, 422).
Eigen::Matrix3d read_value(const json& v, const fields::Field&, const std::string& path, Reading&, Tag<Eigen::Matrix3d>) {
  return read_matrix(v, path, 3, path + " must be a 3 x 3 array of rows of finite numbers");
}

// Coordinates in the algebra of the request's group (SO(n): n(n-1)/2 of them); an unknown group is refused here
// with the registry's 422.
std::optional<Eigen::VectorXd> read_value(const json& v, const fields::Field&, const std::string& path, Reading& r,
                                          Tag<std::optional<Eigen::VectorXd>>) {
  const GroupFamily& family = group_family(*r.group);
  const auto dim = static_cast<std::size_t>(family.algebra_dim(*r.n));
  const std::string message = path + " must be an array of " + std::to_string(dim) +
                              " finite numbers (coordinates in the algebra, " + family.algebra_dimension() + " of them)";
  if (!v.is_array() || v.size() != dim) fail(path, message);
  Eigen::VectorXd out(static_cast<Eigen::Index>(dim));
  for (std::size_t i = 0; i < dim; ++i) out[static_cast<Eigen::Index>(i)] = read_number(v[i], path, message);
  return out;
}

const fields::Field& property(const fields::Field& row, std::string_view name) {
  for (const fields::Field& p : row.properties)
    if (p.name == name) return p;
  throw std::logic_error("no property " + std::string(name) + " in " + row.name);
}

// {"index": i, "count": k}, 0 <= i < k: a non-negative index beyond the count is well-formed but names no part
// (422).
std::optional<Shard> read_value(const json& v, const fields::Field& row, const std::string& path, Reading& r,
                                Tag<std::optional<Shard>>) {
  Fields f(v, path + ".", names_of(row.properties));
  const json* index = f["index"];
  const json* count = f["count"];
  if (!index || !count) fail(path, path + " needs index and count");
  Shard s;
  s.count = read_value(*count, property(row, "count"), f.path("count"), r, Tag<int>{});
  s.index = read_value(*index, property(row, "index"), f.path("index"), r, Tag<int>{});
  if (s.index >= s.count)
    throw RequestError(RequestError::Kind::unprocessable, f.path("index"),
                       f.path("index") + " must be less than " + f.path("count") + " (" + std::to_string(s.count) + ")");
  return s;
}

template <class Target>
void read_object(const json& v, const std::string& prefix, const std::vector<const fields::Field*>& rows, Target& target,
                 Reading& r);

// An object of the row's properties (rigid_body), read into its own struct.
template <class T>
  requires std::is_aggregate_v<T>
T read_value(const json& v, const fields::Field& row, const std::string& path, Reading& r, Tag<T>) {
  std::vector<const fields::Field*> rows;
  for (const fields::Field& p : row.properties) rows.push_back(&p);
  T out{};
  read_object(v, path + ".", rows, out, r);
  return out;
}

// An array: its size within the row's [min_items, max_items] (capped), each element read as the row describes.
template <class T>
std::vector<T> read_value(const json& v, const fields::Field& row, const std::string& path, Reading& r,
                          Tag<std::vector<T>>) {
  const long long cap = cap_of(row.cap_items, r.limits);
  const auto& items = read_array(v, path, row.min_items,
                                 std::min<std::size_t>(row.max_items, static_cast<std::size_t>(cap)), row.items);
  std::vector<T> out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    // Objects are named by their place (choices[2].method), plain values by the field (h).
    const std::string item_path = row.type == fields::Type::object ? path + "[" + std::to_string(i) + "]" : path;
    out.push_back(read_value(items[i], row, item_path, r, Tag<T>{}));
  }
  return out;
}

// The part of a request a member belongs to: the request itself, its ProblemSpec or SolverOptions, or (a basin
// map) its solve request's; nullptr when the request has no such part.
template <class C, class R>
C* part(R& r) {
  if constexpr (std::is_same_v<C, R>) return &r;
  else if constexpr (std::is_same_v<C, ProblemSpec> && requires { r.problem; }) return &r.problem;
  else if constexpr (std::is_same_v<C, SolverOptions> && requires { r.solver; }) return &r.solver;
  else if constexpr (requires { r.solve; }) return part<C>(r.solve);
  else return nullptr;
}

template <class R, class C, class T>
void land(R& request, T C::*member, const json& v, const fields::Field& row, const std::string& path, Reading& r) {
  C* target = part<C>(request);
  if (!target) return;
  if constexpr (std::is_same_v<C, ProblemSpec> && std::is_same_v<T, std::optional<Eigen::MatrixXd>>) {
    // z without n: n is the index whose matrices have z's size (z's size itself unless the default n's do), on the
    // families of square matrices (a system of bodies is named with its n).
    const MatrixShape shape = group_family(*r.group).matrix_shape(target->n);
    if (!r.n_given && v.is_array() && v.size() >= 2 && v.size() <= static_cast<std::size_t>(r.limits.max_n) &&
        shape.square() && shape != MatrixShape{int(v.size()), int(v.size())})
      target->n = static_cast<int>(v.size());
  }
  target->*member = read_value(v, row, path, r, Tag<T>{});
}

// Reads the rows present in the object, in the table's order (the first bad field is the one reported).
template <class Target>
void read_object(const json& v, const std::string& prefix, const std::vector<const fields::Field*>& rows, Target& target,
                 Reading& r) {
  Fields f(v, prefix, names_of(rows));
  for (const fields::Field* row : rows) {
    const json* x = f[row->name];
    if (!x) continue;
    for (const fields::Member& member : row->lands)
      std::visit([&](auto m) { land(target, m, *x, *row, f.path(row->name), r); }, member);
  }
}

// "group": "SExR^8" is {"group": "SExR^k", "n": 8} when "SExR^k" is a registered family that bounds its index; an
// index out of its range is a 422 naming group, a different explicit n one naming n. Other names pass unchanged.
json with_power_shorthand(const json& body) {
  if (!body.is_object() || !body.contains("group") || !body["group"].is_string()) return body;
  const std::string& name = body["group"].get_ref<const std::string&>();
  const std::size_t caret = name.rfind('^');
  if (caret == std::string::npos || caret + 1 == name.size() ||
      name.find_first_not_of("0123456789", caret + 1) != std::string::npos)
    return body;
  const std::string family_name = name.substr(0, caret) + "^k";
  const auto names = registered_group_names();
  if (std::find(names.begin(), names.end(), family_name) == names.end()) return body;
  const std::optional<int> max = group_family(family_name).max_index();
  const std::string digits = name.substr(caret + 1);
  const long long k = digits.size() > 6 ? LLONG_MAX : std::stoll(digits);
  if (!max || k < fields::n.min || k > *max)
    throw RequestError(RequestError::Kind::unprocessable, "group",
                       "group " + name + " must name " + std::to_string(fields::n.min) + " to " +
                           std::to_string(max.value_or(fields::n.min)) + " bodies (" + family_name + " with n = k)");
  json out = body;
  // A sweep's n is a list: [k] says the same.
  const bool listed = out.contains("n") && out["n"] == json::array({k});
  if (out.contains("n") && !out["n"].is_null() && out["n"] != json(k) && !listed)
    throw RequestError(RequestError::Kind::unprocessable, "n",
                       "group " + name + " has n = " + digits + ": n must be " + digits + " (or [" + digits +
                           "] on a sweep) or absent, got " + out["n"].dump());
  out["group"] = family_name;
  if (!listed) out["n"] = k;
  return out;
}

// A built-in problem written for one group ("problem": "heavy-top": SOxR; "chain": SExR^k) implies it when the
// request names no group and no program of its own; a group given is checked against it (validation).
json with_implied_group(const json& body) {
  if (!body.is_object() || !body.contains("problem") || !body["problem"].is_string() ||
      (body.contains("group") && !body["group"].is_null()) || (body.contains("g") && !body["g"].is_null()))
    return body;
  for (ProblemKind kind : kAllProblems) {
    if (body["problem"] != to_string(kind)) continue;
    const std::optional<std::string> group = required_group(kind);
    if (!group) return body;
    json out = body;
    out["group"] = *group;
    return out;
  }
  return body;  // not a problem's name: its row refuses it
}

// The group names a registered family that bounds its index itself (max_index: SExR^k's bodies), so that the
// server's --max-n does not apply to it.
bool family_bounds_index(const std::string& group) {
  const auto names = registered_group_names();
  return std::find(names.begin(), names.end(), group) != names.end() && group_family(group).max_index().has_value();
}

// A route's request: every row the route takes, read into the request struct.
template <class Request>
Request read_request(const json& given, fields::Route route, const Limits& limits) {
  const json body = with_power_shorthand(with_implied_group(given));
  Request request;
  Reading r{limits};
  r.n = &part<ProblemSpec>(request)->n;
  r.group = &part<ProblemSpec>(request)->group;
  r.n_given = body.is_object() && body.contains("n") && !body["n"].is_null();
  if (body.is_object() && body.contains("group") && body["group"].is_string())
    r.family_bounds_n = family_bounds_index(body["group"].get_ref<const std::string&>());
  try {
    read_object(body, "", fields::fields_of(route), request, r);
  } catch (const RequestError& e) {
    // A parameter's expression is evaluated as it is read, before the program compiles; a program that does not
    // even parse is the first thing to fix, so its error is the one reported.
    if (!e.field().starts_with("parameters.") || !body.contains("g") || !body["g"].is_string()) throw;
    (void)user_field::parse(body["g"].get_ref<const std::string&>());
    throw;
  }
  if (part<ProblemSpec>(request)->g && body.contains("problem") && !body["problem"].is_null())
    throw RequestError(RequestError::Kind::unprocessable, "g",
                       "give either g (your own field) or problem (a built-in one), not both");
  return request;
}

json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
json optional_number(const std::optional<double>& v) { return v ? finite_or_null(*v) : json(nullptr); }
json optional_integer(const std::optional<int>& v) { return v ? json(*v) : json(nullptr); }

}  // namespace

Limits Limits::unlimited() {
  Limits l;
  l.max_n = INT_MAX;
  l.max_iterations = INT_MAX;
  l.max_grid_cells = std::numeric_limits<std::size_t>::max();
  l.max_steps = std::numeric_limits<double>::infinity();
  l.max_t_end = fields::t_end.max;
  l.max_frames = INT_MAX;
  l.max_threads = 1024;
  return l;
}

std::string error_code(const RequestError& error) {
  if (auto fe = dynamic_cast<const FieldError*>(&error)) return fe->code();
  switch (error.kind()) {
    case RequestError::Kind::unprocessable: return "unprocessable";
    case RequestError::Kind::too_large: return "program_too_large";
    case RequestError::Kind::invalid: break;
  }
  return "invalid_field";
}

json parse_body(std::string_view text) {
  if (text.empty()) throw FieldError("malformed_json", "", "the request body is empty; send a JSON object");
  // nlohmann's parser stops at a NUL byte and accepts what came before it.
  if (text.find('\0') != std::string_view::npos) {
    throw FieldError("malformed_json", "", "the request body holds a NUL byte");
  }
  std::vector<std::set<std::string>> keys;  // one set per open object
  json::parser_callback_t check = [&](int depth, json::parse_event_t event, json& parsed) {
    if (depth > kMaxDepth) throw FieldError("malformed_json", "", "the request body is nested too deeply");
    if (event == json::parse_event_t::object_start) keys.emplace_back();
    if (event == json::parse_event_t::object_end && !keys.empty()) keys.pop_back();
    if (event == json::parse_event_t::key && !keys.empty()) {
      const auto& name = parsed.get_ref<const std::string&>();
      if (!keys.back().insert(name).second) throw FieldError("duplicate_field", name, "duplicate field " + name);
    }
    return true;
  };
  try {
    return json::parse(text.begin(), text.end(), check);
  } catch (const json::parse_error& e) {
    throw FieldError("malformed_json", "", "the request body is not valid JSON (at byte " + std::to_string(e.byte) + ")");
  } catch (const json::exception&) {
    // e.g. out_of_range.406: a number literal that overflows a double (1e400) would be Inf.
    throw FieldError("malformed_json", "", "the request body holds a number outside the range of a double");
  }
}

SolveRequest solve_request_from_json(const json& body, const Limits& limits) {
  return read_request<SolveRequest>(body, fields::solve, limits);
}

SweepRequest sweep_request_from_json(const json& body, const Limits& limits) {
  SweepRequest r = read_request<SweepRequest>(body, fields::sweep, limits);
  // The defaults count too; n's default (the paper's 2..15) must also respect the server's N cap.
  const SweepRequest full = with_defaults(r);
  for (int n : full.n) {
    if (n > limits.max_n && !family_bounds_index(full.problem.group)) fail("n", fields::n.message("n", limits.max_n));
  }
  const double cells = static_cast<double>(full.methods.size()) * static_cast<double>(full.n.size()) *
                       static_cast<double>(full.h.size());
  if (cells > static_cast<double>(limits.max_grid_cells)) {
    fail("h", "the grid has " + std::to_string(static_cast<long long>(cells)) + " cells (methods x n x h); at most " +
                  std::to_string(limits.max_grid_cells) + " are allowed");
  }
  return r;
}

namespace {
// The server's cap on t_end (--max-t-end); the CLI's is the core's.
void check_t_end(double t_end, const Limits& limits) {
  if (t_end > limits.max_t_end)
    fail("t_end", "t_end must be at most " + fields::format_bound(limits.max_t_end) + " (the server's --max-t-end)");
}
}  // namespace

IntegrateRequest integrate_request_from_json(const json& body, const Limits& limits) {
  IntegrateRequest r = read_request<IntegrateRequest>(body, fields::integrate, limits);
  check_t_end(r.t_end, limits);
  r.integrator_defaulted = !body.contains("integrator");
  resolve_defaults(r);
  // Adaptive steps: h is only the first step; the tries are bounded by max_steps, at most the server's step limit.
  if (r.adaptive()) {
    r.max_steps = static_cast<int>(std::min<double>(r.max_steps, limits.max_steps));
    return r;
  }
  if (r.t_end / *r.h > limits.max_steps) {
    fail("h", "t_end / h must be at most " + std::to_string(static_cast<long long>(limits.max_steps)) + " steps");
  }
  return r;
}

WorkPrecisionRequest work_precision_request_from_json(const json& body, const Limits& limits) {
  WorkPrecisionRequest r = read_request<WorkPrecisionRequest>(body, fields::work_precision, limits);
  check_t_end(r.t_end, limits);
  validate(r.problem);  // its time scale gives the default h
  const WorkPrecisionRequest full = with_defaults(r);
  const double choices = static_cast<double>(full.choices.size());
  if (!r.tolerances.empty()) {  // adaptive runs share the server's step budget
    const double runs = choices * static_cast<double>(r.tolerances.size());
    if (runs > static_cast<double>(limits.max_grid_cells))
      fail("tolerances", "choices x tolerances must be at most " + std::to_string(limits.max_grid_cells) + " runs");
    r.max_steps = static_cast<int>(std::max(1.0, std::min<double>(r.max_steps, std::floor(limits.max_steps / runs))));
    return r;
  }
  // The core's defaults (every integrator, the problem's step sizes) count too.
  const std::vector<double>& hs = full.h;
  double steps = 0;
  for (double h : hs) steps += choices * r.t_end / h;
  if (choices * static_cast<double>(hs.size()) > static_cast<double>(limits.max_grid_cells)) {
    fail("h", "choices x h must be at most " + std::to_string(limits.max_grid_cells) + " runs");
  }
  if (steps > limits.max_steps) {
    fail("h", "the runs would take " + std::to_string(static_cast<long long>(steps)) + " steps in total; at most " +
                  std::to_string(static_cast<long long>(limits.max_steps)) + " are allowed");
  }
  return r;
}

// A solve request without method (and without y0 and include_iterates: every pixel has its own start and keeps
// no iterates) plus the plane: methods, size, r, b1, b2.
BasinRequest basin_request_from_json(const json& body, const Limits& limits) {
  if (!body.is_object()) fail("", "the request must be a JSON object");
  for (const char* name : {"method", "y0", "include_iterates"}) {
    if (body.contains(name))
      throw FieldError("unknown_field", name, std::string("unknown field ") + name + " (a basin map runs every one of "
                                              "methods from every start of its grid)");
  }
  BasinRequest r = read_request<BasinRequest>(body, fields::basins, limits);
  if (r.shard) {  // the parts of one map carry the same key
    json request = body;
    request.erase("shard");
    r.request_key = dump(request);
  }
  return r;
}

SweepResult sweep_result_from_json(const json& body, const Limits& limits) {
  Fields f(body, "sweep.", {"cells", "seconds", "shard"});
  SweepResult r;
  if (auto x = f["shard"]) {  // a part of a sharded sweep: its part, the grid's size, its cells' grid positions
    Fields s(*x, "sweep.shard.", {"index", "count", "grid_cells", "cell_indices"});
    const auto required = [&](std::string_view name) -> const json& {
      const json* v = s[name];
      if (!v) fail(s.path(name), s.path(name) + " is required");
      return *v;
    };
    r.shard = Shard{};
    r.shard->count = read_int(required("count"), s.path("count"), 1, 1000000);
    r.shard->index = read_int(required("index"), s.path("index"), 0, r.shard->count - 1);
    r.grid_cells = static_cast<std::size_t>(read_int(required("grid_cells"), s.path("grid_cells"), 0, INT_MAX));
    for (const auto& i : read_array(required("cell_indices"), s.path("cell_indices"), 0, r.grid_cells, "cell indices"))
      r.cell_indices.push_back(static_cast<std::size_t>(read_int(i, s.path("cell_indices"), 0, INT_MAX)));
  }
  const json* cells = f["cells"];
  if (!cells) fail("sweep.cells", "sweep.cells is required");
  const auto& arr = read_array(*cells, "sweep.cells", r.shard ? 0 : 1, limits.max_grid_cells, "cell objects");
  for (std::size_t i = 0; i < arr.size(); ++i) {
    Fields c(arr[i], "sweep.cells[" + std::to_string(i) + "].",
             {"method", "n", "h", "status", "reason", "iterations", "rate", "residual", "seconds"});
    SweepCell cell;
    auto required = [&](std::string_view name) -> const json& {
      const json* v = c[name];
      if (!v) fail(c.path(name), c.path(name) + " is required");
      return *v;
    };
    cell.method = read_enum(required("method"), c.path("method"), method_from_string, kAllMethods);
    cell.n = read_field(required("n"), fields::n, c.path("n"), limits.max_n);
    cell.h = read_h(required("h"), c.path("h"));
    cell.status = read_enum(required("status"), c.path("status"), status_from_string, kAllStatuses);
    if (auto v = c["reason"]) {
      if (!v->is_string()) fail(c.path("reason"), c.path("reason") + " must be a string");
      cell.reason = v->get<std::string>();
    }
    cell.iterations = read_int(required("iterations"), c.path("iterations"), 0, INT_MAX);
    if (auto v = c["rate"]) cell.rate = read_number(*v, c.path("rate"), c.path("rate") + " must be a finite number or null");
    if (auto v = c["residual"]) {
      cell.residual = read_number(*v, c.path("residual"), c.path("residual") + " must be a finite number or null");
    } else {
      cell.residual = std::numeric_limits<double>::quiet_NaN();  // null: the solve produced no finite residual
    }
    if (auto v = c["seconds"]) cell.seconds = read_number(*v, c.path("seconds"), c.path("seconds") + " must be a finite number");
    r.cells.push_back(std::move(cell));
  }
  if (auto v = f["seconds"]) r.seconds = read_number(*v, "sweep.seconds", "sweep.seconds must be a finite number");
  return r;
}

namespace {

// A number that the writer's finite_or_null may have written as null (NaN then).
double read_nullable_number(const Fields& f, std::string_view name) {
  const json* v = f[name];
  return v ? read_number(*v, f.path(name), f.path(name) + " must be a finite number or null")
           : std::numeric_limits<double>::quiet_NaN();
}

const json& required_field(const Fields& f, std::string_view name) {
  const json* v = f[name];
  if (!v) fail(f.path(name), f.path(name) + " is required");
  return *v;
}

Eigen::VectorXd read_vector(const json& v, const std::string& field, std::size_t max_size) {
  const auto& arr = read_array(v, field, 1, max_size, "finite numbers");
  Eigen::VectorXd out(static_cast<Eigen::Index>(arr.size()));
  for (std::size_t i = 0; i < arr.size(); ++i)
    out[static_cast<Eigen::Index>(i)] = read_number(arr[i], field, field + " must hold finite numbers");
  return out;
}

BasinGrid read_basin_grid(const json& v) {
  Fields f(v, "basins.grid.", {"a", "b", "r", "b1", "b2", "z"});
  BasinGrid g;
  const Eigen::VectorXd axis = read_vector(required_field(f, "a"), f.path("a"), kMaxBasinSize);
  g.axis.assign(axis.data(), axis.data() + axis.size());
  g.radius = read_number(required_field(f, "r"), f.path("r"), f.path("r") + " must be a finite number");
  const std::size_t dim = INT_MAX;  // n(n-1)/2 coordinates; merge_shards compares them across parts
  g.b1 = read_vector(required_field(f, "b1"), f.path("b1"), dim);
  g.b2 = read_vector(required_field(f, "b2"), f.path("b2"), dim);
  const json& z = required_field(f, "z");
  g.z = read_matrix(z, f.path("z"), z.is_array() ? static_cast<int>(z.size()) : 0);
  return g;
}

BasinRoot read_basin_root(const json& v, const std::string& prefix, int n) {
  Fields f(v, prefix, {"id", "y", "residual", "distance_from_z", "hg_angle"});
  BasinRoot root;
  root.id = read_int(required_field(f, "id"), f.path("id"), 0, INT_MAX);
  root.y = read_matrix(required_field(f, "y"), f.path("y"), n);
  root.residual = read_nullable_number(f, "residual");
  root.distance_from_z = read_nullable_number(f, "distance_from_z");
  root.hg_angle = read_nullable_number(f, "hg_angle");
  return root;
}

// A row of `size` pixels per method; the methods' names are checked against `methods` (the summary's order).
BasinRow read_basin_row(const json& v, const std::string& prefix, std::size_t size, const std::vector<Method>& methods) {
  Fields f(v, prefix, {"row", "b", "methods", "new_roots"});
  BasinRow row;
  row.row = read_int(required_field(f, "row"), f.path("row"), 0, static_cast<long long>(size) - 1);
  row.b = read_number(required_field(f, "b"), f.path("b"), f.path("b") + " must be a finite number");
  const auto& per_method = read_array(required_field(f, "methods"), f.path("methods"), methods.size(), methods.size(),
                                      "one object per method");
  for (std::size_t m = 0; m < methods.size(); ++m) {
    Fields pm(per_method[m], f.path("methods[" + std::to_string(m) + "]."), {"method", "status", "root", "iterations"});
    if (read_enum(required_field(pm, "method"), pm.path("method"), method_from_string, kAllMethods) != methods[m])
      fail(pm.path("method"), pm.path("method") + " is not the method of the summary at this place");
    const auto& status = read_array(required_field(pm, "status"), pm.path("status"), size, size, "statuses");
    const json& root = read_array(required_field(pm, "root"), pm.path("root"), size, size, "root ids or null");
    const auto& iterations = read_array(required_field(pm, "iterations"), pm.path("iterations"), size, size, "integers");
    std::vector<BasinPixel> pixels(size);
    for (std::size_t c = 0; c < size; ++c) {
      pixels[c].status = read_enum(status[c], pm.path("status"), status_from_string, kAllStatuses);
      pixels[c].root = root[c].is_null() ? -1 : read_int(root[c], pm.path("root"), 0, INT_MAX);
      pixels[c].iterations = read_int(iterations[c], pm.path("iterations"), 0, INT_MAX);
    }
    row.pixels.push_back(std::move(pixels));
  }
  return row;
}

}  // namespace

BasinResult basin_result_from_json(const json& body) {
  Fields f(body, "basins.", {"grid", "rows", "roots", "methods", "complete", "seconds", "shard"});
  BasinResult r;
  r.grid = read_basin_grid(required_field(f, "grid"));
  const std::size_t size = r.grid.axis.size();
  const int n = static_cast<int>(r.grid.z.rows());
  std::vector<Method> methods;
  const auto& summaries = read_array(required_field(f, "methods"), "basins.methods", 1, std::size(kAllMethods),
                                     "method summaries");
  for (std::size_t m = 0; m < summaries.size(); ++m) {
    const std::string path = "basins.methods[" + std::to_string(m) + "].method";
    if (!summaries[m].is_object() || !summaries[m].contains("method")) fail(path, path + " is required");
    methods.push_back(read_enum(summaries[m]["method"], path, method_from_string, kAllMethods));
  }
  r.methods = basin_summaries({}, methods);  // the methods' order; merge_shards recomputes the counts
  const auto& rows = read_array(required_field(f, "rows"), "basins.rows", 0, size, "row objects");
  for (std::size_t i = 0; i < rows.size(); ++i)
    r.rows.push_back(read_basin_row(rows[i], "basins.rows[" + std::to_string(i) + "].", size, methods));
  const auto& roots = read_array(required_field(f, "roots"), "basins.roots", 0, size * size * methods.size(), "root objects");
  for (std::size_t i = 0; i < roots.size(); ++i) {
    r.roots.push_back(read_basin_root(roots[i], "basins.roots[" + std::to_string(i) + "].", n));
    if (r.roots.back().id != static_cast<int>(i)) fail("basins.roots", "basins.roots must be numbered 0, 1, ... in order");
  }
  r.complete = read_bool(required_field(f, "complete"), "basins.complete");
  if (auto v = f["seconds"]) r.seconds = read_number(*v, "basins.seconds", "basins.seconds must be a finite number");
  if (auto v = f["shard"]) {  // the part's rows are the rows it holds
    Fields s(*v, "basins.shard.", {"index", "count", "rows", "request"});
    r.shard = Shard{};
    r.shard->count = read_int(required_field(s, "count"), s.path("count"), 1, 1000000);
    r.shard->index = read_int(required_field(s, "index"), s.path("index"), 0, r.shard->count - 1);
    if (auto q = s["request"]) r.request_key = dump(*q);
  }
  return r;
}

json to_json(const BasinGrid& g) {
  json axis = json::array();
  for (double v : g.axis) axis.push_back(finite_or_null(v));
  auto vector = [](const Eigen::VectorXd& v) {
    json out = json::array();
    for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(finite_or_null(v[i]));
    return out;
  };
  return json{{"a", axis}, {"b", axis}, {"r", finite_or_null(g.radius)}, {"b1", vector(g.b1)}, {"b2", vector(g.b2)},
              {"z", matrix_to_json(g.z)}};
}

json to_json(const BasinRoot& root) {
  return json{{"id", root.id},
              {"y", matrix_to_json(root.y)},
              {"residual", finite_or_null(root.residual)},
              {"distance_from_z", finite_or_null(root.distance_from_z)},
              {"hg_angle", finite_or_null(root.hg_angle)}};
}

json to_json(const BasinRow& row, const std::vector<BasinRoot>& roots, const std::vector<Method>& methods) {
  json per_method = json::array();
  for (std::size_t m = 0; m < row.pixels.size(); ++m) {
    json status = json::array(), root = json::array(), iterations = json::array();
    for (const BasinPixel& p : row.pixels[m]) {
      status.push_back(std::string(to_string(p.status)));
      root.push_back(p.root >= 0 ? json(p.root) : json(nullptr));
      iterations.push_back(p.iterations);
    }
    per_method.push_back(json{{"method", std::string(to_string(methods[m]))},
                              {"status", std::move(status)},
                              {"root", std::move(root)},
                              {"iterations", std::move(iterations)}});
  }
  json new_roots = json::array();
  for (int id : row.new_roots) new_roots.push_back(to_json(roots[static_cast<std::size_t>(id)]));
  return json{{"row", row.row}, {"b", finite_or_null(row.b)}, {"methods", std::move(per_method)},
              {"new_roots", std::move(new_roots)}};
}

json basin_summary_json(const BasinResult& map) {
  json roots = json::array();
  for (const BasinRoot& r : map.roots) roots.push_back(to_json(r));
  json methods = json::array();
  for (const BasinMethodSummary& s : map.methods) {
    json statuses = json::object();
    for (std::size_t i = 0; i < std::size(kAllStatuses); ++i)
      if (s.status_counts[i] > 0) statuses[std::string(to_string(kAllStatuses[i]))] = s.status_counts[i];
    methods.push_back(json{{"method", std::string(to_string(s.method))},
                           {"pixels", s.pixels},
                           {"converged", s.converged},
                           {"converged_fraction", finite_or_null(s.converged_fraction)},
                           {"basins", s.basins},
                           {"mean_iterations", optional_number(s.mean_iterations)},
                           {"statuses", std::move(statuses)}});
  }
  json out{{"roots", std::move(roots)}, {"methods", std::move(methods)}, {"complete", map.complete},
           {"seconds", finite_or_null(map.seconds)}};
  if (map.shard) {  // which part this is and which rows of the map it holds
    json rows = json::array();
    for (const BasinRow& row : map.rows) rows.push_back(row.row);
    out["shard"] = json{{"index", map.shard->index}, {"count", map.shard->count}, {"rows", std::move(rows)}};
    if (!map.request_key.empty()) out["shard"]["request"] = json::parse(map.request_key);
  }
  return out;
}

json to_json(const BasinResult& map, const std::vector<Method>& methods) {
  json rows = json::array();
  for (const BasinRow& row : map.rows) {
    json r = to_json(row, map.roots, methods);
    r.erase("new_roots");  // the summary lists every root
    rows.push_back(std::move(r));
  }
  json out{{"grid", to_json(map.grid)}, {"rows", std::move(rows)}};
  out.update(basin_summary_json(map));
  return out;
}

json matrix_to_json(const Eigen::MatrixXd& m) {
  json rows = json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    json row = json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(finite_or_null(m(i, j)));
    rows.push_back(std::move(row));
  }
  return rows;
}

json to_json(const PathPoint& p) {
  return json{{"kind", std::string(to_string(p.kind))},
              {"h", finite_or_null(p.h)},
              {"status", std::string(to_string(p.status))},
              {"iterations", p.iterations},
              {"residual", finite_or_null(p.residual)},
              {"distance", finite_or_null(p.distance)},
              {"angle", finite_or_null(p.angle)},
              {"dh_ds", finite_or_null(p.dh_ds)},
              {"step_length", finite_or_null(p.step_length)}};
}

json to_json(const TraceRecord& t, bool include_iterates) {
  json j{{"iteration", t.iteration},
         {"residual", finite_or_null(t.residual)},
         {"step", finite_or_null(t.step)},
         {"angle", finite_or_null(t.angle)},
         {"distance_to_pi", finite_or_null(t.log_boundary_distance)},
         {"orthogonality_error", finite_or_null(t.orthogonality_error)},
         {"seconds", finite_or_null(t.seconds)},
         {"cpu_seconds", finite_or_null(t.cpu_seconds)}};
  if (t.algebra_residual) j["algebra_residual"] = finite_or_null(*t.algebra_residual);
  if (!t.step_kind.empty()) j["step_kind"] = t.step_kind;
  if (t.step_length) j["step_length"] = finite_or_null(*t.step_length);
  if (t.trust_radius) j["trust_radius"] = finite_or_null(*t.trust_radius);
  if (t.step_from_iterate) j["step_from_iterate"] = *t.step_from_iterate;
  if (t.stage_h) j["stage_h"] = finite_or_null(*t.stage_h);
  if (t.path_point) j["path_point"] = to_json(*t.path_point);
  if (include_iterates) j["y"] = matrix_to_json(t.y);
  return j;
}

json to_json(const SolveResult& r, bool include_iterates) {
  json trace = json::array();
  for (const auto& t : r.trace) trace.push_back(to_json(t, include_iterates));
  json j{{"status", std::string(to_string(r.status))},
         {"reason", r.reason},
         {"iterations", r.iterations},
         {"rate", optional_number(r.rate)},
         {"rate_reliable", r.rate_reliable},
         {"iterate", r.iterate},
         {"residual", finite_or_null(r.residual)},
         {"floor", finite_or_null(r.floor)},
         {"orthogonality_error", finite_or_null(r.orthogonality_error)},
         {"z_adjustment", finite_or_null(r.z_adjustment)},
         {"reorthogonalisations", r.reorthogonalisations},
         {"y", matrix_to_json(r.y)},
         {"trace", std::move(trace)},
         {"seconds", finite_or_null(r.seconds)},
         {"cpu_seconds", finite_or_null(r.cpu_seconds)},
         {"linear_solver", std::string(to_string(r.linear_solver))}};
  if (r.algebra_residual) j["algebra_residual"] = finite_or_null(*r.algebra_residual);
  j["branch"] = std::string(to_string(r.branch));
  j["found_by"] = std::string(to_string(r.found_by));
  j["distance_from_z"] = finite_or_null(r.distance_from_z);
  j["total_iterations"] = r.total_iterations();
  if (r.fold_h) j["fold_h"] = finite_or_null(*r.fold_h);
  if (r.path_h) j["path_h"] = finite_or_null(*r.path_h);
  if (r.multistart_start) j["multistart_start"] = *r.multistart_start;
  if (r.multistart_tries > 0) j["multistart_tries"] = r.multistart_tries;
  if (!r.continuation.empty()) {
    json stages = json::array();
    for (const PathPoint& p : r.continuation) stages.push_back(to_json(p));
    j["continuation"] = json{{"stages", std::move(stages)}, {"total_iterations", r.total_iterations()}};
  }
  return j;
}

json to_json(const SweepCell& c) {
  return json{{"method", std::string(to_string(c.method))},
              {"n", c.n},
              {"h", finite_or_null(c.h)},
              {"status", std::string(to_string(c.status))},
              {"reason", c.reason},
              {"iterations", c.iterations},
              {"rate", optional_number(c.rate)},
              {"residual", finite_or_null(c.residual)}};
}

json to_json(const SweepResult& r) {
  json cells = json::array();
  for (const auto& c : r.cells) cells.push_back(to_json(c));
  json out{{"cells", std::move(cells)}, {"seconds", finite_or_null(r.seconds)}};
  if (r.shard)
    out["shard"] = json{{"index", r.shard->index},
                        {"count", r.shard->count},
                        {"grid_cells", r.grid_cells},
                        {"cell_indices", r.cell_indices}};
  return out;
}

namespace {
// One number (or null) per invariant, named prefix + its API name + suffix (openapi.cpp's invariant_numbers).
json& add_invariants(json& out, const InvariantValues& values, const std::string& prefix, const std::string& suffix) {
  for (Invariant i : kAllInvariants) out[prefix + std::string(to_string(i)) + suffix] = optional_number(values[i]);
  return out;
}
}  // namespace

json to_json(const StepRecord& s) {
  json out{{"step", s.step},
           {"t", finite_or_null(s.t)},
           {"iterations", s.iterations},
           {"residual", finite_or_null(s.residual)},
           {"status", std::string(to_string(s.status))},
           {"substeps", s.substeps},
           {"h", finite_or_null(s.h)},
           {"error_estimate", optional_number(s.error_estimate)},
           {"rejected", s.rejected},
           {"jacobian_evaluations", optional_integer(s.jacobian_evaluations)},
           {"factorizations", optional_integer(s.factorizations)}};
  return add_invariants(out, s.invariants, "", "");
}

json to_json(const IntegrateResult& r) {
  json steps = json::array();
  for (const auto& s : r.steps) steps.push_back(to_json(s));
  json frames = json::array();
  for (const auto& m : r.frames) frames.push_back(matrix_to_json(m));
  json times = json::array();
  for (double t : r.frame_times) times.push_back(finite_or_null(t));
  json out{{"status", std::string(to_string(r.status))},
              {"reason", r.reason},
              {"steps", std::move(steps)},
              {"global_error", optional_number(r.global_error)},
              {"reference_error", optional_number(r.reference_error)},
              {"global_error_at_reference", r.global_error_at_reference},
              {"orthogonality_error", finite_or_null(r.orthogonality_error)},
              {"total_iterations", r.total_iterations},
              {"substeps", r.substeps},
              {"mean_iterations", finite_or_null(r.mean_iterations)},
              {"jacobian_evaluations", optional_integer(r.jacobian_evaluations)},
              {"factorizations", optional_integer(r.factorizations)},
              {"linear_solver", r.linear_solver ? json(std::string(to_string(*r.linear_solver))) : json(nullptr)},
              {"y", matrix_to_json(r.y)},
              {"frames", std::move(frames)},
              {"frame_times", std::move(times)},
              {"frame_steps", r.frame_steps},
              {"cpu_seconds", finite_or_null(r.cpu_seconds)},
              {"reference_seconds", finite_or_null(r.reference_seconds)},
              {"adaptive", r.adaptive},
              {"rejected", r.rejected},
              {"h", finite_or_null(r.h)}};
  json warnings = json::array();
  for (const IntegrateWarning& w : r.warnings) warnings.push_back({{"code", w.code}, {"message", w.message}});
  out["warnings"] = std::move(warnings);
  add_invariants(out, r.initial_invariants, "initial_", "");
  add_invariants(out, r.invariant_scales, "", "_scale");
  return add_invariants(out, r.invariant_drifts, "", "_drift");
}

json to_json(const WorkPrecisionChoice& c) {
  return json{{"integrator", std::string(to_string(c.integrator))},
              {"method", std::string(to_string(c.method))},
              {"differential", std::string(to_string(c.differential))}};
}

json to_json(const WorkPrecisionSeries& s) {
  json points = json::array();
  for (const auto& p : s.points) {
    points.push_back(json{{"h", finite_or_null(p.h)},
                          {"cpu_seconds", finite_or_null(p.cpu_seconds)},
                          {"global_error", finite_or_null(p.error)},
                          {"error", finite_or_null(p.error)},  // the old name of global_error, kept for clients
                          {"status", std::string(to_string(p.status))},
                          {"iterations", p.iterations},
                          {"substeps", p.substeps},
                          {"tolerance", optional_number(p.tolerance)},
                          {"rejected", p.rejected},
                          {"in_fit", p.in_fit}});
    add_invariants(points.back(), p.drifts, "", "_drift");
    if (!p.in_fit) points.back()["excluded"] = p.excluded;
  }
  json fit_h = json::array();
  for (const auto& p : s.points)
    if (p.in_fit) fit_h.push_back(finite_or_null(p.h));
  return json{{"choice", to_json(s.choice)},
              {"points", std::move(points)},
              {"fitted_order", optional_number(s.fitted_order)},
              {"fit_reason", s.fit_reason},
              {"fit_h", std::move(fit_h)}};
}

json to_json(const WorkPrecisionResult& r) {
  json series = json::array();
  for (const auto& s : r.series) series.push_back(to_json(s));
  return json{{"series", std::move(series)},
              {"seconds", finite_or_null(r.seconds)},
              {"reference_error", optional_number(r.reference_error)},
              {"reference_seconds", finite_or_null(r.reference_seconds)}};
}

json error_body(std::string_view code, std::string_view field, std::string_view message) {
  json e{{"code", code}, {"message", message}};
  e["field"] = field.empty() ? json(nullptr) : json(field);
  return json{{"error", std::move(e)}};
}

json error_body(const RequestError& error) {
  json body = error_body(error_code(error), error.field(), error.what());
  if (error.line() > 0) {  // a program's fault: where in it
    body["error"]["line"] = error.line();
    body["error"]["column"] = error.column();
  }
  return body;
}

std::string dump(const json& value) { return value.dump(-1, ' ', false, json::error_handler_t::replace); }

std::string stream_line(std::string_view type, const json& record) {
  const std::string rest = dump(record);
  return "{\"type\":" + dump(json(type)) + (rest.size() > 2 ? "," : "") + rest.substr(1);
}

}  // namespace lienewton::service

// lienewton: the command-line front end. Same JSON documents as the HTTP API, no server caps on N.
#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "core/basins.hpp"
#include "core/fields.hpp"
#include "core/integrate.hpp"
#include "core/solve.hpp"
#include "core/sweep.hpp"
#include "core/work_precision.hpp"
#include "render/renderer.hpp"
#include "server/http_errors.hpp"
#include "server/json_codec.hpp"
#include "server/cli/command_help.hpp"
#include "server/cli/output_file.hpp"
#include "server/cli/paper_figures.hpp"
#include "server/cli/progress_line.hpp"
#include "server/cli/table_output.hpp"
#include "server/render_requests.hpp"
#include "server/request_runner.hpp"
#ifdef LIENEWTON_MPI
#include "server/cli/mpi_farm.hpp"
#endif

namespace {

using namespace lienewton;
using namespace lienewton::service;
using lienewton::cli::Format;
using lienewton::cli::ProgressLine;

constexpr const char* kUsage =
    "usage: lienewton COMMAND [--FIELD VALUE ...] [--pretty] [< request.json]\n"
    "\n"
    "Commands (request JSON on stdin, result on stdout; the documents of the HTTP API, see /openapi.json):\n"
    "  solve            one solve of y = z exp(h g(y)) -> result JSON\n"
    "  sweep            stability map over (method, n, h) -> {\"cells\": [...], \"seconds\"}\n"
    "  basins           basin map: each method from every start y0 = z exp(a B1 + b B2) -> {\"grid\",\"rows\",\"roots\",...}\n"
    "  integrate        time stepping with a Lie group integrator (implicit; rkmk4 explicit) -> result JSON\n"
    "  work-precision   CPU time vs global error per choice -> {\"series\": [...], ...}\n"
    "  render frames    solve (n = 3) or integrate request -> PNG of the rotation frames on stdout\n"
    "  render motion    the same -> the bodies' motion as an animated WebP (--format png|svg: one state)\n"
    "  render heatmap   sweep request, or {\"sweep\": <sweep result>} -> PNG heatmap on stdout\n"
    "  render residuals solve request (methods, differentials lists) -> PNG of ||f(y_n)|| against CPU time\n"
    "  render work-precision  work-precision request -> PNG of CPU time against global error\n"
    "  render invariants integrate request (rigid-body, heavy-top) -> PNG of its invariants' drift over time\n"
    "  merge FILE...    join the outputs of a sweep or basin map run in shards (\"shard\": {\"index\": i, \"count\": k},\n"
    "                   one FILE each, any order) into the unsharded output (\"seconds\": summed over the parts)\n"
    "  render basins    basin request (plus width/height) -> PNG basin map on stdout\n"
    "  figures [DIFF]   the paper's Figures 5.1 and 5.2 as Markdown tables (no stdin): the default sweep of\n"
    "                   paper-linear and paper-sine, differential DIFF (default finite-difference, as the paper)\n"
    "  --help           this text; COMMAND --help (or help COMMAND): the fields COMMAND takes\n"
    "  --version        the version\n"
    "\n"
    "Any request field may be given as a flag instead of (or over) the JSON on stdin, typed by the request\n"
    "contract (/openapi.json): `lienewton solve --n 8 --h 2 --method newton-group --pretty`; a list as 2,3,4;\n"
    "an object or matrix as JSON; - or _ in the name alike. Stdin is not read when it is a terminal; with\n"
    "nothing on it (a terminal, </dev/null) a command runs its defaults and the flags given.\n"
    "Long commands show their progress on stderr when it is a terminal (--quiet: not).\n"
    "--pretty indents the JSON result; --out FILE writes the answer to FILE (whole, or not at all) instead of stdout,\n"
    "which never takes a picture when it is a terminal; FILE keeps its permissions, and a FIFO or symbolic link is\n"
    "refused unless --out-through is given (then written into, or through to the file it names).\n"
    "--stream (solve, sweep, basins, integrate, work-precision) prints the records of the HTTP API's NDJSON stream on\n"
    "stdout as they come, one JSON line each, the result (a basin map's summary) last: {\"type\": ...} as /openapi.json's\n"
    "*StreamRecord. --format csv|table prints the result's rows instead of its JSON: a solve's trace, a sweep's\n"
    "cells, an integration's steps, the work-precision points, a basin map's methods (scalar fields only).\n"
    "\n"
    "Any N the machine can hold is accepted (the server's --max-n cap does not apply here).\n"
    "Built with -DLIENEWTON_MPI=ON, `mpirun -n P lienewton sweep|basins|figures` (or srun) spreads the cells or\n"
    "rows over P processes, one item at a time as they finish; rank 0 reads stdin and prints the same output.\n"
    "Exit status: 0 with the result (also when the solve did not converge: see its status), 2 for an invalid\n"
    "request or usage -- then a JSON error {\"error\":{\"code\",\"field\",\"message\"}} naming the field is\n"
    "printed on stderr (never stdout, which may carry a PNG; a sentence instead when stderr is a terminal; a\n"
    "misspelt flag is told its nearest field) -- and 1 when the work could not be done (renderer unavailable,\n"
    "internal error).\n";

// How this process takes part in a command: alone, or as one rank of an MPI job whose rank 0 reads the request,
// hands out the cells or rows (farm) and prints; the other ranks compute and print nothing.
struct Part {
  const WorkFarm* farm = nullptr;
  bool prints = true;
  std::function<std::string(std::string)> share_input = [](std::string text) { return text; };
};

// An error on stderr: the JSON document for a program reading it, a sentence for a person at a terminal.
void print_error(const json& body) {
  if (!isatty(STDERR_FILENO)) {
    std::cerr << dump(body) << "\n";
    return;
  }
  const json& e = body["error"];
  std::cerr << "lienewton: " << e.value("message", std::string("error"));
  if (e.contains("line") && e["line"].is_number())
    std::cerr << " (line " << e["line"].get<int>() << ", column " << e.value("column", 0) << ")";
  std::cerr << "\n";
}

int fail(int status, std::string_view code, std::string_view field, std::string_view message, bool prints = true) {
  if (prints) print_error(error_body(code, field, message));
  return status;
}

// The answer, on stdout or, with --out FILE, into FILE (cli/output_file.hpp: whole or untouched).
void emit(const std::string& bytes, const std::optional<std::string>& out, bool through) {
  if (!out) {
    std::fwrite(bytes.data(), 1, bytes.size(), stdout);
    std::fflush(stdout);
    return;
  }
  cli::write_output_file(*out, bytes, through);
}

// All of stdin; a read error (stdin a directory, an I/O error) is one, not an empty request.
std::string read_stdin() {
  std::string text;
  char buffer[65536];
  for (;;) {
    const ssize_t n = read(STDIN_FILENO, buffer, sizeof buffer);
    if (n == 0) return text;
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw ApiError(500, "input_failed", "", std::string("cannot read stdin: ") + std::strerror(errno));
    text.append(buffer, static_cast<std::size_t>(n));
  }
}

// The closest of `names` to a misspelt `name` (at most a third of its letters changed), if any.
std::optional<std::string> nearest(const std::string& name, const std::vector<std::string>& names) {
  std::optional<std::string> best;
  std::size_t best_distance = name.size() / 3 + 1;
  for (const std::string& candidate : names) {
    // Levenshtein distance, one row at a time.
    std::vector<std::size_t> row(candidate.size() + 1);
    for (std::size_t j = 0; j <= candidate.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= name.size(); ++i) {
      std::size_t diagonal = row[0];
      row[0] = i;
      for (std::size_t j = 1; j <= candidate.size(); ++j) {
        const std::size_t up = row[j];
        row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (name[i - 1] == candidate[j - 1] ? 0 : 1)});
        diagonal = up;
      }
    }
    if (row.back() < best_distance) best_distance = row.back(), best = candidate;
  }
  return best;
}

// A compute command as the CLI spells it (work-precision, not Python's work_precision).
const CommandSpec* plain_command(const std::string& name) {
  const CommandSpec* c = find_command(name);
  return c && c->name == name ? c : nullptr;
}

// The command's route in the field table, and a render command's picture options (picture_fields()).
fields::Route route_of(const std::string& command, const std::string& sub) {
  if (const CommandSpec* c = plain_command(command)) return c->fields;
  return find_render_route(sub)->base;
}

fields::Route picture_route_of(const std::string& sub) { return find_render_route(sub)->picture; }

// A flag's text as the JSON value its field's row calls for: numbers, integers and true/false as JSON, a string as
// it is, a list comma-separated (or JSON), an object or matrix as JSON. Text that is none of these is sent as a
// string: the codec then names the field and says what it expects.
json flag_value(const fields::Field& f, const std::string& text) {
  const auto one = [&](const std::string& t) -> json {
    if (f.type == fields::Type::string) return t;
    const json v = json::parse(t, nullptr, false);
    return v.is_discarded() ? json(t) : v;
  };
  if (!f.array || (!text.empty() && text.front() == '[')) return one(text);
  json list = json::array();
  std::size_t from = 0;
  for (std::size_t comma; (comma = text.find(',', from)) != std::string::npos; from = comma + 1)
    list.push_back(one(text.substr(from, comma - from)));
  list.push_back(one(text.substr(from)));
  return list;
}

struct Flags {
  json fields = json::object();
  bool pretty = false;
  bool quiet = false;              // --quiet: no progress line
  bool stream = false;             // --stream: NDJSON records on stdout as they come
  Format format = Format::json;    // --format json|csv|table
  std::optional<std::string> out;  // --out FILE
  bool out_through = false;        // --out-through: into a FIFO, or through a symbolic link
};

std::vector<const fields::Field*> command_fields(const std::string& command, const std::string& sub);

// --name value pairs (and --pretty, --out FILE) after the command, each name a field the command's route takes.
Flags read_flags(const std::vector<std::string>& args, const std::string& command, const std::string& sub) {
  Flags out;
  const bool render = command == "render";
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--pretty" || args[i] == "--quiet") {
      (args[i] == "--pretty" ? out.pretty : out.quiet) = true;
      continue;
    }
    if (args[i] == "--out-through") {
      out.out_through = true;
      continue;
    }
    if (args[i] == "--out") {
      if (i + 1 >= args.size()) throw ApiError(400, "usage", "out", "--out needs a file name");
      out.out = args[++i];
      continue;
    }
    if (args[i] == "--stream") {
      if (render) throw ApiError(400, "usage", "stream", "a render command has no stream: it answers one picture");
      out.stream = true;
      continue;
    }
    if (args[i] == "--format" && !render) {
      const std::string value = i + 1 < args.size() ? args[++i] : "";
      if (value != "json" && value != "csv" && value != "table")
        throw ApiError(400, "usage", "format", "--format takes json, csv or table");
      out.format = value == "csv" ? Format::csv : value == "table" ? Format::table : Format::json;
      continue;
    }
    if (args[i].rfind("--", 0) != 0 || args[i].size() < 3)
      throw ApiError(400, "usage", "", "expected --FIELD VALUE or --pretty, got " + args[i] + "; see lienewton --help");
    std::string name = args[i].substr(2);
    for (char& c : name) c = c == '-' ? '_' : c;
    const fields::Field* f = fields::find(route_of(command, sub), name);
    if (!f && render && find_render_route(sub)->integrations_too) f = fields::find(fields::integrate, name);
    if (!f && render) {
      for (const fields::Field& p : picture_fields())
        if (p.name == name && p.takes(picture_route_of(sub))) f = &p;
    }
    if (!f) {
      std::vector<std::string> names{"pretty", "quiet", "out", "out-through", "stream", "format"};
      for (const fields::Field* field : command_fields(command, sub)) names.push_back(field->name);
      const std::optional<std::string> guess = nearest(name, names);
      std::string dashed = guess.value_or("");
      for (char& c : dashed) c = c == '_' ? '-' : c;
      throw ApiError(400, "usage", name, "lienewton " + command + (render ? " " + sub : "") + " takes no field " + name +
                                             (guess ? "; did you mean --" + dashed + "?" : "") + " (see --help)");
    }
    if (i + 1 >= args.size()) throw ApiError(400, "usage", name, "--" + args[i].substr(2) + " needs a value");
    out.fields[name] = flag_value(*f, args[++i]);
  }
  if (out.stream && (out.out || out.format != Format::json))
    throw ApiError(400, "usage", "stream", "--stream writes JSON records to stdout: not with --out or --format");
  return out;
}

// The fields `lienewton command [sub]` takes: its route's rows, and a render's picture options.
std::vector<const fields::Field*> command_fields(const std::string& command, const std::string& sub) {
  std::vector<const fields::Field*> out = fields::fields_of(route_of(command, sub));
  if (command == "render" && find_render_route(sub)->integrations_too)  // a solve's fields, then an integration's own (h, problem: the solve's)
    for (const fields::Field* f : fields::fields_of(fields::integrate))
      if (!fields::find(fields::solve, f->name)) out.push_back(f);
  if (command == "render")
    for (const fields::Field& p : picture_fields())
      if (p.takes(picture_route_of(sub))) out.push_back(&p);
  return out;
}

int run(const std::string& command, const std::string& sub, const Flags& flags, const Part& part) {
  if (command == "render" && !flags.out && part.prints && isatty(STDOUT_FILENO))
    throw ApiError(400, "usage", "", "a picture is not written to a terminal: redirect stdout or give --out FILE");
  std::string text;
  // A terminal on stdin is never waited on; nothing on stdin is the command's defaults (and the flags).
  if (part.prints && !isatty(STDIN_FILENO))
    text = read_stdin();
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) text = "{}";
  json body = parse_body(part.share_input(std::move(text)));
  if (body.is_object()) body.update(flags.fields);
  const Limits limits = Limits::unlimited();
  const bool show = part.prints && !flags.quiet && isatty(STDERR_FILENO);
  if (command == "render") {
    render::Renderer renderer(1);
    RenderHooks hooks;
    // The picture cannot say them: an integration's warnings go to stderr.
    hooks.on_integration = [&](const IntegrateResult& r) {
      if (!part.prints) return;
      for (const IntegrateWarning& w : r.warnings) std::cerr << "lienewton: warning: " << w.code << ": " << w.message << "\n";
    };
    const std::vector<unsigned char> picture = find_render_route(sub)->draw(body, limits, renderer, hooks);
    emit(std::string(picture.begin(), picture.end()), flags.out, flags.out_through);
    return 0;
  }
  std::optional<ProgressLine> line;
  RunHooks hooks;
  hooks.begin = [&](std::string_view unit, std::size_t total) { line.emplace(command, std::string(unit), total, show); };
  hooks.step = [&](std::size_t) {
    if (line) line->step();  // a solve counts no items ahead: no progress line
    return true;
  };
  hooks.farm = part.farm;
  // --stream: each record as the service's NDJSON stream sends it.
  const auto write_record = [&](std::string_view type, const json& record) {
    const std::string text = service::stream_line(type, record) + "\n";
    std::fwrite(text.data(), 1, text.size(), stdout);
    std::fflush(stdout);
    return true;
  };
  if (flags.stream && part.prints) hooks.record = write_record;
  const json out = run_request(plain_command(command)->command, body, limits, hooks);
  if (!part.prints) return 0;
  if (flags.stream) write_record("result", out);
  else if (flags.format != Format::json) emit(cli::format_rows(cli::result_rows(command, out), flags.format), flags.out, flags.out_through);
  else emit((flags.pretty ? out.dump(2, ' ', false, json::error_handler_t::replace) : dump(out)) + "\n", flags.out, flags.out_through);
  return 0;
}

// Joins the outputs of `lienewton sweep` or `lienewton basins` run with a shard each (files) into the unsharded
// output. A basin map is told from a sweep by its "grid".
int merge(const std::vector<std::string>& files) {
  std::vector<json> bodies;
  for (const std::string& file : files) {
    std::ifstream in(file);
    if (!in) return fail(2, "usage", "", "cannot read " + file);
    bodies.push_back(parse_body(std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>())));
  }
  const bool basin_maps = bodies.front().is_object() && bodies.front().contains("grid");
  if (basin_maps) {
    std::vector<BasinResult> parts;
    for (const json& body : bodies) parts.push_back(basin_result_from_json(body));
    const BasinResult merged = merge_shards(parts);
    std::vector<Method> methods;
    for (const BasinMethodSummary& s : merged.methods) methods.push_back(s.method);
    std::cout << dump(to_json(merged, methods)) << "\n";
  } else {
    std::vector<SweepResult> parts;
    for (const json& body : bodies) parts.push_back(sweep_result_from_json(body, Limits::unlimited()));
    std::cout << dump(to_json(merge_shards(parts))) << "\n";
  }
  return 0;
}

// Both problems of section 5 on the paper's default grid, as tables.
int figures(const std::string& differential_name, const Part& part) {
  const auto differential = differential_from_string(differential_name.empty() ? "finite-difference" : differential_name);
  if (!differential)
    return fail(2, "invalid_field", "differential", "unknown differential " + differential_name, part.prints);
  for (ProblemKind problem : {ProblemKind::paper_linear, ProblemKind::paper_sine}) {
    SweepRequest req;
    req.problem.kind = problem;
    req.solver.differential = *differential;
    const SweepResult result = sweep(req, {}, {}, part.farm);
    if (part.prints)
      std::cout << "## " << to_string(problem) << " (" << result.cells.size() << " cells in " << result.seconds
              << " s)\n\n"
              << figure_tables(result, problem, *differential);
  }
  return 0;
}

bool render_command(const std::string& sub) {
  return find_render_route(sub) != nullptr;
}
// --help or -h among the arguments after the command.
bool asks_help(int argc, char** argv) {
  for (int i = 2; i < argc; ++i)
    if (std::string_view(argv[i]) == "--help" || std::string_view(argv[i]) == "-h") return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  // The solvers allocate and free N x N and q x q matrices in every iteration; glibc's defaults hand the heap top
  // back to the system beyond 128 KB and fault it in again (measured: ~3x the system time of an exact sweep,
  // ~8 % of its CPU time). A CLI run is one request: keep the memory.
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  const std::string command = argc > 1 ? argv[1] : "";
  const std::string sub = argc > 2 ? argv[2] : "";
  if (command == "--version" || command == "version") {
    std::cout << "lienewton " << LIENEWTON_VERSION << "\n";
    return 0;
  }
  if ((command == "help" && argc <= 2) || command == "--help" || command == "-h") {
    std::cout << kUsage;
    return 0;
  }
  Part part;
#ifdef LIENEWTON_MPI
  std::optional<cli::MpiSession> mpi;
  std::optional<cli::MpiFarm> farm;
  if (cli::MpiSession::launched_by_mpi()) {
    mpi.emplace(argc, argv);
    farm.emplace(*mpi);
    part = {&*farm, mpi->rank() == 0, [&](std::string text) { return mpi->broadcast(std::move(text)); }};
    // Commands without a map run on rank 0 alone.
    const CommandSpec* spec = plain_command(command);
    if (!(spec && spec->is_map) && command != "figures" && !part.prints) return 0;
  }
#endif
  if (command == "figures" && argc <= 3) return figures(sub, part);
  const bool plain = plain_command(command);
  const bool render = command == "render" && render_command(sub);
  const bool merging = command == "merge" && argc > 2;
  if (command == "help" || ((plain || render) && asks_help(argc, argv))) {
    const bool about = command == "help";
    const std::string what = about ? sub : command, what_sub = about ? (argc > 3 ? argv[3] : "") : sub;
    const bool known = plain_command(what) || (what == "render" && render_command(what_sub));
    if (!known) return fail(2, "usage", "", "no command " + what + "; see lienewton --help", part.prints);
    if (part.prints)
      std::cout << cli::command_help(what + (what == "render" ? " " + what_sub : ""), command_fields(what, what_sub));
    return 0;
  }
  if (!plain && !render && !merging) {
    if (part.prints) std::cerr << kUsage;
    return fail(2, "usage", "", "unknown command " + command + (command == "render" ? " " + sub : "") +
                                    "; see lienewton --help", part.prints);
  }
  // Every rank of an MPI job meets the same request errors; rank 0 reports them.
  const bool prints = part.prints;
  try {
    if (merging) return merge(std::vector<std::string>(argv + 2, argv + argc));
    const Flags flags = read_flags(std::vector<std::string>(argv + (render ? 3 : 2), argv + argc), command, sub);
    return run(command, sub, flags, part);
  } catch (const RequestError& e) {
    if (prints) print_error(error_body(e));  // with a program's line and column
    return 2;
  } catch (const ApiError& e) {
    return fail(e.status() < 500 ? 2 : 1, e.code(), e.field(), e.what(), prints);
  } catch (const render::RenderUnavailable& e) {
    return fail(1, "render_unavailable", "", e.what(), prints);
  } catch (const std::bad_alloc&) {
    return fail(1, "out_of_memory", "", "the request needs more memory than the machine has", prints);
  } catch (const std::exception& e) {
    return fail(1, "internal_error", "", e.what(), prints);
  }
}

// lienewton._lienewton: the C++ side of the Python package. A request document (JSON text) goes through the
// same path as `lienewton COMMAND` (server/request_runner.hpp, the CLI's unlimited Limits) and the result's JSON
// text comes back; lienewton/__init__.py turns keyword arguments into the document and the answer into NumPy
// arrays. The work runs on its own thread with the GIL released, while the calling thread polls Python's
// signal handlers, so Ctrl-C cancels it within about one solver iteration.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <new>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <variant>

#include "core/cancellation.hpp"
#include "core/fields.hpp"
#include "core/integrate.hpp"
#include "python/group_bindings.hpp"
#include "server/json_codec.hpp"
#include "server/request_runner.hpp"

namespace py = pybind11;
using namespace lienewton;
using namespace lienewton::service;

namespace {

// How often the waiting thread looks at Python's signal flags: Ctrl-C answers within this plus one iteration.
constexpr auto kSignalPoll = std::chrono::milliseconds(20);

// (true, result JSON) or (false, the CLI's error document {"error": {"code", "field", "message"[, line, column]}}).
// Raises KeyboardInterrupt (or whatever a signal handler raised) when a signal stopped the work.
py::tuple run(const std::string& command, const std::string& request) {
  const CommandSpec* c = find_command(command);
  if (!c) throw py::value_error("no command " + command);
  CancellationToken token;
  std::string answer;
  bool ok = false;
  std::exception_ptr failure;
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  bool interrupted = false;
  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      CancellationScope scope(&token);
      try {
        answer = dump(run_request(c->command, parse_body(request), Limits::unlimited()));
        ok = true;
      } catch (const RequestError& e) {
        answer = dump(error_body(e));
      } catch (...) {
        failure = std::current_exception();
      }
      std::lock_guard lock(mutex);
      done = true;
      finished.notify_one();
    });
    std::unique_lock lock(mutex);
    while (!finished.wait_for(lock, kSignalPoll, [&] { return done; })) {
      if (interrupted) continue;
      lock.unlock();
      {
        py::gil_scoped_acquire acquire;
        // Leaves the handler's exception set; it is raised once the worker has stopped.
        if (PyErr_CheckSignals() != 0) interrupted = token.cancel(CancelReason::shutdown);
      }
      lock.lock();
    }
    lock.unlock();
    worker.join();
  }
  if (interrupted) throw py::error_already_set();
  if (failure) {
    try {
      std::rethrow_exception(failure);
    } catch (const Cancelled&) {
      throw py::error_already_set();
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& e) {
      throw std::runtime_error(e.what());
    }
  }
  return py::make_tuple(ok, py::bytes(answer));
}

const char* type_name(fields::Type t) {
  switch (t) {
    case fields::Type::number: return "number";
    case fields::Type::integer: return "integer";
    case fields::Type::boolean: return "boolean";
    case fields::Type::string: return "string";
    case fields::Type::object: return "object";
    case fields::Type::matrix: return "matrix";
  }
  return "";
}

py::dict row(const fields::Field& f) {
  py::dict d;
  d["name"] = f.name;
  d["type"] = type_name(f.type);
  d["array"] = f.array;
  d["description"] = f.description;
  d["minimum"] = f.minimum ? py::cast(*f.minimum) : py::none();
  d["maximum"] = f.maximum ? py::cast(*f.maximum) : py::none();
  d["exclusive_minimum"] = f.exclusive_minimum;
  d["values"] = f.values;
  d["default"] = std::visit(
      [](const auto& v) -> py::object {
        if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::monostate>) return py::none();
        else return py::cast(v);
      },
      f.default_value);
  d["min_items"] = f.min_items;
  d["max_items"] = f.max_items;
  d["items"] = f.items;
  py::list properties;
  for (const fields::Field& p : f.properties) properties.append(row(p));
  d["properties"] = properties;
  return d;
}

// The request fields COMMAND takes, in the codec's reading order, each row of core/fields.hpp as a dict.
py::list fields_of(const std::string& command) {
  const CommandSpec* c = find_command(command);
  if (!c) throw py::value_error("no command " + command);
  py::list out;
  for (const fields::Field* f : fields::fields_of(c->fields)) out.append(row(*f));
  return out;
}

}  // namespace

PYBIND11_MODULE(_lienewton, m) {
  m.doc() = "lienewton's C++ core: run(command, request_json) -> (ok, answer_json)";
  m.def("run", &run, py::arg("command"), py::arg("request"),
        "Runs COMMAND (solve, sweep, basins, integrate, work-precision) on a request document (JSON text), as "
        "the CLI does. Returns (True, result JSON) or (False, the error document naming the field).");
  m.def("fields", &fields_of, py::arg("command"),
        "The request fields COMMAND takes (the codec's table): name, type, array, default, minimum, maximum, "
        "exclusive_minimum, values, description, items, properties.");
  m.attr("version") = LIENEWTON_VERSION;
  m.attr("max_frames") = IntegrateRequest::kMaxFrames;
  python::bind_groups(m);
}

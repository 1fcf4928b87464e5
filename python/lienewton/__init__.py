"""lienewton from Python: Newton's method for y = z exp(h g(y)) on Lie groups, the C++ core of the CLI.

Each command takes the fields of its request document (the CLI's and the HTTP API's, see /openapi.json or
`lienewton COMMAND --help`) as keyword arguments, NumPy arrays for matrices, and answers the same document as the
CLI, with NumPy arrays for its matrices and vectors:

    import lienewton
    r = lienewton.solve(n=8, h=2, method="newton-group", differential="exact")
    r.status, r.reason, r.y          # "converged", "converged: ...", an 8 x 8 ndarray

    r = lienewton.integrate(problem="heavy-top")
    r.t, r.y                         # (T,) times and the (T, 7, 7) states, like scipy's solve_ivp
    lienewton.SO3.exp(w).log()       # the core's groups as NumPy objects (lienewton.groups)

A request the CLI refuses raises RequestError naming the field (with a did-you-mean for a misspelt one). Long calls
release the GIL; Ctrl-C stops them (KeyboardInterrupt) within about one solver iteration. help(lienewton.solve)
lists every field of the request, from the table the codec reads them by.
"""
import collections.abc as _abc
import difflib as _difflib
import functools as _functools
import inspect as _inspect
import json as _json
import math as _math
import numbers as _numbers

import numpy as _np

from . import _lienewton
from .groups import SE3, SO, SO3, Product, Rn, SO3xR3

__all__ = ["solve", "sweep", "basins", "integrate", "work_precision", "run", "request_json", "fields", "Result",
           "RequestError", "SO3", "SE3", "SO", "Rn", "Product", "SO3xR3", "__version__"]
__version__ = _lienewton.version


class RequestError(ValueError):
    """A request the CLI would refuse (exit 2): code (invalid_field, unknown_field, unprocessable, ...), field (the
    request field it names), message, and a program's line and column (g) when it has them."""

    def __init__(self, error):
        self.document = error
        self.code = error.get("code")
        self.field = error.get("field")
        self.message = error.get("message", "")
        self.line = error.get("line")
        self.column = error.get("column")
        where = f" (line {self.line}, column {self.column})" if self.line is not None else ""
        super().__init__(f"{self.field or 'request'}: {self.message}{where} [{self.code}]")


class Result(dict):
    """A result document: a dict whose keys are also attributes (r.status, r.cells[0].h). Its repr summarises
    arrays and lists by shape and length; print(dict(r)) shows everything."""

    # The repr shows this many entries, these first, then how many more there are.
    _REPR_ENTRIES = 12
    _REPR_FIRST = ("status", "reason", "t", "y", "iterations", "residual", "global_error")

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name) from None

    def __dir__(self):
        return list(super().__dir__()) + list(self.keys())

    def __repr__(self):
        keys = [k for k in self._REPR_FIRST if k in self] + [k for k in self if k not in self._REPR_FIRST]
        entries = [f"{k}={_summary(self[k])}" for k in keys[:self._REPR_ENTRIES]]
        if len(keys) > self._REPR_ENTRIES:
            entries.append(f"... {len(keys) - self._REPR_ENTRIES} more: {', '.join(keys[self._REPR_ENTRIES:])}")
        return "Result(" + ", ".join(entries) + ")"

    _repr_pretty_ = None  # IPython: use __repr__, not its dict printer


def _summary(value):
    """A value in a line: small arrays and numbers as they are, the rest by shape, length or keys."""
    if isinstance(value, _np.ndarray):
        if value.size <= 4:
            return _np.array2string(value, precision=6, separator=", ")
        return f"<{value.dtype} array {value.shape}>"
    if isinstance(value, list):
        return f"[{len(value)} {type(value[0]).__name__ if value else 'item'}s]"
    if isinstance(value, Result):
        return "{" + ", ".join(list(value)[:4]) + (", ..." if len(value) > 4 else "") + "}"
    if isinstance(value, str) and len(value) > 60:
        return repr(value[:57] + "...")
    return repr(value)


def _plain(value):
    """A request value as JSON can hold it: arrays as nested lists, NumPy scalars as Python numbers."""
    if isinstance(value, _np.ndarray):
        return value.tolist()
    if isinstance(value, _np.generic):
        return value.item()
    if isinstance(value, tuple):
        return list(value)
    raise TypeError(f"{type(value).__name__} is not a request value")


def _body(request, fields):
    """`request` (a dict or JSON text), then the keyword fields over it, as the CLI's flags go over stdin."""
    if request is None:
        body = {}
    elif isinstance(request, (str, bytes)):
        try:
            body = _json.loads(request)
        except ValueError as e:
            raise RequestError({"code": "malformed_json", "field": "",
                                "message": f"the request is not valid JSON ({e})"}) from None
    else:
        body = request
    if not isinstance(body, _abc.Mapping):
        raise RequestError({"code": "invalid_field", "field": "",
                            "message": f"the request must be a JSON object (a dict or its JSON text), got "
                                       f"{type(body).__name__}"})
    body = dict(body)
    body.update(fields)
    return body


def _first_non_finite(value, path):
    """The field (as the codec names it: objects in a list by their place, choices[0].h; numbers by the field, h or
    y0) of the first NaN or infinity in value."""
    if isinstance(value, (_np.ndarray, _np.generic)):
        value = value.tolist()
    if isinstance(value, float) and not _math.isfinite(value):
        return path
    if isinstance(value, (list, tuple)):
        for i, item in enumerate(value):
            found = _first_non_finite(item, f"{path}[{i}]" if isinstance(item, dict) else path)
            if found is not None:
                return found
    if isinstance(value, dict):
        for key, item in value.items():
            found = _first_non_finite(item, f"{path}.{key}" if path else str(key))
            if found is not None:
                return found
    return None


def request_json(request=None, **fields):
    """The request document (JSON text) a command is given: `request` (a dict or JSON text), then the keyword
    fields over it, as the CLI's flags go over stdin. This is the text `lienewton COMMAND` reads the same way."""
    body = _body(request, fields)
    # NaN and infinities are not JSON; the codec would refuse the text anyway, but without naming the field.
    where = _first_non_finite(body, "")
    if where is not None:
        raise RequestError({"code": "invalid_field", "field": where,
                            "message": f"{where} must be finite (NaN and infinities are not JSON numbers)"})
    return _json.dumps(body, default=_plain, allow_nan=False)


def _is_number(x):
    return x is None or (isinstance(x, _numbers.Real) and not isinstance(x, bool))


def _arrays(value):
    """The answer with every list of numbers (null: NaN) as a 1-D array and every rectangular list of such lists as
    a 2-D array; other lists stay lists, objects become Results."""
    if isinstance(value, dict):
        return Result((k, _arrays(v)) for k, v in value.items())
    if not isinstance(value, list) or not value:
        return value
    if all(_is_number(x) for x in value):
        return _vector(value)
    if all(isinstance(row, list) and row and all(_is_number(x) for x in row) for row in value) and \
            len({len(row) for row in value}) == 1:
        return _vector(value)
    return [_arrays(v) for v in value]


def _vector(numbers):
    flat = numbers if not isinstance(numbers[0], list) else [x for row in numbers for x in row]
    if all(isinstance(x, int) for x in flat):
        return _np.array(numbers, dtype=_np.int64)
    return _np.array(numbers, dtype=_np.float64)  # None -> nan


@_functools.lru_cache(maxsize=None)
def fields(command):
    """The request fields COMMAND takes, in the order the codec reads them: a tuple of Results (name, type, array,
    default, minimum, maximum, exclusive_minimum, values, description, items, properties), the rows of the table
    the codec, `lienewton COMMAND --help` and /openapi.json are made from."""
    return tuple(_arrays_free(row) for row in _lienewton.fields(command))


def _arrays_free(row):
    return Result((k, [_arrays_free(p) for p in v] if k == "properties" else v) for k, v in row.items())


def _did_you_mean(command, error):
    """The codec's unknown_field error with the nearest field name the command takes, when one is near."""
    name = error.get("field") or ""
    if error.get("code") != "unknown_field" or "." in name or "[" in name:
        return error
    near = _difflib.get_close_matches(name, [f.name for f in fields(command)], n=1)
    return dict(error, message=f"{error.get('message', '')}; did you mean {near[0]}?") if near else error


def run(command, request=None, **fields):
    """Runs COMMAND (solve, sweep, basins, integrate, work-precision) on the request, as `lienewton COMMAND`."""
    ok, answer = _lienewton.run(command, request_json(request, **fields))
    document = _json.loads(answer)
    if not ok:
        raise RequestError(_did_you_mean(command.replace("_", "-"), document["error"]))
    return _arrays(document)


def solve(request=None, **fields):
    return run("solve", request, **fields)


def sweep(request=None, **fields):
    return run("sweep", request, **fields)


def basins(request=None, **fields):
    return run("basins", request, **fields)


def work_precision(request=None, **fields):
    return run("work-precision", request, **fields)


def integrate(request=None, **fields):
    body = _body(request, fields)
    wanted = body.get("frames")
    exact = wanted is None or (isinstance(wanted, _numbers.Integral) and not isinstance(wanted, bool)
                               and 0 <= wanted <= _lienewton.max_frames)
    if exact:  # else the codec names the field
        body["frames"] = _lienewton.max_frames
    r = run("integrate", body)
    states = _np.array(r.frames, dtype=_np.float64).reshape((-1,) + _np.shape(r.y))
    times = _np.asarray(r.frame_times, dtype=_np.float64).reshape(-1)
    steps = _np.asarray(r.frame_steps, dtype=_np.int64).reshape(-1)
    if exact and wanted is not None:
        picked = _nearest(times, _np.linspace(times[0], times[-1], wanted)) if wanted and len(times) else []
        states, times, steps = states[picked], times[picked], steps[picked]
    r["y_end"] = r.y
    r["t"] = r["frame_times"] = times
    r["y"] = r["frames"] = states
    r["frame_steps"] = steps
    return r


def _nearest(times, targets):
    """The index of the kept time nearest each target (times ascending), each index once, in order."""
    right = _np.clip(_np.searchsorted(times, targets), 1, len(times) - 1) if len(times) > 1 else _np.zeros(
        len(targets), dtype=_np.int64)
    if len(times) > 1:
        left = right - 1
        right = _np.where(targets - times[left] <= times[right] - targets, left, right)
    return _np.unique(right)


_SUMMARIES = {
    "solve": ("One solve of y = z exp(h g(y)) on a Lie group by Newton's method (`lienewton solve`).",
              "Result\n    status, reason, y (the solution, an (n, n) array), residual, iterations, trace (one "
              "Result per iteration), ..."),
    "sweep": ("The stability map over (methods, n, h) (`lienewton sweep`).",
              "Result\n    cells: one Result per (method, n, h) with status, iterations, rate, residual."),
    "basins": ("The basin map from every start y0 = z exp(a B1 + b B2) (`lienewton basins`).",
               "Result\n    the map's rows, roots and counts per method."),
    "integrate": ("Time stepping of y' = A(y) y with a Lie group integrator (`lienewton integrate`).",
                  "Result\n    t : (T,) array\n        the times of the returned states.\n    y : (T, n, n) array\n"
                  "        the states at t (also r.frames; r.frame_steps: their step numbers).\n    y_end : (n, n) "
                  "array\n        the state at the end.\n    status, reason, steps, global_error, the invariants' "
                  "drifts, ...: the CLI's document."),
    "work-precision": ("CPU time against global error per choice of integrator (`lienewton work-precision`).",
                       "Result\n    series: one Result per choice with its points (h or tolerance, error, cpu)."),
}

# What integrate's frames means here (the CLI's frames keeps every (S / frames)-th step and the last).
_FRAMES_TEXT = ("The number of states returned as t and y: the kept states nearest to `frames` times evenly spaced "
                "over the run (numpy.linspace(0, t_end, frames); every step's state is kept for runs up to "
                f"{_lienewton.max_frames} steps, so with fixed h and frames - 1 dividing the steps these are exactly "
                "the steps 0, S/(frames-1), ..., S); fewer when the run has fewer states. Absent: every kept state "
                f"(every step for up to {_lienewton.max_frames} steps, else about {_lienewton.max_frames} to "
                f"{2 * _lienewton.max_frames} evenly thinned ones). 0: none.")

_PYTHON_TYPES = {"number": "float", "integer": "int", "boolean": "bool", "string": "str", "object": "dict",
                 "matrix": "array_like of shape (n, n)"}


def _bound(x):
    return f"{int(x)}" if float(x).is_integer() and abs(x) < 1e15 else f"{x:g}"


def _kind(f, nested=False):
    """A field's type as numpydoc writes it: float, {'a', 'b'}, sequence of int, ... (a matrix inside an object is
    not n x n)."""
    if f["values"]:
        kind = "{" + ", ".join(repr(v) for v in f["values"]) + "}"
    else:
        kind = "matrix" if nested and f.type == "matrix" else _PYTHON_TYPES[f.type]
    return f"sequence of {kind}" if f.array else kind


def _parameter_doc(command, f):
    """One numpydoc parameter entry: `name : type, default: value` and its description, bounds and values."""
    kind = _kind(f)
    default = f", default: {f.default!r}" if f.default is not None else ", optional"
    about = [f.description[:1].upper() + f.description[1:]] if f.description else []
    if command == "integrate" and f.name == "frames":
        about = [_FRAMES_TEXT, f"In [0, {_lienewton.max_frames}]."]
    elif f.minimum is not None or f.maximum is not None:
        lo = _bound(f.minimum) if f.minimum is not None else "-inf"
        hi = _bound(f.maximum) if f.maximum is not None else "inf"
        about.append(f"In {'(' if f.exclusive_minimum else '['}{lo}, {hi}].")
    if f.array and f.max_items:
        about.append(f"{f.min_items} to {f.max_items} {f['items'] or 'items'}.")
    if f.properties:
        about.append("Keys: " + ", ".join(f"{p.name} ({_kind(p, nested=True)}"
                                          f"{', default ' + repr(p.default) if p.default is not None else ''})"
                                          for p in f.properties) + ".")
    text = " ".join(a if a.endswith(".") else a + "." for a in about)
    return f"{f.name} : {kind}{default}\n" + "\n".join("    " + line for line in _wrap(text))


def _wrap(text, width=100):
    lines, line = [], ""
    for word in text.split():
        if line and len(line) + 1 + len(word) > width:
            lines.append(line)
            line = word
        else:
            line = f"{line} {word}" if line else word
    return lines + ([line] if line else [])


def _document(function, command):
    """function's numpydoc docstring and signature from the command's rows of the field table."""
    summary, returns = _SUMMARIES[command]
    rows = fields(command)
    function.__doc__ = "\n".join([
        summary, "",
        "Every request field is a keyword argument; absent ones take their defaults (the codec's). `request`, a "
        "whole request (dict or JSON text), may come first, the keywords going over it.", "",
        "Parameters", "----------",
        "request : dict or str, optional\n    A request document the keyword fields go over.",
        *(_parameter_doc(command, f) for f in rows), "",
        "Returns", "-------", returns, "",
        "Raises", "------",
        "RequestError\n    A request the CLI refuses: .code, .field (the field it names), .message (with a did-you-mean "
        "for a misspelt field), .line and .column for a g program.",
    ])
    parameters = [_inspect.Parameter("request", _inspect.Parameter.POSITIONAL_OR_KEYWORD, default=None)]
    parameters += [_inspect.Parameter(f.name, _inspect.Parameter.KEYWORD_ONLY, default=f.default) for f in rows]
    function.__signature__ = _inspect.Signature(parameters)


for _function, _command in ((solve, "solve"), (sweep, "sweep"), (basins, "basins"), (integrate, "integrate"),
                            (work_precision, "work-precision")):
    _document(_function, _command)

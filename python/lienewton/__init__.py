"""lienewton from Python: Newton's method for y = z exp(h g(y)) on Lie groups, the C++ core of the CLI.

Each command takes the fields of its request document (the CLI's and the HTTP API's, see /openapi.json or
`lienewton COMMAND --help`) as keyword arguments, NumPy arrays for matrices, and answers the same document as the
CLI, with NumPy arrays for its matrices and vectors:

    import lienewton
    r = lienewton.solve(n=8, h=2, method="newton-group", differential="exact")
    r.status, r.reason, r.y          # "converged", "converged: ...", an 8 x 8 ndarray

A request the CLI refuses raises RequestError naming the field. Long calls release the GIL; Ctrl-C stops them
(KeyboardInterrupt) within about one solver iteration.
"""
import json as _json
import numbers as _numbers

import numpy as _np

from . import _lienewton

__all__ = ["solve", "sweep", "basins", "integrate", "work_precision", "run", "request_json", "Result",
           "RequestError", "__version__"]
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
    """A result document: a dict whose keys are also attributes (r.status, r.cells[0].h)."""

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name) from None

    def __dir__(self):
        return list(super().__dir__()) + list(self.keys())


def _plain(value):
    """A request value as JSON can hold it: arrays as nested lists, NumPy scalars as Python numbers."""
    if isinstance(value, _np.ndarray):
        return value.tolist()
    if isinstance(value, _np.generic):
        return value.item()
    if isinstance(value, tuple):
        return list(value)
    raise TypeError(f"{type(value).__name__} is not a request value")


def request_json(request=None, **fields):
    """The request document (JSON text) a command is given: `request` (a dict or JSON text), then the keyword
    fields over it, as the CLI's flags go over stdin. This is the text `lienewton COMMAND` reads the same way."""
    if request is None:
        body = {}
    elif isinstance(request, (str, bytes)):
        body = _json.loads(request)
    else:
        body = dict(request)
    body.update(fields)
    # allow_nan=False: NaN is not JSON; the codec would refuse the text anyway, but without naming the field.
    try:
        return _json.dumps(body, default=_plain, allow_nan=False)
    except ValueError as e:
        raise RequestError({"code": "invalid_field", "field": "", "message": str(e)}) from None


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


def run(command, request=None, **fields):
    """Runs COMMAND (solve, sweep, basins, integrate, work-precision) on the request, as `lienewton COMMAND`."""
    ok, answer = _lienewton.run(command, request_json(request, **fields))
    document = _json.loads(answer)
    if not ok:
        raise RequestError(document["error"])
    return _arrays(document)


def solve(request=None, **fields):
    """One solve of y = z exp(h g(y)): status, reason, y, residual, trace, ... (`lienewton solve`)."""
    return run("solve", request, **fields)


def sweep(request=None, **fields):
    """The stability map over (methods, n, h): cells with status, iterations, rate (`lienewton sweep`)."""
    return run("sweep", request, **fields)


def basins(request=None, **fields):
    """The basin map from every start y0 = z exp(a B1 + b B2) (`lienewton basins`)."""
    return run("basins", request, **fields)


def integrate(request=None, **fields):
    """Time stepping with a Lie group integrator (`lienewton integrate`)."""
    return run("integrate", request, **fields)


def work_precision(request=None, **fields):
    """CPU time against global error per choice of integrator (`lienewton work-precision`)."""
    return run("work-precision", request, **fields)

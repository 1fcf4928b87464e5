#!/usr/bin/env python3
"""The Python package's overhead on a batch: the same sweep request through `lienewton sweep` (a process: read the
JSON, compute, print) and through lienewton.sweep (kwargs to JSON, compute, JSON to NumPy), alternately in the same
run, and the ratio of their median wall times. Cells must agree (timing aside).
    PYTHONPATH=build/python python3 bench/python_sweep.py build/bin/lienewton [--repeat 3] [--figure]
--figure: the paper's Figure 5.1 sweep (paper-linear, finite differences, the default grid) instead of the
10 000-cell batch.
"""
import argparse
import json
import statistics
import subprocess
import sys
import time

import lienewton

# 10 000 cells: the two Newton versions x N = 3..12 x 500 step sizes 2^-4 .. 2^6.
BATCH = {
    "problem": "paper-linear",
    "differential": "exact",
    "methods": ["newton-group", "newton-algebra"],
    "n": list(range(3, 13)),
    "h": [2.0 ** (-4 + 10 * i / 499) for i in range(500)],
    "max_iterations": 100,
}
FIGURE_5_1 = {"problem": "paper-linear", "differential": "finite-difference"}


def timeless_cells(document):
    return [{k: v for k, v in c.items() if k != "seconds"} for c in document["cells"]]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("cli")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--figure", action="store_true")
    args = parser.parse_args()
    request = FIGURE_5_1 if args.figure else BATCH
    text = lienewton.request_json(request)
    cli_times, py_times = [], []
    cli_answer = py_answer = None
    for _ in range(args.repeat):
        start = time.perf_counter()
        proc = subprocess.run([args.cli, "sweep"], input=text, capture_output=True, text=True, check=True)
        cli_times.append(time.perf_counter() - start)
        cli_answer = json.loads(proc.stdout)
        start = time.perf_counter()
        py_answer = lienewton.sweep(request)
        py_times.append(time.perf_counter() - start)
    cells = len(py_answer.cells)
    py_cells = json.loads(json.dumps(timeless_cells(py_answer), default=lambda a: a.tolist()))
    same = py_cells == timeless_cells(cli_answer)
    cli_t, py_t = statistics.median(cli_times), statistics.median(py_times)
    print(f"{'figure 5.1' if args.figure else 'batch'}: {cells} cells, same cells as the CLI: {same}")
    print(f"  lienewton sweep : median {cli_t:.3f} s of {[round(t, 3) for t in cli_times]}")
    print(f"  lienewton.sweep : median {py_t:.3f} s of {[round(t, 3) for t in py_times]}")
    print(f"  Python / CLI    : {py_t / cli_t:.3f}")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""The paper's Figure 5.1 and the heavy-top benchmark from Python (docs/python.md).

Figure 5.1: y = z exp(h g(y)) with the paper-linear field, N = 2..15, h = 2^-10..2^10, the fixed point and both
Newton versions with finite-difference differentials, as `lienewton figures` (docs/experiments.md). Printed per
method: iterations to ||f|| <= 1e-13 for each N (rows) and log2 h (columns), '.' where it did not converge, and
how many cells ended with each other status.
The heavy top: the benchmark's top (docs/requests.md#the-heavy-top) integrated to t = 1 by every default
integrator, CPU time against global error, as `lienewton work-precision --problem heavy-top --group SOxR`.
    python3 docs/figure_5_1.py [--exact] [--no-top]
"""
import argparse
import math
import time
from collections import Counter

import numpy as np

import lienewton


def figure_5_1(differential):
    start = time.perf_counter()
    sweep = lienewton.sweep(problem="paper-linear", differential=differential)
    wall = time.perf_counter() - start
    ns = sorted({c.n for c in sweep.cells})
    hs = sorted({c.h for c in sweep.cells})
    print(f"Figure 5.1: paper-linear, {differential}, {len(sweep.cells)} cells in {wall:.1f} s\n")
    for method in dict.fromkeys(c.method for c in sweep.cells):
        cells = {(c.n, c.h): c for c in sweep.cells if c.method == method}
        statuses = Counter(c.status for c in cells.values())
        converged = statuses.pop("converged", 0)
        others = ", ".join(f"{s} {k}" for s, k in statuses.most_common())
        print(f"{method}: {converged} of {len(cells)} cells converged; not ({'.' if others else ''}): {others or '-'}")
        print("  N \\ log2 h " + "".join(f"{round(math.log2(h)):>4}" for h in hs))
        for n in ns:
            row = (cells[n, h] for h in hs)
            print(f"{n:>12} " + "".join(f"{c.iterations if c.status == 'converged' else '.':>4}" for c in row))
        print()


def heavy_top():
    start = time.perf_counter()
    wp = lienewton.work_precision(problem="heavy-top", group="SOxR")
    print(f"Heavy top: work-precision to t = 1, {time.perf_counter() - start:.1f} s\n")
    for s in wp.series:
        ok = [p for p in s.points if p.status == "converged" and p.error is not None]
        errors = np.array([p.error for p in ok])
        cpu = np.array([p.cpu_seconds for p in ok])
        order = f"{s.fitted_order:.2f}" if s.fitted_order is not None else "-"
        print(f"{s.choice.integrator:<14} order {order:>5}  error {errors.min() if ok else float('nan'):9.2e} .. "
              f"{errors.max() if ok else float('nan'):9.2e}  CPU {cpu.sum() if ok else 0:7.3f} s over {len(ok)} h")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--exact", action="store_true", help="exact differentials instead of finite differences")
    parser.add_argument("--no-top", action="store_true", help="Figure 5.1 only")
    args = parser.parse_args()
    figure_5_1("exact" if args.exact else "finite-difference")
    if not args.no_top:
        heavy_top()


if __name__ == "__main__":
    main()

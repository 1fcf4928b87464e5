"""The Python package against the CLI: the same request gives the same answer (timing fields aside), the same
statuses and reasons, NumPy arrays of the right shapes, the CLI's error documents as RequestError, a released GIL,
and Ctrl-C that stops a long call. Run: LIENEWTON_CLI=build/bin/lienewton PYTHONPATH=build/python python3 -m unittest
"""
import inspect
import json
import os
import signal
import subprocess
import sys
import threading
import time
import unittest

import numpy as np

import lienewton

CLI = os.environ["LIENEWTON_CLI"]
TIMING_FIELDS = {"seconds", "cpu_seconds", "reference_seconds"}


def cli(command, request_text):
    """The CLI's (exit status, answer document or error document) for the request text."""
    proc = subprocess.run([CLI, command], input=request_text, capture_output=True, text=True, check=False)
    return proc.returncode, json.loads(proc.stdout if proc.returncode == 0 else proc.stderr)


def timeless(value):
    if isinstance(value, dict):
        return {k: timeless(v) for k, v in value.items() if k not in TIMING_FIELDS}
    if isinstance(value, list):
        return [timeless(v) for v in value]
    return value


def plain(value):
    """A Python answer back as the JSON document's values, to compare with the CLI's exactly."""
    if isinstance(value, dict):
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, list):
        return [plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return [plain(v) for v in value] if value.ndim > 1 else \
            [None if isinstance(x, float) and np.isnan(x) else x for x in value.tolist()]
    return value


class SameAsCli(unittest.TestCase):
    def same(self, command, **fields):
        text = lienewton.request_json(**fields)
        status, expected = cli(command, text)
        self.assertEqual(status, 0, expected)
        answer = lienewton.run(command, **fields)
        self.assertEqual(timeless(plain(answer)), timeless(expected))
        return answer

    def test_solve_default(self):
        r = self.same("solve")
        self.assertEqual(r.status, "converged")
        self.assertIsInstance(r.y, np.ndarray)
        self.assertEqual(r.y.shape, (3, 3))
        self.assertEqual(r.y.dtype, np.float64)
        self.assertTrue(r.reason.startswith("converged"))
        self.assertIsInstance(r.trace[0], lienewton.Result)

    def test_solve_newton_group_exact_n8(self):
        r = self.same("solve", n=8, h=2, method="newton-group", differential="exact", include_iterates=True)
        self.assertEqual(r.y.shape, (8, 8))
        self.assertEqual(r.trace[-1].y.shape, (8, 8))

    def test_statuses_and_reasons_of_failures(self):
        r = self.same("solve", n=6, h=16, method="fixed-point", max_iterations=3)
        self.assertEqual(r.status, "max_iterations")
        self.assertTrue(r.reason.startswith("no convergence in 3 iterations"), r.reason)

    def test_program_string_g(self):
        r = self.same("solve", g="u = sin(y)*(2*y - 5*y^2); g = u - u'", n=4, h=1, differential="exact")
        self.assertEqual(r.y.shape, (4, 4))

    def test_numpy_matrices_in(self):
        y0 = np.linalg.qr(np.arange(9.0).reshape(3, 3) + np.eye(3))[0]
        from_array = lienewton.solve(y0=y0, h=1)
        from_list = lienewton.solve(y0=y0.tolist(), h=1)
        self.assertEqual(timeless(plain(from_array)), timeless(plain(from_list)))
        self.same("solve", y0=y0, h=1)

    def test_request_then_fields_over_it(self):
        base = {"n": 8, "h": 0.5, "method": "fixed-point"}
        over = lienewton.solve(base, h=2, method="newton-group")
        direct = lienewton.solve(n=8, h=2, method="newton-group")
        self.assertEqual(timeless(plain(over)), timeless(plain(direct)))

    def test_sweep(self):
        r = self.same("sweep", problem="paper-linear", differential="exact", methods=["newton-group", "fixed-point"],
                      n=[3, 4], h=[0.5, 2.0, 8.0], max_iterations=50)
        self.assertEqual(len(r.cells), 12)
        self.assertIn("status", r.cells[0])

    def test_basins(self):
        r = self.same("basins", size=8, methods=["newton-group"], h=4, n=3)
        self.assertTrue(all(isinstance(v, (list, np.ndarray, lienewton.Result, str, int, float, bool, type(None)))
                            for v in r.values()))

    def test_integrate(self):
        r = self.same("integrate", problem="rigid-body", h=0.1, t_end=1)
        self.assertIsInstance(r.global_error, float)

    def test_work_precision(self):
        self.same("work-precision", problem="rigid-body", h=[0.1, 0.05], t_end=0.5)


class Trajectories(unittest.TestCase):
    """lienewton.integrate's t and y: (T,) times and (T, n, n) states as solve_ivp gives, the CLI's states."""

    def cli_states(self, **fields):
        """The CLI's document with a frame at every step (its frames keep every step up to 1000 steps)."""
        status, document = cli("integrate", lienewton.request_json(frames=1000, **fields))
        self.assertEqual(status, 0, document)
        return document

    def test_default_is_the_whole_trajectory(self):
        r = lienewton.integrate(problem="heavy-top")
        steps = len(r.steps)
        self.assertEqual(r.t.shape, (steps + 1,))
        self.assertEqual(r.y.shape, (steps + 1, 7, 7))
        self.assertEqual((r.t[0], r.t[-1]), (0.0, 1.0))
        self.assertTrue(np.array_equal(r.y[-1], r.y_end))
        self.assertTrue(np.array_equal(r.frame_steps, np.arange(steps + 1)))
        expected = self.cli_states(problem="heavy-top")
        self.assertEqual(r.y.tolist(), expected["frames"])
        self.assertEqual(r.y_end.tolist(), expected["y"])

    def test_frames_gives_that_many_evenly_spaced_states(self):
        # 40 fixed steps; frames = 5 are the steps 0, 10, 20, 30, 40.
        fields = dict(problem="rigid-body", h=0.025, t_end=1)
        expected = self.cli_states(**fields)
        r = lienewton.integrate(frames=5, **fields)
        self.assertEqual(r.t.shape, (5,))
        self.assertEqual(r.y.shape, (5, 3, 3))
        self.assertEqual(r.frame_steps.tolist(), [0, 10, 20, 30, 40])
        np.testing.assert_allclose(r.t, np.linspace(0, 1, 5), rtol=0, atol=1e-12)
        self.assertEqual(r.y.tolist(), [expected["frames"][k] for k in (0, 10, 20, 30, 40)])
        self.assertIs(r.frames, r.y)
        for frames in (1, 2, 3, 7, 41):
            self.assertEqual(len(lienewton.integrate(frames=frames, **fields).t), frames)
        self.assertEqual(len(lienewton.integrate(frames=100, **fields).t), 41)  # fewer states than asked
        none = lienewton.integrate(frames=0, **fields)
        self.assertEqual((none.t.shape, none.y.shape, none.y_end.shape), ((0,), (0, 3, 3), (3, 3)))

    def test_adaptive_frames_are_evenly_spread_in_time(self):
        r = lienewton.integrate(problem="rigid-body", rtol=1e-8, t_end=2, frames=5)
        self.assertEqual(len(r.t), 5)
        self.assertEqual((r.t[0], r.t[-1]), (0.0, 2.0))
        self.assertTrue(np.all(np.diff(r.t) > 0))

    def test_bad_frames_is_the_codecs_error(self):
        with self.assertRaises(lienewton.RequestError) as caught:
            lienewton.integrate(frames=-1)
        self.assertEqual(caught.exception.field, "frames")

    def test_repr_is_short(self):
        r = lienewton.integrate(problem="heavy-top")
        self.assertLess(len(repr(r)), 1500)
        self.assertTrue(repr(r).startswith("Result(status='converged'"), repr(r)[:80])


class Documentation(unittest.TestCase):
    def test_help_lists_every_field(self):
        for name, command in (("solve", "solve"), ("sweep", "sweep"), ("basins", "basins"),
                              ("integrate", "integrate"), ("work_precision", "work-precision")):
            function = getattr(lienewton, name)
            rows = lienewton.fields(command)
            self.assertGreater(len(rows), 10)
            signature = inspect.signature(function)
            for f in rows:
                with self.subTest(command=command, field=f.name):
                    self.assertIn(f"\n{f.name} : ", function.__doc__)
                    self.assertEqual(signature.parameters[f.name].default, f["default"])
            self.assertIn("Parameters\n----------", function.__doc__)

    def test_entries_state_type_default_and_bounds(self):
        doc = lienewton.solve.__doc__
        self.assertIn("\nn : int, default: 3\n", doc)
        self.assertIn("In [2, 100000].", doc)
        self.assertIn("method : {'fixed-point', 'newton-group', 'newton-algebra'}, default: 'newton-group'", doc)
        self.assertIn("\nh : float, default: 0.5\n", doc)
        self.assertIn("In (0, 1000000].", doc)
        self.assertIn("\nh : float, optional\n", lienewton.integrate.__doc__)
        self.assertIn("frames : int, optional", lienewton.integrate.__doc__)

class Errors(unittest.TestCase):
    def refused(self, command, **fields):
        status, expected = cli(command, lienewton.request_json(**fields))
        self.assertEqual(status, 2)
        with self.assertRaises(lienewton.RequestError) as caught:
            lienewton.run(command, **fields)
        self.assertEqual(caught.exception.document, expected["error"])
        return caught.exception

    def test_invalid_field(self):
        e = self.refused("solve", n=-1)
        self.assertEqual((e.field, e.code), ("n", "invalid_field"))

    def test_unknown_field_with_did_you_mean(self):
        status, expected = cli("sweep", lienewton.request_json(speed=3))
        self.assertEqual(status, 2)
        with self.assertRaises(lienewton.RequestError) as caught:
            lienewton.sweep(speed=3)
        e = caught.exception
        self.assertEqual((e.field, e.code), ("speed", "unknown_field"))
        self.assertEqual(e.message, expected["error"]["message"] + "; did you mean seed?")

    def test_misspelt_keyword_names_the_field_it_meant(self):
        with self.assertRaises(lienewton.RequestError) as caught:
            lienewton.integrate(problme="heavy-top")
        self.assertTrue(caught.exception.message.endswith("did you mean problem?"), caught.exception.message)

    def test_unknown_field_far_from_every_name_has_no_guess(self):
        e = self.refused("solve", xyzzy=1)
        self.assertNotIn("did you mean", e.message)

    def test_program_error_has_line_and_column(self):
        e = self.refused("solve", g="a = y\nb = a*")
        self.assertEqual((e.field, e.code, e.line), ("g", "unprocessable", 2))
        self.assertIsInstance(e.column, int)

    def test_unclosed_bracket_is_reported_where_it_opens(self):
        e = self.refused("solve", g="a = (y + 1\nb = a * 2\ng = b - b'")
        self.assertEqual((e.field, e.line, e.column), ("g", 1, 5))
        self.assertIn("'(' is never closed", e.message)

    def test_non_finite_numbers_name_their_field(self):
        for fields, field in [(dict(h=float("nan")), "h"), (dict(h=1e400), "h"),
                              (dict(y0=np.diag([1.0, 1.0, -np.inf])), "y0"),
                              (dict(choices=[{"integrator": "implicit-euler"}, {"integrator": "dirk-cg3", "x": np.nan}]),
                               "choices[1].x")]:
            with self.subTest(field=field), self.assertRaises(lienewton.RequestError) as caught:
                lienewton.work_precision(**fields) if "choices" in fields else lienewton.solve(**fields)
            self.assertEqual((caught.exception.field, caught.exception.code), (field, "invalid_field"))

    def test_a_request_that_is_not_an_object_is_a_request_error(self):
        for request, code, said in [(5, "invalid_field", "got int"), ([1, 2], "invalid_field", "got list"),
                                    ("[1, 2]", "invalid_field", "got list"), (b"3", "invalid_field", "got int"),
                                    ("{not json", "malformed_json", "not valid JSON")]:
            with self.subTest(request=request), self.assertRaises(lienewton.RequestError) as caught:
                lienewton.solve(request)
            self.assertEqual((caught.exception.code, caught.exception.field), (code, ""))
            self.assertIn(said, caught.exception.message)
        status, expected = cli("solve", "[1, 2]")  # the CLI's code for the same document
        self.assertEqual((status, expected["error"]["code"]), (2, "invalid_field"))

    def test_no_command(self):
        with self.assertRaises(ValueError):
            lienewton.run("render")


# A sweep that takes minutes: finite differences at N = 24 and 32, large h, up to 10 000 iterations a cell.
LONG_SWEEP = dict(problem="paper-sine", differential="finite-difference", methods=["newton-group"], n=[24, 32],
                  h=[2.0 ** k for k in range(0, 8)], max_iterations=10000, threads=1)


class LongCalls(unittest.TestCase):
    def test_gil_is_released(self):
        started, done = threading.Event(), threading.Event()

        def work():
            started.set()
            lienewton.sweep(**dict(LONG_SWEEP, n=[24], h=[64.0], max_iterations=400))
            done.set()

        worker = threading.Thread(target=work)
        worker.start()
        started.wait()
        ticks = 0
        while not done.is_set() and ticks < 200:
            ticks += 1  # Python code runs while the sweep computes (each sleep lets the worker into C++)
            time.sleep(0.001)
        finished_first = not done.is_set()
        worker.join()
        self.assertTrue(finished_first, "the sweep held the GIL (or took under 0.2 s)")

    def test_ctrl_c_interrupts(self):
        # A child started from a shell's background job inherits SIGINT ignored, and Python then installs no
        # handler: install it, as an interactive Python has it.
        code = ("import signal; signal.signal(signal.SIGINT, signal.default_int_handler)\n"
                "import lienewton\n"
                "print('start', flush=True)\n"
                "try:\n"
                f"    lienewton.sweep(**{LONG_SWEEP!r})\n"
                "    print('finished', flush=True)\n"
                "except KeyboardInterrupt:\n"
                "    print('interrupted, then', lienewton.solve().status, flush=True)\n"
                "    raise\n")
        proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                text=True)
        self.assertEqual(proc.stdout.readline().strip(), "start")
        time.sleep(1.0)  # inside the C++ sweep
        proc.send_signal(signal.SIGINT)
        try:
            # Bounds a hang, not a speed: the sweep itself takes many minutes.
            out, err = proc.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.communicate()
            self.fail("Ctrl-C did not stop the sweep")
        self.assertIn("interrupted, then converged", out)
        self.assertNotIn("finished", out)
        self.assertIn("KeyboardInterrupt", err)
        self.assertNotEqual(proc.returncode, 0)


if __name__ == "__main__":
    unittest.main()

"""lienewton's group objects (lienewton/groups.py on the core's closed forms) against independent truth: Rodrigues'
formula in extended precision, the core's other SO(n) implementation, finite differences of exp for the Jacobians,
and the identities sophus and manif test (exp(log g) = g, g g^-1 = e, exp(Adj_g v) = g exp(v) g^-1,
Jl(v) = Adj_exp(v) Jr(v), dexpinv = dexp^-1), on single elements and on stacks.
Run: PYTHONPATH=build/python python3 -m unittest test_groups
"""
import unittest

import numpy as np

import lienewton
from lienewton import SE3, SO, SO3, SO3xR3, Product, Rn

EPS = np.finfo(np.float64).eps
RNG = np.random.default_rng(54)


def rotation_vectors(m, max_angle):
    """m rotation vectors with angles uniform in (0, max_angle) and directions uniform on the sphere."""
    w = RNG.normal(size=(m, 3))
    return w * (RNG.uniform(0, max_angle, size=(m, 1)) / np.linalg.norm(w, axis=1, keepdims=True))


def rodrigues_long_double(w):
    """exp(hat w) by Rodrigues' formula in x87 extended precision (64-bit mantissa): the reference."""
    w = w.astype(np.longdouble)
    t = np.sqrt(np.sum(w * w, axis=1))[:, None, None]
    k = np.zeros((len(w), 3, 3), dtype=np.longdouble)
    k[:, 0, 1], k[:, 0, 2], k[:, 1, 2] = -w[:, 2], w[:, 1], -w[:, 0]
    k[:, 1, 0], k[:, 2, 0], k[:, 2, 1] = w[:, 2], -w[:, 1], w[:, 0]
    return np.eye(3, dtype=np.longdouble) + np.sin(t) / t * k + (1 - np.cos(t)) / t ** 2 * (k @ k)


class SO3Stacks(unittest.TestCase):
    def test_exp_matches_extended_precision_rodrigues(self):
        w = rotation_vectors(10_000, 3.1)
        error = np.abs(SO3.exp(w).matrix - rodrigues_long_double(w).astype(np.float64))
        self.assertLess(error.max(), 8 * EPS)  # entries <= 1: a few ulp

    def test_log_round_trips_10k_stacked_vectors(self):
        w = rotation_vectors(10_000, np.pi - 1e-3)
        back = SO3.exp(w).log()
        self.assertEqual(back.shape, (10_000, 3))
        relative = np.linalg.norm(back - w, axis=1) / np.linalg.norm(w, axis=1)
        self.assertLess(relative.max(), 8 * EPS)

    def test_stack_is_the_elements_one_by_one(self):
        w = rotation_vectors(50, 3.0)
        stacked = SO3.exp(w)
        for i in (0, 17, 49):
            self.assertTrue(np.array_equal(stacked[i].matrix, SO3.exp(w[i]).matrix))
            self.assertTrue(np.array_equal(stacked.log()[i], SO3.exp(w[i]).log()))

    def test_agrees_with_the_cores_son_on_so3(self):
        # Two implementations in the core: SO(3)'s closed form and SO(n)'s Pade exp, on the paper's coordinates
        # alpha = (-w3, w2, -w1).
        w = rotation_vectors(1000, 3.0)
        alpha = np.stack([-w[:, 2], w[:, 1], -w[:, 0]], axis=1)
        self.assertLess(np.abs(SO3.exp(w).matrix - SO(3).exp(alpha).matrix).max(), 8 * EPS)
        self.assertLess(np.abs(SO(3).exp(alpha).log() - alpha).max(), 16 * EPS)

    def test_small_angles_keep_relative_accuracy(self):
        w = rotation_vectors(100, 1e-9)
        self.assertLess((np.linalg.norm(SO3.exp(w).log() - w, axis=1) / np.linalg.norm(w, axis=1)).max(), 4 * EPS)


def all_groups():
    return [SO3, SE3, SO(4), SO(5), Rn(3), SO3xR3, Product(SE3, SO(3))]


def coordinates(group, m, scale=0.8):
    return RNG.normal(size=(m, group.dim)) * scale / np.sqrt(group.dim)


class Identities(unittest.TestCase):
    def test_exp_log_inverse_and_composition(self):
        for g in all_groups():
            with self.subTest(group=g.name):
                v = coordinates(g, 20)
                x = g.exp(v)
                self.assertLess(np.abs(x.log() - v).max(), 1e-14)
                self.assertLess(np.abs((x * x.inv()).matrix - np.eye(g.size)).max(), 1e-14)
                y = g.exp(coordinates(g, 20))
                self.assertLess(np.abs((x * y).inv().matrix - (y.inv() * x.inv()).matrix).max(), 1e-14)
                # One element composes with every element of a stack.
                self.assertTrue(np.allclose((x[3] * y).matrix, x.matrix[3] @ y.matrix, rtol=0, atol=1e-15))

    def test_adjoint(self):
        for g in all_groups():
            with self.subTest(group=g.name):
                x, u = g.exp(coordinates(g, 10)), coordinates(g, 10, 0.3)
                conjugated = (x * g.exp(u) * x.inv()).matrix
                moved = g.exp(np.einsum("mij,mj->mi", x.Adj(), u)).matrix
                self.assertLess(np.abs(conjugated - moved).max(), 1e-14)
                self.assertLess(np.abs(g.hat(np.einsum("mij,mj->mi", x.Adj(), u))
                                       - x.matrix @ g.hat(u) @ x.inv().matrix).max(), 1e-14)

    def test_jacobians_are_the_derivatives_of_exp(self):
        # exp(v + s d) = exp(v) exp(s Jr d + O(s^2)) = exp(s Jl d + O(s^2)) exp(v): central differences of the
        # logs, whose error is O(s^2) + rounding/s; at s = 1e-5 both are below 1e-8.
        s = 1e-5
        for g in all_groups():
            with self.subTest(group=g.name):
                v, d = coordinates(g, 1)[0], coordinates(g, 1, 1.0)[0]
                ahead, behind = g.exp(v + s * d), g.exp(v - s * d)
                right = ((g.exp(v).inv() * ahead).log() - (g.exp(v).inv() * behind).log()) / (2 * s)
                left = ((ahead * g.exp(v).inv()).log() - (behind * g.exp(v).inv()).log()) / (2 * s)
                self.assertLess(np.abs(right - g.dexp(v) @ d).max(), 1e-8)
                self.assertLess(np.abs(left - g.dexp(v, side="left") @ d).max(), 1e-8)
                self.assertLess(np.abs(g.dexp(v, side="left") - g.exp(v).Adj() @ g.dexp(v)).max(), 1e-14)
                for side in ("right", "left"):
                    self.assertLess(np.abs(g.dexpinv(v, side) @ g.dexp(v, side) - np.eye(g.dim)).max(), 1e-13)

    def test_stacked_jacobians(self):
        v = rotation_vectors(100, 3.0)
        self.assertEqual(SO3.dexp(v).shape, (100, 3, 3))
        self.assertTrue(np.array_equal(SO3.dexpinv(v)[42], SO3.dexpinv(v[42])))


class Shapes(unittest.TestCase):
    def test_state_of_the_heavy_top_is_so3xr3(self):
        r = lienewton.integrate(problem="heavy-top", h=0.01, t_end=0.1, frames=3)
        states = SO3xR3.from_matrix(r.y)
        self.assertEqual(states.log().shape, (3, 6))
        self.assertLess(np.abs(SO3xR3.exp(states.log()).matrix - r.y).max(), 1e-13)
        self.assertTrue(np.array_equal(states.factor(1).log(), r.y[:, 3:6, 6]))  # omega, as so3xr3_state.hpp has it

    def test_bad_shapes_and_domains_are_value_errors(self):
        with self.assertRaises(ValueError):
            SO3.exp(np.zeros((4, 2)))
        with self.assertRaises(ValueError):
            SO3.from_matrix(2 * np.eye(3)).log()  # not a rotation: the core's checked log refuses it
        with self.assertRaises(ValueError):
            SO3.dexp(np.zeros(3), side="middle")
        with self.assertRaises(ValueError):
            SO3.exp(np.zeros((3, 3))) * SO3.exp(np.zeros((4, 3)))

    def test_reprs_are_short(self):
        self.assertLess(len(repr(SO3.exp(np.zeros((10_000, 3))))), 40)
        self.assertTrue(repr(SO3.identity()).startswith("SO3([[1."))


if __name__ == "__main__":
    unittest.main()

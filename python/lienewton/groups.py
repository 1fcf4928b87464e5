"""Lie groups as NumPy objects: SO3, SE3, SO(n), Rn(n) and their products, each an element or a stack of elements.

An element is held as its matrix (a stack: an (m, d, d) array) and built from algebra coordinates by ``exp``; every
operation takes one element or a stack and broadcasts one against many, like scipy's ``Rotation``::

    import numpy as np, lienewton
    g = lienewton.SO3.exp(np.random.default_rng(1).normal(size=(1000, 3)))   # 1000 rotations
    g.log().shape, (g * g.inv()).matrix.shape, g[0].Adj().shape             # (1000, 3) (1000, 3, 3) (3, 3)
    lienewton.SO3.dexp(w)               # the right Jacobian of exp at w (the paper's dexp, (2.10))
    lienewton.SO3.dexp(w, side="left")  # the left one, = dexp(-w)

exp, log, dexp and dexpinv are the C++ core's (core/groups: the closed forms of SO(3) and SE(3), the spectral forms of
SO(n)), so a solver's step and this module's agree to the last bit. Coordinates:

- SO3: the rotation vector w (hat(w) x = w x x).
- SE3: xi = (w, r), hat(xi) = [[hat(w), r], [0, 0]]; the element [[R, p], [0, 1]].
- SO(n): the paper's basis E_ij - E_ji, i < j, row-major, q = n(n-1)/2 coordinates (SO(3)'s are (-w3, w2, -w1)).
- Rn(n): the vector x; the element [[I, x], [0, 1]] (composition adds).
- Product(G1, G2, ...): the factors' coordinates one after another; the element the block-diagonal matrix of the
  factors' (SO3xR3 = Product(SO3, Rn(3)) is the 7 x 7 state of the heavy top and the stiff body).

Jacobians: with J = dexp(v) (right, the paper's left-trivialised dexp) exp(v + d) = exp(v) exp(J d + O(d^2)); with
J = dexp(v, side="left"), exp(v + d) = exp(J d + O(d^2)) exp(v); dexpinv is each one's inverse.
"""
import functools as _functools

import numpy as _np

from . import _lienewton

__all__ = ["SO3", "SE3", "SO", "Rn", "Product", "SO3xR3"]


def _stack(a, tail, what):
    """a as an (m, *tail) float array and whether it was one element (shape tail)."""
    a = _np.asarray(a, dtype=_np.float64)
    if a.shape == tuple(tail):
        return a[None], True
    if a.ndim == len(tail) + 1 and a.shape[1:] == tuple(tail):
        return a, False
    raise ValueError(f"{what} must have shape {tuple(tail)} or (m, {', '.join(map(str, tail))}), not {a.shape}")


def _single(a, single):
    return a[0] if single else a


def _sided(jacobian, v, side):
    if side == "right":
        return jacobian(v)
    if side == "left":
        return jacobian(-v)
    raise ValueError(f"side must be 'right' or 'left', not {side!r}")


class _Group:
    """One element or a stack of elements of a matrix Lie group (see the module's doc)."""

    dim = 0   # algebra coordinates
    size = 0  # matrix size
    name = ""

    def __init__(self, matrix):
        self._m, self._single = _stack(matrix, (self.size, self.size), f"a {self.name} matrix")

    # The group's own arithmetic on stacks: (m, dim) coordinates, (m, size, size) matrices.
    @classmethod
    def _exp(cls, v):
        raise NotImplementedError

    @classmethod
    def _log(cls, m):
        raise NotImplementedError

    @classmethod
    def _inv(cls, m):
        raise NotImplementedError

    @classmethod
    def _adj(cls, m):
        raise NotImplementedError

    @classmethod
    def _dexp(cls, v):
        raise NotImplementedError

    @classmethod
    def _dexpinv(cls, v):
        raise NotImplementedError

    @classmethod
    def _of(cls, m, single):
        g = cls.__new__(cls)
        g._m, g._single = m, single
        return g

    # Construction
    @classmethod
    def exp(cls, v):
        """The element(s) exp(hat(v)) of algebra coordinates v: shape (dim,) or (m, dim)."""
        v, single = _stack(v, (cls.dim,), "algebra coordinates")
        return cls._of(cls._exp(v), single)

    @classmethod
    def from_matrix(cls, matrix):
        """The element(s) of a (size, size) or (m, size, size) matrix (not checked to lie on the group: log checks)."""
        return cls(matrix)

    @classmethod
    def identity(cls, m=None):
        """The identity, or a stack of m identities."""
        eye = _np.eye(cls.size)
        return cls(eye) if m is None else cls(_np.broadcast_to(eye, (m, cls.size, cls.size)).copy())

    @classmethod
    def hat(cls, v):
        """The algebra matrix of coordinates v: (dim,) -> (size, size), (m, dim) -> (m, size, size)."""
        return _np.array(_single(*_map_single(cls._hat, v, (cls.dim,))))

    @classmethod
    def dexp(cls, v, side="right"):
        """The (dim, dim) Jacobian of exp at v (stacked: (m, dim, dim)); side="right" is the paper's dexp (2.10)."""
        v, single = _stack(v, (cls.dim,), "algebra coordinates")
        return _single(_sided(cls._dexp, v, side), single)

    @classmethod
    def dexpinv(cls, v, side="right"):
        """The inverse of dexp(v, side); side="right" is the paper's dexpinv (3.9)."""
        v, single = _stack(v, (cls.dim,), "algebra coordinates")
        return _single(_sided(cls._dexpinv, v, side), single)

    # Operations on elements
    @property
    def matrix(self):
        """The (size, size) matrix, or the (m, size, size) stack."""
        return _single(self._m, self._single)

    @property
    def single(self):
        """Whether this is one element (not a stack)."""
        return self._single

    def log(self):
        """The algebra coordinates of the principal logarithm: (dim,) or (m, dim)."""
        return _single(self._log(self._m), self._single)

    def inv(self):
        return self._of(self._inv(self._m), self._single)

    def Adj(self):
        """The adjoint, the (dim, dim) matrix of v -> vee(g hat(v) g^-1) on coordinates (stacked: (m, dim, dim))."""
        return _single(self._adj(self._m), self._single)

    def __mul__(self, other):
        """Composition g h; one element composes with every element of a stack, stacks element by element."""
        if type(other) is not type(self):
            return NotImplemented
        if not (self._single or other._single or len(self) == len(other)):
            raise ValueError(f"stacks of {len(self)} and {len(other)} elements do not compose")
        return self._of(self._m @ other._m, self._single and other._single)

    def __len__(self):
        if self._single:
            raise TypeError(f"one {self.name} element has no len()")
        return self._m.shape[0]

    def __getitem__(self, index):
        if self._single:
            raise TypeError(f"one {self.name} element is not indexable")
        picked = self._m[index]
        return self._of(picked, False) if picked.ndim == 3 else self._of(picked[None], True)

    def __iter__(self):
        return (self[i] for i in range(len(self)))

    def __repr__(self):
        if self._single:
            body = _np.array2string(self._m[0], precision=4, suppress_small=True, separator=", ").replace("\n", "")
            return f"{self.name}({body})"
        return f"{self.name}(stack of {len(self)})"


def _map_single(f, v, tail):
    v, single = _stack(v, tail, "algebra coordinates")
    return f(v), single


def _skew(w):
    """hat of a stack of 3-vectors: (m, 3) -> (m, 3, 3)."""
    out = _np.zeros(w.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2], out[..., 1, 2] = -w[..., 2], w[..., 1], -w[..., 0]
    out[..., 1, 0], out[..., 2, 0], out[..., 2, 1] = w[..., 2], -w[..., 1], w[..., 0]
    return out


def _transpose(m):
    return _np.swapaxes(m, -1, -2)


class SO3(_Group):
    """Rotations of R^3; coordinates: the rotation vector w (|w| = angle, w / |w| = axis)."""

    dim, size, name = 3, 3, "SO3"

    _hat = staticmethod(_skew)
    _exp = staticmethod(_lienewton.so3_exp)
    _log = staticmethod(_lienewton.so3_log)
    _dexp = staticmethod(_lienewton.so3_dexp)
    _dexpinv = staticmethod(_lienewton.so3_dexpinv)

    @staticmethod
    def _inv(m):
        return _transpose(m).copy()

    @staticmethod
    def _adj(m):
        return m.copy()

    def apply(self, points):
        """R x for points x of shape (3,) or (k, 3) (every element to every point when both are stacks of one
        length: element i to point i)."""
        return _np.einsum("...ij,...j->...i", self.matrix, _np.asarray(points, dtype=_np.float64))


class SE3(_Group):
    """Rigid motions [[R, p], [0, 1]]; coordinates xi = (w, r), the rotation vector first."""

    dim, size, name = 6, 4, "SE3"

    _exp = staticmethod(_lienewton.se3_exp)
    _log = staticmethod(_lienewton.se3_log)
    _dexp = staticmethod(_lienewton.se3_dexp)
    _dexpinv = staticmethod(_lienewton.se3_dexpinv)

    @staticmethod
    def _hat(xi):
        out = _np.zeros(xi.shape[:-1] + (4, 4))
        out[..., :3, :3] = _skew(xi[..., :3])
        out[..., :3, 3] = xi[..., 3:]
        return out

    @staticmethod
    def _inv(m):
        out = _np.zeros_like(m)
        rt = _transpose(m[:, :3, :3])
        out[:, :3, :3] = rt
        out[:, :3, 3] = -_np.einsum("mij,mj->mi", rt, m[:, :3, 3])
        out[:, 3, 3] = 1.0
        return out

    @staticmethod
    def _adj(m):
        # g hat(w, r) g^-1 = hat(R w, R r + p x R w): Adj = [[R, 0], [hat(p) R, R]].
        out = _np.zeros((m.shape[0], 6, 6))
        r = m[:, :3, :3]
        out[:, :3, :3] = r
        out[:, 3:, 3:] = r
        out[:, 3:, :3] = _skew(m[:, :3, 3]) @ r
        return out

    @property
    def rotation(self):
        return SO3._of(self._m[:, :3, :3].copy(), self._single)

    @property
    def translation(self):
        return _single(self._m[:, :3, 3].copy(), self._single)


class _SOn(_Group):
    """SO(n) on the paper's coordinates (basis E_ij - E_ji, i < j, row-major)."""

    @classmethod
    def _hat(cls, a):
        return _lienewton.son_hat(a, cls.size)

    @classmethod
    def _exp(cls, a):
        return _lienewton.son_exp(a, cls.size)

    @classmethod
    def _log(cls, m):
        return _lienewton.son_log(m, cls.size)

    @classmethod
    def _dexp(cls, a):
        return _lienewton.son_dexp(a, cls.size)

    @classmethod
    def _dexpinv(cls, a):
        return _lienewton.son_dexpinv(a, cls.size)

    @staticmethod
    def _inv(m):
        return _transpose(m).copy()

    @classmethod
    def _adj(cls, m):
        # Column k: vee(g b_k g^T) for the basis element b_k.
        basis = _lienewton.son_hat(_np.eye(cls.dim), cls.size)                   # (q, n, n)
        moved = _np.einsum("mij,qjk,mlk->mqil", m, basis, m)                      # (m, q, n, n)
        return _transpose(_lienewton.son_vee(moved.reshape(-1, cls.size, cls.size), cls.size)
                          .reshape(m.shape[0], cls.dim, cls.dim))


@_functools.lru_cache(maxsize=None)
def SO(n):
    """The group SO(n), n >= 2, as a class (SO(4).exp(a) with a of shape (6,) or (m, 6))."""
    if not isinstance(n, int) or n < 2:
        raise ValueError(f"SO(n) needs an integer n >= 2, not {n!r}")
    return type(f"SO{n}", (_SOn,), {"dim": n * (n - 1) // 2, "size": n, "name": f"SO({n})",
                                     "__doc__": f"SO({n}) on the paper's coordinates (E_ij - E_ji, i < j)."})


class _Rn(_Group):
    """R^n under addition, as matrices [[I, x], [0, 1]]."""

    @classmethod
    def _hat(cls, x):
        out = _np.zeros(x.shape[:-1] + (cls.size, cls.size))
        out[..., :-1, -1] = x
        return out

    @classmethod
    def _exp(cls, x):
        out = _np.broadcast_to(_np.eye(cls.size), (x.shape[0], cls.size, cls.size)).copy()
        out[:, :-1, -1] = x
        return out

    @staticmethod
    def _log(m):
        return m[:, :-1, -1].copy()

    @classmethod
    def _inv(cls, m):
        return cls._exp(-m[:, :-1, -1])

    @classmethod
    def _adj(cls, m):
        return _np.broadcast_to(_np.eye(cls.dim), (m.shape[0], cls.dim, cls.dim)).copy()

    @classmethod
    def _dexp(cls, x):
        return _np.broadcast_to(_np.eye(cls.dim), (x.shape[0], cls.dim, cls.dim)).copy()

    _dexpinv = _dexp


@_functools.lru_cache(maxsize=None)
def Rn(n):
    """The translation group R^n, n >= 1, as a class; its element is [[I, x], [0, 1]]."""
    if not isinstance(n, int) or n < 1:
        raise ValueError(f"Rn(n) needs an integer n >= 1, not {n!r}")
    return type(f"R{n}", (_Rn,), {"dim": n, "size": n + 1, "name": f"R{n}",
                                   "__doc__": f"R^{n} under addition, as matrices [[I, x], [0, 1]]."})


def _block_diag(blocks):
    """The block-diagonal stack of stacks: [(m, a, a), (m, b, b)] -> (m, a + b, a + b)."""
    m = blocks[0].shape[0]
    size = sum(b.shape[-1] for b in blocks)
    out = _np.zeros((m, size, size))
    at = 0
    for b in blocks:
        k = b.shape[-1]
        out[:, at:at + k, at:at + k] = b
        at += k
    return out


class _Product(_Group):
    """A direct product: coordinates concatenated, matrices block-diagonal."""

    factors = ()

    @classmethod
    def _split_coordinates(cls, v):
        cuts = _np.cumsum([g.dim for g in cls.factors])[:-1]
        return _np.split(v, cuts, axis=-1)

    @classmethod
    def _blocks(cls, m):
        out, at = [], 0
        for g in cls.factors:
            out.append(m[:, at:at + g.size, at:at + g.size])
            at += g.size
        return out

    @classmethod
    def _each(cls, f, parts):
        return [f(g, p) for g, p in zip(cls.factors, parts)]

    @classmethod
    def _hat(cls, v):
        return _block_diag(cls._each(lambda g, p: g._hat(p), cls._split_coordinates(v)))

    @classmethod
    def _exp(cls, v):
        return _block_diag(cls._each(lambda g, p: g._exp(_np.ascontiguousarray(p)), cls._split_coordinates(v)))

    @classmethod
    def _log(cls, m):
        return _np.concatenate(cls._each(lambda g, b: g._log(_np.ascontiguousarray(b)), cls._blocks(m)), axis=-1)

    @classmethod
    def _inv(cls, m):
        return _block_diag(cls._each(lambda g, b: g._inv(b), cls._blocks(m)))

    @classmethod
    def _adj(cls, m):
        return _block_diag(cls._each(lambda g, b: g._adj(b), cls._blocks(m)))

    @classmethod
    def _dexp(cls, v):
        return _block_diag(cls._each(lambda g, p: g._dexp(_np.ascontiguousarray(p)), cls._split_coordinates(v)))

    @classmethod
    def _dexpinv(cls, v):
        return _block_diag(cls._each(lambda g, p: g._dexpinv(_np.ascontiguousarray(p)), cls._split_coordinates(v)))

    def factor(self, i):
        """The i-th factor's element(s)."""
        g = self.factors[i]
        return g._of(self._blocks(self._m)[i].copy(), self._single)


@_functools.lru_cache(maxsize=None)
def Product(*factors):
    """The direct product of groups (classes such as SO3, SE3, SO(4), Rn(3)) as a class."""
    if not factors or not all(isinstance(g, type) and issubclass(g, _Group) for g in factors):
        raise TypeError("Product takes group classes: SO3, SE3, SO(n), Rn(n) or products")
    name = "x".join(g.name for g in factors)
    return type(name, (_Product,), {"factors": factors, "dim": sum(g.dim for g in factors),
                                    "size": sum(g.size for g in factors), "name": name,
                                    "__doc__": f"The product {name}: coordinates one factor's after another."})


SO3xR3 = Product(SO3, Rn(3))

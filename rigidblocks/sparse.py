"""Sparse matrices in compressed sparse column form, on numpy alone.

A check of a scene needs few sparse operations: the equilibrium matrix and the
problems' constraint matrices built from (value, row, column) triplets, stacked, their
rows and columns scaled, products with vectors, and the arrays handed to Clarabel (its
Python interface reads ``data``, ``indices``, ``indptr``, ``shape`` and
``has_canonical_format`` of whatever it is given: it needs no scipy). Importing
scipy.sparse costs about 0.1 CPU seconds (its array-API layer loads numpy's testing,
f2py, ma, random ... modules), a quarter of a whole ``rigidblocks check`` of a
1,000-block wall; :class:`CscMatrix` keeps it out of that path.

Everything else (slicing, products of matrices, factorisations, the other back ends)
takes scipy's matrices: :meth:`CscMatrix.tocsc` and :meth:`CscMatrix.tocsr` return
them (importing scipy then), as does indexing. Products with vectors add in scipy's
order (column by column, entry by entry), so they give the same numbers to the bit.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np


class CscMatrix:
    """An immutable m x n matrix in canonical CSC form: the row indices of each column
    sorted, no duplicates (explicit zeros are kept, as scipy keeps them).

    ``CscMatrix((data, indices, indptr), shape=(m, n))`` takes arrays already in that
    form (as scipy's ``csc_matrix`` does); :meth:`from_triplets` sums and sorts.
    """

    format = "csc"
    has_canonical_format = True
    has_sorted_indices = True

    def __init__(self, arrays: tuple[Any, Any, Any], shape: tuple[int, int]):
        data, indices, indptr = arrays
        self.data = np.asarray(data, dtype=float)
        self.indices = np.asarray(indices, dtype=np.int64)
        self.indptr = np.asarray(indptr, dtype=np.int64)
        self.shape = (int(shape[0]), int(shape[1]))
        if len(self.indptr) != self.shape[1] + 1 or len(self.indices) != len(self.data):
            raise ValueError(f"inconsistent CSC arrays for shape {self.shape}")
        self._cols: np.ndarray | None = None

    # -- construction --------------------------------------------------------------------
    @classmethod
    def from_triplets(cls, values: Any, rows: Any, cols: Any,
                      shape: tuple[int, int]) -> CscMatrix:
        """The matrix with ``values[k]`` at (``rows[k]``, ``cols[k]``), duplicates added
        (scipy's ``csc_matrix((values, (rows, cols)), shape)``)."""
        m, n = int(shape[0]), int(shape[1])
        v = np.asarray(values, dtype=float).ravel()
        r = np.asarray(rows, dtype=np.int64).ravel()
        c = np.asarray(cols, dtype=np.int64).ravel()
        if not len(r) == len(c) == len(v):
            raise ValueError("triplets of unequal lengths")
        if len(r) and (r.min() < 0 or r.max() >= m or c.min() < 0 or c.max() >= n):
            raise ValueError(f"triplet index outside the shape {(m, n)}")
        key = c * m + r
        if len(key) > 1 and not bool(np.all(key[1:] > key[:-1])):
            order = np.argsort(key, kind="stable")
            key, v = key[order], v[order]
            first = np.ones(len(key), dtype=bool)
            first[1:] = key[1:] != key[:-1]
            if not first.all():
                start = np.flatnonzero(first)
                v = np.add.reduceat(v, start)
                key = key[start]
        c, r = np.divmod(key, m) if m else (key, key)
        indptr = np.zeros(n + 1, dtype=np.int64)
        np.cumsum(np.bincount(c, minlength=n), out=indptr[1:])
        return cls((v, r, indptr), (m, n))

    @classmethod
    def empty(cls, shape: tuple[int, int]) -> CscMatrix:
        """The m x n matrix with no entries."""
        return cls((np.zeros(0), np.zeros(0, np.int64), np.zeros(shape[1] + 1, np.int64)),
                   shape)

    @classmethod
    def diagonal_of(cls, d: Any) -> CscMatrix:
        """The square matrix with ``d`` on its diagonal (its zeros left out, as scipy's
        ``diags(d, format="csc")`` leaves them)."""
        d = np.asarray(d, dtype=float)
        k = np.flatnonzero(d)
        return cls.from_triplets(d[k], k, k, (len(d), len(d)))

    @classmethod
    def from_dense(cls, a: Any) -> CscMatrix:
        """The nonzero entries of a dense 2D array."""
        a = np.atleast_2d(np.asarray(a, dtype=float))
        r, c = np.nonzero(a)
        return cls.from_triplets(a[r, c], r, c, a.shape)

    def with_data(self, data: Any) -> CscMatrix:
        """The same sparsity pattern with other values."""
        out = CscMatrix((data, self.indices, self.indptr), self.shape)
        out._cols = self._cols
        return out

    # -- properties ----------------------------------------------------------------------
    @property
    def nnz(self) -> int:
        return len(self.data)

    @property
    def dtype(self) -> np.dtype:
        return self.data.dtype

    @property
    def col_ids(self) -> np.ndarray:
        """The column of every stored entry."""
        if self._cols is None:
            self._cols = np.repeat(np.arange(self.shape[1], dtype=np.int64),
                                   np.diff(self.indptr))
        return self._cols

    @property
    def T(self) -> _Transposed:
        return _Transposed(self)

    # -- arithmetic ----------------------------------------------------------------------
    def __matmul__(self, x: Any) -> np.ndarray:
        """The product with a vector (n,) or with the columns of a dense (n, k) array."""
        x = _operand(self, x)
        if x.ndim == 2:
            return _by_columns(self, x)
        return np.bincount(self.indices, self.data * x[self.col_ids],
                           minlength=self.shape[0])

    def __abs__(self) -> CscMatrix:
        return self.with_data(np.abs(self.data))

    def __add__(self, other: CscMatrix) -> CscMatrix:
        if not isinstance(other, CscMatrix) or other.shape != self.shape:
            return NotImplemented
        return CscMatrix.from_triplets(np.concatenate([self.data, other.data]),
                                       np.concatenate([self.indices, other.indices]),
                                       np.concatenate([self.col_ids, other.col_ids]),
                                       self.shape)

    def scaled(self, row: Any = None, col: Any = None) -> CscMatrix:
        """diag(row) @ self @ diag(col) (either may be None: no scaling)."""
        data = self.data
        if row is not None:
            data = np.asarray(row, dtype=float)[self.indices] * data
        if col is not None:
            data = data * np.asarray(col, dtype=float)[self.col_ids]
        return self.with_data(data)

    def max(self) -> float:
        """The largest entry (0 where an entry is not stored)."""
        top = float(self.data.max(initial=-np.inf))
        stored_all = self.nnz == self.shape[0] * self.shape[1]
        return top if stored_all else max(top, 0.0)

    def diagonal(self) -> np.ndarray:
        out = np.zeros(min(self.shape))
        on = self.indices == self.col_ids
        out[self.indices[on]] = self.data[on]
        return out

    def triu(self) -> CscMatrix:
        """The upper triangle, diagonal included."""
        keep = self.indices <= self.col_ids
        return CscMatrix.from_triplets(self.data[keep], self.indices[keep],
                                       self.col_ids[keep], self.shape)

    def toarray(self) -> np.ndarray:
        out = np.zeros(self.shape)
        np.add.at(out, (self.indices, self.col_ids), self.data)
        return out

    # -- scipy's, for everything else ----------------------------------------------------
    def tocsc(self) -> Any:
        """scipy's ``csc_matrix`` of the same entries."""
        import scipy.sparse as sp

        return sp.csc_matrix((self.data, self.indices, self.indptr), shape=self.shape)

    def tocsr(self) -> Any:
        """scipy's ``csr_matrix`` of the same entries."""
        return self.tocsc().tocsr()

    def __getitem__(self, key: Any) -> Any:
        return self.tocsc()[key]

    def __repr__(self) -> str:
        return f"<CscMatrix {self.shape[0]}x{self.shape[1]}, {self.nnz} stored entries>"


class _Transposed:
    """The transpose of a :class:`CscMatrix`, for products with vectors."""

    def __init__(self, a: CscMatrix):
        self.a = a
        self.shape = (a.shape[1], a.shape[0])

    def __matmul__(self, y: Any) -> np.ndarray:
        a = self.a
        y = _operand(self, y)
        if y.ndim == 2:
            return _by_columns(self, y)
        return np.bincount(a.col_ids, a.data * y[a.indices], minlength=a.shape[1])

    def tocsr(self) -> Any:
        return self.a.tocsc().T.tocsr()

    def tocsc(self) -> Any:
        return self.a.tocsc().T.tocsc()


def _operand(m: CscMatrix | _Transposed, x: Any) -> np.ndarray:
    """``x`` as an array that ``m @ x`` takes: (n,) or (n, k), n the width of m."""
    x = np.asarray(x)
    if x.ndim not in (1, 2) or x.shape[0] != m.shape[1]:
        raise ValueError(f"dimension mismatch: {m.shape} @ {x.shape}")
    return x


def _by_columns(m: CscMatrix | _Transposed, x: np.ndarray) -> np.ndarray:
    """m @ x for a dense (n, k) x, column by column."""
    if not x.shape[1]:
        return np.zeros((m.shape[0], 0))
    return np.column_stack([m @ x[:, j] for j in range(x.shape[1])])


def as_csc(m: Any) -> CscMatrix:
    """A :class:`CscMatrix` of a matrix given as one, or as any of scipy's."""
    if isinstance(m, CscMatrix):
        return m
    c = m.tocsc()
    if not c.has_canonical_format:
        c = c.copy()
        c.sum_duplicates()
    return CscMatrix((c.data, c.indices, c.indptr), c.shape)


def vstack(blocks: Sequence[CscMatrix]) -> CscMatrix:
    """The blocks one under the other (all of the same width)."""
    n = blocks[0].shape[1]
    if any(b.shape[1] != n for b in blocks):
        raise ValueError("vstack: blocks of unequal widths")
    offsets = np.cumsum([0] + [b.shape[0] for b in blocks])
    rows = [b.indices + o for b, o in zip(blocks, offsets[:-1], strict=True)]
    return CscMatrix.from_triplets(np.concatenate([b.data for b in blocks]),
                                   np.concatenate(rows),
                                   np.concatenate([b.col_ids for b in blocks]),
                                   (int(offsets[-1]), n))


def hstack(blocks: Sequence[CscMatrix]) -> CscMatrix:
    """The blocks side by side (all of the same height)."""
    m = blocks[0].shape[0]
    if any(b.shape[0] != m for b in blocks):
        raise ValueError("hstack: blocks of unequal heights")
    starts = np.cumsum([0] + [b.nnz for b in blocks])
    indptr = np.concatenate([[0]] + [b.indptr[1:] + s
                                     for b, s in zip(blocks, starts[:-1], strict=True)])
    return CscMatrix((np.concatenate([b.data for b in blocks]),
                      np.concatenate([b.indices for b in blocks]), indptr),
                     (m, sum(b.shape[1] for b in blocks)))


__all__ = ["CscMatrix", "as_csc", "hstack", "vstack"]

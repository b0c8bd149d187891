"""rigidblocks.sparse against scipy.sparse, the reference implementation of every
operation it has (test_cli_analyses: a check runs without scipy imported)."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from rigidblocks.sparse import CscMatrix, as_csc, hstack, vstack


def _random(m: int, n: int, k: int, seed: int) -> tuple[np.ndarray, ...]:
    """k triplets in an m x n matrix, unsorted, with duplicates and a zero value."""
    rng = np.random.default_rng(seed)
    rows, cols = rng.integers(0, m, k), rng.integers(0, n, k)
    vals = rng.normal(size=k)
    vals[0] = 0.0
    rows[1], cols[1] = rows[2], cols[2]  # a duplicate
    return vals, rows, cols


@pytest.mark.parametrize("shape,k", [((7, 5), 20), ((1, 9), 6), ((12, 1), 8), ((40, 30), 300)])
def test_triplets_as_scipy_sums_and_sorts_them(shape, k):
    vals, rows, cols = _random(*shape, k, seed=k)
    ours = CscMatrix.from_triplets(vals, rows, cols, shape)
    ref = sp.csc_matrix((vals, (rows, cols)), shape=shape)
    ref.sum_duplicates()
    assert ours.shape == ref.shape
    np.testing.assert_array_equal(ours.indptr, ref.indptr)
    np.testing.assert_array_equal(ours.indices, ref.indices)
    np.testing.assert_allclose(ours.data, ref.data, rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose(ours.toarray(), ref.toarray(), rtol=0, atol=1e-15)
    assert ours.has_canonical_format


def test_products_with_vectors_are_scipys_to_the_bit():
    vals, rows, cols = _random(40, 30, 300, seed=3)
    ours = CscMatrix.from_triplets(vals, rows, cols, (40, 30))
    ref = sp.csc_matrix((ours.data, ours.indices, ours.indptr), shape=(40, 30))
    rng = np.random.default_rng(4)
    x, y = rng.normal(size=30), rng.normal(size=40)
    np.testing.assert_array_equal(ours @ x, ref @ x)
    np.testing.assert_array_equal(ours.T @ y, ref.T @ y)
    X = rng.normal(size=(30, 3))
    np.testing.assert_allclose(ours @ X, ref @ X, rtol=1e-14, atol=1e-14)
    np.testing.assert_array_equal(abs(ours) @ np.abs(x), abs(ref) @ np.abs(x))
    with pytest.raises(ValueError, match="dimension mismatch"):
        ours @ y


def test_stacking_scaling_and_parts_match_scipy():
    a = CscMatrix.from_triplets(*_random(6, 4, 12, seed=1), (6, 4))
    b = CscMatrix.from_triplets(*_random(3, 4, 7, seed=2), (3, 4))
    c = CscMatrix.from_triplets(*_random(6, 2, 5, seed=5), (6, 2))
    A, B, C = (x.tocsc() for x in (a, b, c))
    np.testing.assert_array_equal(vstack([a, b]).toarray(), sp.vstack([A, B]).toarray())
    np.testing.assert_array_equal(hstack([a, c]).toarray(), sp.hstack([A, C]).toarray())
    row, col = np.arange(1.0, 7.0), np.array([2.0, -1.0, 0.5, 3.0])
    np.testing.assert_allclose(a.scaled(row, col).toarray(),
                               (sp.diags(row) @ A @ sp.diags(col)).toarray(), rtol=1e-15)
    np.testing.assert_array_equal((a + a).toarray(), (A + A).toarray())
    sq = CscMatrix.from_triplets(*_random(5, 5, 15, seed=6), (5, 5))
    np.testing.assert_array_equal(sq.triu().toarray(), sp.triu(sq.tocsc()).toarray())
    np.testing.assert_array_equal(sq.diagonal(), sq.tocsc().diagonal())
    d = np.array([1.0, 0.0, 3.0])
    dm = CscMatrix.diagonal_of(d)
    ref = sp.diags(d, format="csc")
    assert dm.nnz == ref.nnz == 2
    np.testing.assert_array_equal(dm.toarray(), ref.toarray())
    dense = np.array([[0.0, 2.0], [0.0, 0.0], [-1.0, 0.0]])
    np.testing.assert_array_equal(CscMatrix.from_dense(dense).toarray(), dense)
    assert CscMatrix.from_dense(dense).nnz == 2
    assert CscMatrix.from_dense(dense).max() == 2.0
    assert CscMatrix.from_dense(-np.abs(dense)).max() == 0.0  # entries not stored are 0
    assert CscMatrix.empty((3, 2)).nnz == 0
    np.testing.assert_array_equal(CscMatrix.empty((3, 2)) @ np.ones(2), np.zeros(3))


def test_scipys_matrices_convert_both_ways():
    ref = sp.random(9, 7, density=0.3, random_state=7, format="csr")
    ours = as_csc(ref)
    assert isinstance(ours, CscMatrix) and as_csc(ours) is ours
    np.testing.assert_array_equal(ours.toarray(), ref.toarray())
    np.testing.assert_array_equal(ours.tocsr().toarray(), ref.toarray())
    np.testing.assert_array_equal(ours[2:5].toarray(), ref[2:5].toarray())  # scipy's
    with pytest.raises(ValueError, match="outside the shape"):
        CscMatrix.from_triplets([1.0], [9], [0], (9, 7))

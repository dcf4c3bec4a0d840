"""CG iterations on the implicit-euler step's reduced systems S z = b, dumped from
BM_ImplicitStep/sheet/implicit-euler (dump_reduced_systems.patch), with two preconditioners:

- the geometric cycle of `pcg-multigrid` (integrators/linear/grid_multigrid.hpp) reproduced in
  double precision: bilinear P, Galerkin coarse operators, one forward block Gauss-Seidel sweep
  before the coarse correction and one backward after, the coarsest grid (at most 16 nodes)
  solved densely;
- smoothed aggregation (Vanek, Mandel and Brezina 1996, "Algebraic multigrid by smoothed
  aggregation for second and fourth order elliptic problems", Computing 56): 3 x 3 node
  aggregates on the grid (a remainder joins the last aggregate of its row or column), the six
  rigid-body modes of the flat sheet as near-null space, orthonormalised per aggregate, the
  tentative prolongator smoothed by one damped block Jacobi step (omega = 4 / (3 rho(D^-1 S))),
  the same sweeps, a dense solve below 100 nodes.

CG stops at |b - S z| <= 1e-3 |b| as implicit-euler's does, from zero and from the start the
solver used (the projection onto the last two steps' solutions, dumped with the system).
Usage: aggregation_study.py DUMP... (docs/journal/2026-11-27-smoothed-aggregation.md).
"""
import sys

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

TOLERANCE = 1e-3  # implicit-euler's linear_tolerance


def load(path):
    """S (3x3 block rows, symmetrised against round-off), b, the solver's start, the grid side."""
    with open(path, "rb") as f:
        n, blocks = np.frombuffer(f.read(8), dtype=np.int32)
        row_start = np.frombuffer(f.read(4 * (n + 1)), dtype=np.int32)
        column = np.frombuffer(f.read(4 * blocks), dtype=np.int32)
        values = np.frombuffer(f.read(72 * blocks), dtype=np.float64).reshape(blocks, 3, 3)
        b = np.frombuffer(f.read(24 * n), dtype=np.float64).copy()
        start = np.frombuffer(f.read(24 * n), dtype=np.float64).copy()
    s = sp.bsr_matrix((values, column, row_start), shape=(3 * n, 3 * n)).tocsr()
    return (0.5 * (s + s.T)).tocsr(), b, start, int(round(np.sqrt(n)))


class Cycle:
    """A V-cycle over given prolongators: block Gauss-Seidel forward before, backward after."""

    def __init__(self, a, prolongators, block_sizes):
        self.levels = []
        for p, size in zip(prolongators, block_sizes):
            coo = a.tocoo()
            lower = coo.row // size >= coo.col // size
            upper = coo.row // size <= coo.col // size
            factor = lambda mask: spla.splu(
                sp.csc_matrix((coo.data[mask], (coo.row[mask], coo.col[mask])), shape=a.shape),
                permc_spec="NATURAL", diag_pivot_thresh=0.0)
            self.levels.append((a, factor(lower), factor(upper), p))
            a = (p.T @ a @ p).tocsr()
        self.coarsest = np.linalg.cholesky(a.toarray())
        self.complexity = sum(level[0].nnz for level in self.levels) + a.nnz
        self.complexity /= self.levels[0][0].nnz

    def apply(self, r, k=0):
        if k == len(self.levels):
            return np.linalg.solve(self.coarsest.T, np.linalg.solve(self.coarsest, r))
        a, forward, backward, p = self.levels[k]
        x = forward.solve(r)
        x += p @ self.apply(p.T @ (r - a @ x), k + 1)
        return x + backward.solve(r - a @ x)


def cg_iterations(a, b, precondition, x=None):
    x = np.zeros_like(b) if x is None else x.copy()
    r = b - a @ x
    limit = TOLERANCE * np.linalg.norm(b)
    if np.linalg.norm(r) <= limit:
        return 0
    z = precondition(r)
    d, rz = z.copy(), r @ z
    for iteration in range(1, 1000):
        q = a @ d
        step = rz / (d @ q)
        x += step * d
        r -= step * q
        if np.linalg.norm(r) <= limit:
            return iteration
        z = precondition(r)
        rz, previous = r @ z, rz
        d = z + (rz / previous) * d
    raise RuntimeError("CG did not converge")


def bilinear(n):
    """The geometric cycle's P from an n x n grid to ((n + 1) // 2)^2 nodes, 3 values a node."""
    coarse = (n + 1) // 2

    def parents(r):
        if r % 2 == 0:
            return [(r // 2, 1.0)]
        return [(r // 2, 0.5), (r // 2 + 1, 0.5)] if r + 1 < n else [(r // 2, 1.0)]

    rows, cols, weights = [], [], []
    for i in range(n * n):
        for pr, wr in parents(i // n):
            for pc, wc in parents(i % n):
                for d in range(3):
                    rows.append(3 * i + d)
                    cols.append(3 * (pr * coarse + pc) + d)
                    weights.append(wr * wc)
    return sp.csr_matrix((weights, (rows, cols)), shape=(3 * n * n, 3 * coarse * coarse)), coarse


def geometric_cycle(a, n):
    prolongators = []
    while n * n > 16:
        p, n = bilinear(n)
        prolongators.append(p)
    return Cycle(a, prolongators, [3] * len(prolongators))


def rigid_body_modes(n):
    """Translations and rotations of the flat n x n sheet (side 1, in the x-z plane)."""
    h = 1.0 / (n - 1)
    x = np.array([[c * h, 0.0, r * h] for r in range(n) for c in range(n)])
    modes = np.zeros((3 * n * n, 6))
    for d in range(3):
        modes[d::3, d] = 1.0
    modes[0::3, 3], modes[1::3, 3] = -x[:, 1], x[:, 0]
    modes[1::3, 4], modes[2::3, 4] = -x[:, 2], x[:, 1]
    modes[2::3, 5], modes[0::3, 5] = -x[:, 0], x[:, 2]
    return modes


def block_jacobi_smoothed(a, tentative, size):
    """(I - omega D^-1 A) T, D the block diagonal, omega = 4 / (3 rho(D^-1 A))."""
    n = a.shape[0] // size
    diagonal = np.array([a[i * size:(i + 1) * size, i * size:(i + 1) * size].toarray()
                         for i in range(n)])
    d_inverse_a = (sp.block_diag(list(np.linalg.inv(diagonal)), format="csr") @ a).tocsr()
    v = np.random.default_rng(0).standard_normal(a.shape[0])
    for _ in range(20):  # power iteration for rho
        w = d_inverse_a @ v
        rho = np.linalg.norm(w) / np.linalg.norm(v)
        v = w / np.linalg.norm(w)
    return (tentative - (4.0 / (3.0 * rho)) * (d_inverse_a @ tentative)).tocsr()


def aggregation_cycle(a, n, width=3):
    near_null, size, prolongators, sizes = rigid_body_modes(n), 3, [], []
    modes = near_null.shape[1]
    while a.shape[0] // size > 100:
        coarse = max(1, n // width)
        aggregate = [min(i // n // width, coarse - 1) * coarse + min(i % n // width, coarse - 1)
                     for i in range(n * n)]
        members = [[] for _ in range(coarse * coarse)]
        for node, g in enumerate(aggregate):
            members[g].extend(range(size * node, size * node + size))
        rows, cols, values = [], [], []
        coarse_null = np.zeros((coarse * coarse * modes, modes))
        for g, dofs in enumerate(members):
            q, r = np.linalg.qr(near_null[dofs])
            for k, dof in enumerate(dofs):
                rows.extend([dof] * modes)
                cols.extend(range(modes * g, modes * g + modes))
                values.extend(q[k])
            coarse_null[modes * g:modes * (g + 1)] = r
        tentative = sp.csr_matrix((values, (rows, cols)), shape=(a.shape[0], coarse * coarse * modes))
        p = block_jacobi_smoothed(a, tentative, size)
        prolongators.append(p)
        sizes.append(size)
        a = (p.T @ a @ p).tocsr()
        near_null, size, n = coarse_null, modes, coarse
    return prolongators, sizes


def main(paths):
    rows = {}
    for path in paths:
        a, b, start, n = load(path)
        geometric = geometric_cycle(a, n)
        aggregation = Cycle(a, *aggregation_cycle(a, n))
        counts = [cg_iterations(a, b, cycle.apply, x)
                  for cycle in (geometric, aggregation) for x in (None, start)]
        rows.setdefault(n, []).append(counts)
        print(path, counts, flush=True)
        complexity = (geometric.complexity, aggregation.complexity)
    print("grid | systems | geometric: from zero, from the start | aggregation: from zero, "
          "from the start (mean +- standard deviation)")
    for n, counts in sorted(rows.items()):
        c = np.array(counts, dtype=float)
        cells = [f"{m:.2f} +- {s:.2f}" for m, s in zip(c.mean(axis=0), c.std(axis=0, ddof=1))]
        print(f"{n} x {n} | {len(c)} | " + " | ".join(cells))
    print(f"operator complexity (last grid): geometric {complexity[0]:.2f}, aggregation "
          f"{complexity[1]:.2f}")


if __name__ == "__main__":
    main(sys.argv[1:])

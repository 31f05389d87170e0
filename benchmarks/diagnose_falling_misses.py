"""Where the falling-friction fast path misses: each case of the benchmark's sample that is
off the exact theory by more than a threshold, with the correction table's interpolation
error split by axis. Prints one JSON line per miss; asserts nothing.

    python benchmarks/diagnose_falling_misses.py --region collapse --n 300 --seeds 101-102 \
        --cache 'refs/collapse_{seed}.npz' [--threshold 1.0]

The cache files are those of ``bench_falling_friction_3d.py`` (same ``--n``, ``--seeds``,
``--region``: the same cases). For a miss at table coordinates c = (ln(a0/b0), nu, s, theta,
tau, mu_k/mu_0, kappa number), ``f(c)`` = exact minus model (what the table holds, from
``tablegen.falling_correction.exact_point`` and ``model_points``) is solved at c and, per
axis, at the 4 nodes of the table nearest c along it (2 along the linear nu and mu_k/mu_0),
the other coordinates kept: the axis's error is ``|f(c) - L(c)|``, L the Lagrange interpolant
through those nodes, in % of mu_0 N (a local stand-in for the table's spline along that axis;
``null`` where a node does not converge). ``spline_err`` is the table's own error at c
(equal to the miss when the model is evaluated as the package does). Some 25 exact solves a
miss (a few seconds). Used 2026-11-29 to choose the ln(a0/b0) node 0.25 ln 5 (see
``tablegen/falling_correction.py``).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import warnings
from pathlib import Path

import numpy as np
from scipy.interpolate import BarycentricInterpolator

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "fmu_src"), str(ROOT), str(ROOT / "benchmarks")]

import bench_falling_friction_3d as bench  # noqa: E402
from railcontact import creep_force_3d  # noqa: E402
from railcontact._compiled import falling_correction_batch  # noqa: E402
from railcontact.falling_table import _coordinates_at, load_falling_correction  # noqa: E402
from tablegen.falling_correction import AXES, NODES, exact_point, model_points  # noqa: E402

LINEAR = ("poisson_ratio", "friction_ratio")


def table_residual(c):
    """Exact minus model (T_x, T_y) / (mu_0 N) at table coordinates ``c`` (NaN if the exact
    solver does not converge)."""
    e = exact_point(*c)
    return (e - model_points(*[np.array([v]) for v in c])[:, 0])[:2]


def table_value(corr, c):
    """The correction table's (T_x, T_y) / (mu_0 N) at ``c``."""
    d = np.zeros((1, 3))
    falling_correction_batch()(corr, *(np.array([float(v)]) for v in c), d)
    return d[0, :2]


def axis_nodes(axis, x):
    """The nodes of ``axis`` the local interpolant at ``x`` uses."""
    nodes = NODES[axis].copy()
    if axis == "spin_coordinate":
        nodes = np.sort(math.copysign(1.0, x) * nodes)
    if axis == "creepage_angle":
        nodes = np.concatenate([nodes - 2 * np.pi, nodes, nodes + 2 * np.pi])
    k = 2 if axis in LINEAR else 4
    lo = max(0, min(int(np.searchsorted(nodes, x)) - k // 2, nodes.size - k))
    return nodes[lo:lo + k]


def diagnose(c, corr):
    """The miss at table coordinates ``c``: the table's error and each axis's."""
    true = table_residual(c)
    row = {"c": c, "true": true.tolist(),
           "spline_err": 100.0 * float(np.hypot(*(true - table_value(corr, c))))}
    for ia, axis in enumerate(AXES):
        sel = axis_nodes(axis, c[ia])
        vals = np.array([table_residual(c[:ia] + [float(v)] + c[ia + 1:]) for v in sel])
        est = BarycentricInterpolator(sel, vals, axis=0)(c[ia])   # (the Lagrange cubic)
        row[axis] = (100.0 * float(np.hypot(*(true - est))) if np.all(np.isfinite(est))
                     else None)
        row[axis + "_nodes"] = sel.tolist()
    return row


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=150)
    ap.add_argument("--seeds", default="11-40")
    ap.add_argument("--region", choices=("all", "collapse"), default="all")
    ap.add_argument("--cache", required=True, help="the benchmark's cache, with {seed}")
    ap.add_argument("--threshold", type=float, default=1.0, help="[% of mu_0 N]")
    opts = ap.parse_args(argv)
    warnings.simplefilter("ignore")
    corr = load_falling_correction()
    first, last = (int(v) for v in opts.seeds.split("-"))
    for seed in range(first, last + 1):
        cache = dict(np.load(opts.cache.format(seed=seed)))
        for k, (args, law, tau, m, kn) in enumerate(
                bench.cases(opts.n, np.random.default_rng(seed), "smooth", opts.region)):
            ref = cache[f"c{k}"]
            if np.isnan(ref[0]):
                continue
            f = creep_force_3d(*args[:8], law, method="exact_table")
            err = math.hypot(f.tx - ref[0], f.ty - ref[1]) / (args[3] * args[8]) * 100.0
            if err <= opts.threshold:
                continue
            lg, s, th, tau0, _ = _coordinates_at(*(np.array([v]) for v in args[:8]), args[8])
            c = [float(lg[0]), args[7], float(s[0]), float(th[0]), float(tau0[0]), m, kn]
            print(json.dumps({"seed": seed, "case": k, "err": err, **diagnose(c, corr)}),
                  flush=True)


if __name__ == "__main__":
    main()

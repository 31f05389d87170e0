"""Falling friction in 3-D: cheap corrections on the Coulomb exact table against Kalker's exact
theory with the smooth law (5.16) (``creep_force_3d(..., method="exact",
friction_coefficient=SmoothFriction(...))``). Prints the error by class and the time per
scalar call of each candidate; asserts nothing.

    python benchmarks/bench_falling_friction_3d.py [--n 200] [--seed 11]
    python benchmarks/bench_falling_friction_3d.py --n 150 --seeds 11-40 --candidates package \
        --cache 'refs/smooth_{seed}.npz'

``--seeds A-B``: the samples of seeds A to B (``--n`` cases each) taken together, with the
count of cases within issue 38's 1 % of mu_0 N; ``--cache`` with ``{seed}`` keeps one file of
exact forces per seed (some 10-20 s of exact solves per 150 cases on one core).

Cases: a0/b0 log-uniform in [0.2, 5], nu uniform in [0, 0.5], creepage direction uniform,
|v| / sqrt(1 + tau^2) log-uniform in [0.05, 10] (a tenth pure spin), spin coordinate tau 0 (30 %)
or |tau| log-uniform in [0.1, 10]; the law mu_k / mu_0 uniform in [0.3, 1] and kappa (mu_0 p0 /
G) uniform in [0, 2] (a strongly falling curve: the law's steepness number (3/2) ln 3 K p0
max|mu'| up to about 1, where the discrete exact problem stays unique; steeper laws may not
converge, see railcontact.creep3d).

Candidates (each one call of the Coulomb exact table; the target of issue 38 is 1 % of mu_0 N
at <= 20 us per scalar call):

* ``coulomb``: the table at mu_0 (the law ignored);
* ``mu(rigid)``: the table at mu(s_r), s_r = sqrt(xi^2 + eta^2 + phi^2 (a0^2 + b0^2) / 5) the
  pressure-weighted RMS rigid slip (the law at the slip of full sliding, as Polach 2005 uses
  the creepage);
* ``sliding ratio``: the table at mu_0 times |T_fs(law)| / |T_fs(mu_0)|, T_fs the full-sliding
  force with the rigid slip field (8 x 16 Gauss points over the ellipse), which carries the
  spread of the slip over the patch that large spin makes;
* ``coarse MXxMY`` (e.g. ``"coarse 12x8"``, only on request: milliseconds per call): the
  table at the package's effective coefficient mu_e plus the difference of the exact solver
  (``solve_rolling_3d``) with the law and with mu_e on one coarse grid, whose discretisation
  error largely cancels;
* ``dissipation``: the table at mu_eff = mu(s_eff), s_eff the traction-weighted mean slip of
  the table's own Coulomb solution at mu_eff: the frictional power of steady rolling over V,
  |Tx xi + Ty eta + Mz phi|, divided by mu_eff N (1 - stick area fraction) (the load on the
  slip area, taken as its share of the area); six fixed-point steps, relaxed by 1/2 from the
  second (seven table calls with the spin moment).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "fmu_src")]

from railcontact import creep_force_3d  # noqa: E402
from railcontact.creep3d import REFERENCE_CONTACT, load_exact_table  # noqa: E402
from railcontact.errors import RollingConvergenceError  # noqa: E402
from railcontact.exact_table import creepage_coordinate, exact_table_inverse  # noqa: E402
from railcontact.friction import SmoothFriction  # noqa: E402

KEYS = ("creepage_longitudinal", "creepage_lateral", "spin", "normal_load", "a0", "b0",
        "youngs_modulus", "poisson_ratio", "friction_coefficient")


#: Keywords of every call with the law (``--law polach``: its rolling speed).
LAW_KW = {}
#: Rolling speed of the ``--law polach`` sample. [m/s]
POLACH_SPEED = 30.0


def cases(n, rng, law_kind="smooth", region="all"):
    """The random cases: ``(args, law, tau, m, kn)``. ``law_kind="polach"``: Polach's law
    ``mu_0 ((1 - A) exp(-B w) + A)`` in the slip velocity w at :data:`POLACH_SPEED`, with
    ``A = m`` and ``B V = kn / (mu_0 p0 / G)`` (its slope at zero slip that of the smooth
    law with the same m and kn). ``region="collapse"``: only where the stick zone collapses
    with spin under a strong law, the fast path's hardest region (|tau| uniform in [1, 2.5],
    the creepage coordinate's rho log-uniform in [0.02, 3] sqrt(1 + tau^2), 0 for a fifth,
    mu_k/mu_0 in [0.3, 0.8], the kappa number in [0.5, 2])."""
    from railcontact.friction import PolachFriction  # noqa: PLC0415

    out = []
    collapse = region == "collapse"
    for _ in range(n):
        g = math.exp(rng.uniform(math.log(0.2), math.log(5.0)))
        nu = rng.uniform(0.0, 0.5)
        if collapse:
            tau = rng.uniform(1.0, 2.5) * rng.choice([-1.0, 1.0])
            rho = math.exp(rng.uniform(math.log(0.02), math.log(3.0))) * math.hypot(1.0, tau)
            if rng.random() < 0.2:
                rho = 0.0
        else:
            tau = 0.0 if rng.random() < 0.3 else (
                math.exp(rng.uniform(math.log(0.1), math.log(10.0))) * rng.choice([-1.0, 1.0]))
            rho = math.exp(rng.uniform(math.log(0.05), math.log(10.0))) * math.hypot(1.0, tau)
            if rng.random() < 0.1:
                rho = 0.0
        theta = rng.uniform(-math.pi, math.pi)
        ph = exact_table_inverse(math.log(g), nu, float(creepage_coordinate(rho, tau)), theta,
                                 tau, REFERENCE_CONTACT)
        args = [float(ph[k]) for k in KEYS]
        shear = args[6] / (2.0 * (1.0 + nu))
        p0 = 1.5 * args[3] / (math.pi * args[4] * args[5])
        if collapse:
            m, kn = rng.uniform(0.3, 0.8), rng.uniform(0.5, 2.0)
        else:
            m, kn = rng.uniform(0.3, 1.0), rng.uniform(0.0, 2.0)
        law = SmoothFriction(args[8], m * args[8], kn / (args[8] * p0 / shear))
        if law_kind == "polach":
            law = PolachFriction(args[8], m, law.kappa / POLACH_SPEED)
        out.append((args, law, tau, m, kn))
    return out


# Gauss points over the unit disc (r: Gauss-Legendre on [0, 1], theta: midpoint rule)
_R, _WR = np.polynomial.legendre.leggauss(8)
_R, _WR = 0.5 * (_R + 1.0), 0.5 * _WR
_TH = 2.0 * np.pi * (np.arange(16) + 0.5) / 16
_RR, _TT = np.meshgrid(_R, _TH, indexing="ij")
_W = (_WR[:, None] * (2.0 * np.pi / 16)) * _RR * np.sqrt(1.0 - _RR**2) * 1.5 / np.pi
_CX, _SY = _RR * np.cos(_TT), _RR * np.sin(_TT)


def sliding_ratio(args, law):
    """|T_fs(law)| / |T_fs(mu_0)|: full sliding with the rigid slip field."""
    xi, eta, phi, _, a0, b0 = args[:6]
    wx = xi - phi * b0 * _SY
    wy = eta + phi * a0 * _CX
    wn = np.hypot(wx, wy)
    wn = np.where(wn > 0.0, wn, 1e-300)
    mu = law(wn)
    fl = math.hypot(float(np.sum(mu * _W * wx / wn)), float(np.sum(mu * _W * wy / wn)))
    fc = math.hypot(float(np.sum(_W * wx / wn)), float(np.sum(_W * wy / wn))) * law.mu_static
    return fl / fc if fc > 0.0 else 1.0


def full_sliding(args, law, mu=None):
    """Full-sliding force T_fs / N (tx, ty) with the rigid slip field: the law, or Coulomb mu."""
    xi, eta, phi, _, a0, b0 = args[:6]
    wx = xi - phi * b0 * _SY
    wy = eta + phi * a0 * _CX
    wn = np.hypot(wx, wy)
    wn = np.where(wn > 0.0, wn, 1e-300)
    m = law(wn) if mu is None else mu
    return -float(np.sum(m * _W * wx / wn)), -float(np.sum(m * _W * wy / wn))


def effective_mu(table, args, law, steps=6):
    """The dissipation candidate's mu_eff and the table's values there (tx, ty, mz, stick)."""
    xi, eta, phi, n_load = args[:4]
    mu = law.mu_static
    for it in range(steps):
        v = table.step_values(*args[:8], mu, False) or table.step(*args[:8], mu, False)
        power = abs(v[0] * xi + v[1] * eta + v[2] * phi)
        slip_load = n_load * min(max(1.0 - float(v[3]), 1e-3), 1.0)
        new = float(law(power / (mu * slip_load)))
        mu = new if it == 0 else 0.5 * (mu + new)
    return mu, table.step_values(*args[:8], mu, False) or table.step(*args[:8], mu, False)


def effective_mu_spread(table, args, law, steps=6):
    """As effective_mu, but mu_eff the pressure-weighted mean of mu(lambda |w|) over the
    ellipse, |w| the rigid slip and lambda |w|'s mean scaled to the dissipation's slip."""
    xi, eta, phi, n_load, a0, b0 = args[:6]
    wn = np.hypot(xi - phi * b0 * _SY, eta + phi * a0 * _CX)
    w_mean = float(np.sum(_W * wn))
    mu = law.mu_static
    for it in range(steps):
        v = table.step_values(*args[:8], mu, False) or table.step(*args[:8], mu, False)
        power = abs(v[0] * xi + v[1] * eta + v[2] * phi)
        slip_load = n_load * min(max(1.0 - float(v[3]), 1e-3), 1.0)
        s_mean = power / (mu * slip_load)
        lam = s_mean / w_mean if w_mean > 0.0 else 0.0
        new = float(np.sum(_W * law(lam * wn)))
        mu = new if it == 0 else 0.5 * (mu + new)
    return mu, table.step_values(*args[:8], mu, False) or table.step(*args[:8], mu, False)


def package_mu_effective(table, args, law):
    """The package's effective coefficient mu_e (railcontact.falling_table) of one case."""
    from railcontact.falling_table import falling_friction_table  # noqa: PLC0415

    def values(mu):
        sol = table.creep_solution_3d(*args[:8], float(np.asarray(mu)))
        return sol.tx, sol.ty, sol.spin_moment, sol.stick_area_fraction, 0.0

    return float(falling_friction_table(values, *(np.asarray(v) for v in args[:6]), law,
                                        np.asarray(args[8]))[5])


def candidate(name, table, args, law):
    if name == "package":
        return creep_force_3d(*args[:8], law, method="exact_table", **LAW_KW)
    if name.startswith("coarse"):
        # "coarse MXxMY": the table at the package's mu_e plus the exact solver's difference
        # between the law and mu_e on one coarse grid (milliseconds: not a table's speed)
        from railcontact.reference.rolling3d import solve_rolling_3d  # noqa: PLC0415

        mx, my = (int(v) for v in name.split()[1].split("x"))
        mue = package_mu_effective(table, args, law)
        base = table.creep_force_3d(*args[:8], mue)
        with_law = solve_rolling_3d(*args[:8], law, mx=mx, my=my, tolerance=1e-4)
        with_mue = solve_rolling_3d(*args[:8], mue, mx=mx, my=my, tolerance=1e-4)
        return type(base)(base.tx + with_law.tx - with_mue.tx,
                          base.ty + with_law.ty - with_mue.ty)
    if name.startswith("spread+vec"):
        mu, v = effective_mu_spread(table, args, law)
        xi, eta, phi, n_load, a0, b0 = args[:6]
        wx, wy = xi - phi * b0 * _SY, eta + phi * a0 * _CX
        wn = np.hypot(wx, wy)
        w_mean = float(np.sum(_W * wn))
        power = abs(v[0] * xi + v[1] * eta + v[2] * phi)
        slip_load = n_load * min(max(1.0 - float(v[3]), 1e-3), 1.0)
        lam = power / (mu * slip_load) / w_mean if w_mean > 0.0 else 0.0
        wn = np.where(wn > 0.0, wn, 1e-300)
        dm = law(lam * wn) - mu
        w = 1.0 - float(v[3])
        if name.endswith("2"):
            w = w * w
        cx = -float(np.sum(dm * _W * wx / wn)) * n_load * w
        cy = -float(np.sum(dm * _W * wy / wn)) * n_load * w
        return type(table.creep_force_3d(*args))(v[0] + cx, v[1] + cy)
    if name == "dissip-spread":
        mu, v = effective_mu_spread(table, args, law)
        return type(table.creep_force_3d(*args))(v[0], v[1])
    if name.startswith("dissip+fs"):
        mu, v = effective_mu(table, args, law)
        n_load = args[3]
        w = 1.0 - float(v[3])
        if name.endswith("^2"):
            w = w * w
        lx, ly = full_sliding(args, law)
        cx, cy = full_sliding(args, law, mu)
        return type(table.creep_force_3d(*args))(v[0] + w * n_load * (lx - cx),
                                                  v[1] + w * n_load * (ly - cy))
    if name == "coulomb":
        return table.creep_force_3d(*args)
    if name == "mu(rigid)":
        xi, eta, phi, _, a0, b0 = args[:6]
        s_r = math.sqrt(xi * xi + eta * eta + phi * phi * (a0 * a0 + b0 * b0) / 5.0)
        return table.creep_force_3d(*args[:8], float(law(s_r)))
    if name == "dissipation":
        xi, eta, phi, n_load = args[:4]
        mu = law.mu_static
        for it in range(6):
            sol = table.creep_solution_3d(*args[:8], mu)
            power = abs(sol.tx * xi + sol.ty * eta + sol.spin_moment * phi)
            slip_load = n_load * min(max(1.0 - float(sol.stick_area_fraction), 1e-3), 1.0)
            new = float(law(power / (mu * slip_load)))
            mu = new if it == 0 else 0.5 * (mu + new)
        return table.creep_force_3d(*args[:8], mu)
    ratio = sliding_ratio(args, law)
    f = table.creep_force_3d(*args)
    return type(f)(f.tx * ratio, f.ty * ratio)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=200)
    ap.add_argument("--seed", type=int, default=11)
    ap.add_argument("--seeds", default="", help="A-B: the samples of seeds A to B together")
    ap.add_argument("--cache", default="", help="npz file keeping the exact forces between "
                                                "runs ({seed}: one per seed)")
    ap.add_argument("--candidates", nargs="*", default=None)
    ap.add_argument("--retry-failed", action="store_true", help="solve the cases the cache "
                    "holds as not converged again (after a change of the exact solver)")
    ap.add_argument("--law", choices=("smooth", "polach"), default="smooth",
                    help="the sample's law (polach: only the candidates 'package' and "
                         "'coulomb' take it)")
    ap.add_argument("--region", choices=("all", "collapse"), default="all",
                    help="collapse: only where the stick zone collapses with spin under a "
                         "strong law (|tau| 1-2.5; see cases)")
    opts = ap.parse_args(argv)
    if opts.law == "polach":
        LAW_KW["rolling_speed"] = POLACH_SPEED
    warnings.simplefilter("ignore", RuntimeWarning)
    table = load_exact_table()
    if opts.seeds:
        first, last = (int(v) for v in opts.seeds.split("-"))
        seeds = range(first, last + 1)
    else:
        seeds = [opts.seed]
    ref, kept, failed, n_cases, t0 = [], [], 0, 0, time.perf_counter()
    for seed in seeds:
        data = cases(opts.n, np.random.default_rng(seed), opts.law, opts.region)
        n_cases += len(data)
        path = opts.cache.format(seed=seed) if opts.cache else ""
        cache = dict(np.load(path)) if path and Path(path).is_file() else {}
        for k, (args, law, tau, m, kn) in enumerate(data):
            key = f"c{k}"
            if key in cache and opts.retry_failed and np.isnan(cache[key][0]):
                del cache[key]      # (solved again: the solver may converge on it now)
            if key in cache:
                if np.isnan(cache[key][0]):
                    failed += 1
                    continue
                f = type("F", (), {"tx": cache[key][0], "ty": cache[key][1]})
            else:
                try:
                    f = creep_force_3d(*args[:8], law, method="exact", **LAW_KW)
                except RollingConvergenceError:
                    failed += 1
                    cache[key] = np.array([np.nan, np.nan])
                    continue
                cache[key] = np.array([f.tx, f.ty])
            ref.append((float(f.tx), float(f.ty)))
            kept.append((args, law, tau, m, kn))
        if path:
            np.savez(path, **cache)
    t_exact = (time.perf_counter() - t0) / max(n_cases, 1)
    print(f"{len(kept)} cases solved by method='exact' ({failed} did not converge), "
          f"{t_exact * 1e3:.0f} ms per case")
    tau = np.array([k[2] for k in kept])
    m = np.array([k[3] for k in kept])
    kn = np.array([k[4] for k in kept])
    classes = (("no spin", tau == 0.0), ("|tau| <= 1", (tau != 0.0) & (np.abs(tau) <= 1.0)),
               ("|tau| > 1", np.abs(tau) > 1.0), ("kappa_n > 1", kn > 1.0),
               ("m < 0.5", m < 0.5))
    print("error in % of mu_0 N, max / RMS; time per scalar call (least of 3 passes)")
    for name in opts.candidates or ("coulomb", "mu(rigid)", "sliding ratio", "dissipation",
                                    "dissip+fs", "dissip+fs^2"):
        err = []
        for (args, law, *_), (rx, ry) in zip(kept, ref):
            f = candidate(name, table, args, law)
            err.append(math.hypot(f.tx - rx, f.ty - ry) / (args[3] * args[8]) * 100.0)
        err = np.array(err)
        best = np.inf
        for _ in range(3):
            t0 = time.perf_counter()
            for args, law, *_ in kept:
                candidate(name, table, args, law)
            best = min(best, (time.perf_counter() - t0) / len(kept))
        parts = "; ".join(f"{c} {err[s].max():.2f} / {math.sqrt(np.mean(err[s]**2)):.2f}"
                          for c, s in classes if np.any(s))
        print(f"  {name:14s} all {err.max():6.2f} / {math.sqrt(np.mean(err**2)):5.2f}  "
              f"{best * 1e6:6.1f} us | {parts}; within 1 %: {np.sum(err <= 1.0)} of "
              f"{err.size}")
    best = np.inf
    args = kept[0][0]
    for _ in range(3):
        t0 = time.perf_counter()
        for _ in range(200):
            table.creep_force_3d(*args)
        best = min(best, (time.perf_counter() - t0) / 200)
    print(f"  (the Coulomb table alone: {best * 1e6:.1f} us per scalar call in this run)")
    # the fast path's scalar call on one contact the table keeps a buffer for (the compiled
    # path of the package's laws), interleaved with the Coulomb call: best of 7 rounds
    from railcontact.friction import PolachFriction  # noqa: PLC0415

    one = (2e-3, 1e-3, 0.5, 1e5, 6e-3, 9e-3, 210e9, 0.28)
    smooth, polach = SmoothFriction(0.3, 0.15, 300.0), PolachFriction(0.3, 0.4, 0.6)

    def own_law(s):     # a law of the user's (the smooth law's form): its tabulated path
        return 0.15 / (1.0 + 300.0 * np.asarray(s, dtype=float)) + 0.15

    calls = {"coulomb exact table": lambda: creep_force_3d(*one, 0.3, method="exact_table"),
             "SmoothFriction": lambda: creep_force_3d(*one, smooth, method="exact_table"),
             "PolachFriction": lambda: creep_force_3d(*one, polach, method="exact_table",
                                                      rolling_speed=30.0),
             "a user's function": lambda: creep_force_3d(*one, own_law, method="exact_table")}
    for fun in calls.values():
        for _ in range(1000):        # past the table's ski rental: the contact's buffer
            fun()
    best = dict.fromkeys(calls, np.inf)
    for _ in range(7):
        for name, fun in calls.items():
            t0 = time.perf_counter()
            for _ in range(300):
                fun()
            best[name] = min(best[name], (time.perf_counter() - t0) / 300)
    print("  scalar creep_force_3d(method='exact_table') on one contact, us per call: "
          + ", ".join(f"{k} {v * 1e6:.1f}" for k, v in best.items())
          + " (target <= 20)")
    # a contact whose a0/b0 changes at every call (a vehicle's, in a co-simulation): the
    # table keeps no buffer for it; the falling path takes its compiled kernel on the
    # table's five-dimensional spline. First on the file's coefficients, then on those summed
    # over nu (what the table makes itself after NU_SLAB_AFTER_POINTS points of one nu, and
    # what the FMU makes at initialisation)
    b0s = 9e-3 * (1.0 + 0.05 * np.sin(np.arange(300)))
    moving = {"coulomb exact table": ({"friction_coefficient": 0.3}),
              "SmoothFriction": ({"friction_coefficient": smooth}),
              "PolachFriction": ({"friction_coefficient": polach, "rolling_speed": 30.0})}
    for stage in ("the file's coefficients", "summed over nu"):
        if stage == "summed over nu":
            load_exact_table().prepare(one[7])
        best = dict.fromkeys(moving, np.inf)
        for _ in range(5):
            for name, kw in moving.items():
                t0 = time.perf_counter()
                for b0 in b0s:
                    creep_force_3d(*one[:5], float(b0), *one[6:], method="exact_table", **kw)
                best[name] = min(best[name], (time.perf_counter() - t0) / b0s.size)
        print(f"  the same, a0/b0 changing at every call ({stage}), us per call: "
              + ", ".join(f"{k} {v * 1e6:.1f}" for k, v in best.items()) + " (target <= 20)")

if __name__ == "__main__":
    main()

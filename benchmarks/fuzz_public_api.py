"""Seeded fuzz of the public API at extreme magnitudes: finite answers or a ValueError only.

Usage::

    python benchmarks/fuzz_public_api.py [--calls 20000] [--seed 14]

Each call takes a physically sensible set of inputs and replaces one to three of them by a value
drawn over the whole float range: 0, +-5e-324 (the smallest subnormal), +-2.2e-308 (the smallest
normal), +-1e-300, +-1e300, +-1.8e308 (the largest float), or a sign times 10^U(-324, 308).
Each outcome is counted as

* ``finite``: every output finite, and for the creep forces of a theory with a Coulomb limit
  ``|T| <= mu N`` (4 ulp margin, see tests/test_properties.py);
* ``ValueError``: the documented refusal, its message in the house style ("<parameter> must
  be ..."; one that is not counts as ``other``);
* ``other``: anything else -- a NaN or inf output, another exception, a Coulomb violation.
  The first few are printed. The goal is zero.

Outputs that are documented as possibly infinite are not counted as failures: the normalised
creepage z and the spin coefficient Phi (inf without contact or for pure spin) of
``creep_solution_3d`` and ``normalised_creepage_3d``/``spin_coefficient``.

Covered: railcontact.creep_force_3d (every method, "exact" included), creep_solution_3d,
normalised_creepage_3d, saturation_creepage_3d, spin_coefficient, kalker_coefficients,
hertz_3d, hertz_2d, carter_creep_force, carter_stick_ratio, carter_critical_creepage,
nonsteady.relax_creepage, strip_table.CreepTable (creep_force_3d scalar and array,
creep_solution_3d, creep_force_jacobian_3d), exact_table.ExactCreepTable (creep_force_3d,
creep_solution_3d), and the FMU slave class (WheelRailContact, in process: the creep-only
table, exact-table, analytic and non-steady scenes; the outputs computed when read included)
with extreme inputs and step sizes, where a failed step must raise a ValueError after logging
an error naming the input. The velocity-dependent friction iteration, corrugation, wear and
roughness models are not fuzzed here (their own property tests cover their documented
domains).
"""

from __future__ import annotations

import argparse
import collections
import importlib
import math
import sys
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "fmu_src"))

import railcontact as rc  # noqa: E402
from railcontact import nonsteady  # noqa: E402
from railcontact.creep3d import load_exact_table  # noqa: E402
from railcontact.strip_table import CreepTable  # noqa: E402

EPS = float(np.finfo(float).eps)
SPECIAL = [0.0, 5e-324, 2.2250738585072014e-308, 1e-300, 1e300, 1.7976931348623157e308]

# creep inputs: (name, physical value)
CREEP = [("creepage_longitudinal", 1e-3), ("creepage_lateral", -5e-4), ("spin", 0.1),
         ("normal_load", 8e4), ("a0", 6e-3), ("b0", 5e-3), ("youngs_modulus", 2.1e11),
         ("poisson_ratio", 0.28), ("friction_coefficient", 0.3)]


def extreme(rng):
    """One value over the whole float range (both signs)."""
    sign = -1.0 if rng.random() < 0.5 else 1.0
    if rng.random() < 0.4:
        return sign * SPECIAL[rng.integers(len(SPECIAL))]
    return sign * 10.0 ** rng.uniform(-323.3, 308.25)


def perturbed(rng, base, extra=None):
    """``base`` (list of values) with 1-3 entries replaced by extreme values; sometimes one
    entry is an array of an extreme and the physical value (the array paths)."""
    args = list(base)
    for i in rng.choice(len(args), size=rng.integers(1, min(3, len(args)) + 1), replace=False):
        args[i] = extreme(rng)
    if extra is not None and rng.random() < 0.25:
        i = rng.integers(len(args))
        args[i] = np.array([args[i], base[i]])
    LAST[:] = args
    return args


#: The arguments of the last call (printed with a failure).
LAST = []


def finite(*values):
    return all(np.all(np.isfinite(np.asarray(v, dtype=float))) for v in values)


def coulomb(tx, ty, mu, n):
    mu_n = np.asarray(mu, dtype=float) * np.asarray(n, dtype=float)
    return bool(np.all(np.hypot(tx, ty) <= mu_n * (1.0 + 4.0 * EPS)))


def make_cases(tables):
    ct, et = tables
    base = [v for _, v in CREEP]

    def creep(method):
        def call(rng):
            args = perturbed(rng, base, extra=True)
            tx, ty = rc.creep_force_3d(*args, method=method)
            ok = finite(tx, ty) and (method == "linear" or coulomb(tx, ty, args[8], args[3]))
            return ok
        return call

    def solution(rng):
        args = perturbed(rng, base, extra=True)
        s = rc.creep_solution_3d(*args, method=rng.choice(["modified_strip", "she", "strip"]))
        return (finite(s.tx, s.ty, s.stick_area_fraction, s.stick_width_ratio)
                and coulomb(s.tx, s.ty, args[8], args[3]))

    def normalised(rng):
        z = rc.normalised_creepage_3d(*perturbed(rng, base, extra=True))
        return not np.any(np.isnan(z)) and np.all(z >= 0.0)

    def saturation(rng):
        args = perturbed(rng, base[3:], extra=True)
        return finite(rc.saturation_creepage_3d(*args, direction=rng.uniform(-4, 4)))

    def spin(rng):
        phi = rc.spin_coefficient(*perturbed(rng, [1e-3, -5e-4, 0.1, 6e-3, 5e-3], extra=True))
        return not np.any(np.isnan(phi)) and np.all(phi >= 0.0)

    def kalker(rng):
        return finite(*rc.kalker_coefficients(*perturbed(rng, [1.2, 0.28], extra=True)))

    def hertz3(rng):
        return finite(*rc.hertz_3d(*perturbed(rng, [8e4, 1.087, 1.667, 2.1e11, 0.28],
                                              extra=True)))

    def hertz2(rng):
        return finite(*rc.hertz_2d(*perturbed(rng, [1e6, 0.46, 2.1e11, 0.28], extra=True)))

    def carter(rng):
        args = perturbed(rng, [1e-3, 1e6, 0.46, 2.1e11, 0.28, 0.3], extra=True)
        f = rc.carter_creep_force(*args)
        return finite(f) and bool(np.all(np.abs(f) <= np.asarray(args[5]) * np.asarray(args[1])
                                         * (1 + 4 * EPS)))

    def carter_stick(rng):
        return finite(rc.carter_stick_ratio(*perturbed(rng, [1e-3, 1e6, 0.46, 2.1e11, 0.28,
                                                             0.3], extra=True)))

    def carter_critical(rng):
        return finite(rc.carter_critical_creepage(*perturbed(rng, [1e6, 0.46, 2.1e11, 0.28,
                                                                   0.3], extra=True)))

    def relax(rng):
        return finite(nonsteady.relax_creepage(*perturbed(rng, [1e-3, -2e-3, 1e-3, 5e-3],
                                                          extra=True)))

    def table(rng):
        args = perturbed(rng, base, extra=True)
        tx, ty = ct.creep_force_3d(*args)
        return finite(tx, ty) and coulomb(tx, ty, args[8], args[3])

    def table_solution(rng):
        args = perturbed(rng, base, extra=True)
        tx, ty, stick, z = ct.creep_solution_3d(*args)
        return finite(tx, ty, stick) and coulomb(tx, ty, args[8], args[3])

    def table_jacobian(rng):
        return finite(ct.creep_force_jacobian_3d(*perturbed(rng, base, extra=True)))

    def exact(rng):
        args = perturbed(rng, base, extra=True)
        tx, ty = et.creep_force_3d(*args)
        return finite(tx, ty) and coulomb(tx, ty, args[8], args[3])

    def exact_solution(rng):
        args = perturbed(rng, base, extra=True)
        tx, ty, mz, stick, rho = et.creep_solution_3d(*args)
        return finite(tx, ty, mz, stick, rho) and coulomb(tx, ty, args[8], args[3])

    return {
        "creep_force_3d[modified_strip]": creep("modified_strip"),
        "creep_force_3d[she]": creep("she"), "creep_force_3d[strip]": creep("strip"),
        "creep_force_3d[linear]": creep("linear"), "creep_solution_3d": solution,
        "creep_force_3d[fastsim]": creep("fastsim"), "creep_force_3d[polach]": creep("polach"),
        "creep_force_3d[fastrip]": creep("fastrip"), "creep_force_3d[exact]": creep("exact"),
        "normalised_creepage_3d": normalised, "saturation_creepage_3d": saturation,
        "spin_coefficient": spin, "kalker_coefficients": kalker, "hertz_3d": hertz3,
        "hertz_2d": hertz2, "carter_creep_force": carter, "carter_stick_ratio": carter_stick,
        "carter_critical_creepage": carter_critical, "relax_creepage": relax,
        "CreepTable.creep_force_3d": table, "CreepTable.creep_solution_3d": table_solution,
        "CreepTable.creep_force_jacobian_3d": table_jacobian,
        "ExactCreepTable.creep_force_3d": exact,
        "ExactCreepTable.creep_solution_3d": exact_solution,
    }


FMU_INPUTS = ["normal_force", "creepage_longitudinal", "creepage_lateral", "spin",
              "rolling_speed", "rail_position"]
FMU_BASE = [8e4, 1e-3, -5e-4, 0.1, 20.0, 0.0]


def make_slaves():
    module = importlib.import_module("WheelRailContact")
    slaves = {}
    for stem in ("creep_only_table", "creep_exact_table", "creep_only_analytic",
                 "nonsteady_creep"):
        slave = module.WheelRailContact(instance_name=stem, resources=None)
        slave.scene_file = str(ROOT / "examples" / "scenes" / f"{stem}.toml")
        slave._contact.normal_force = 8e4
        slave.exit_initialization_mode()
        slaves[stem] = slave
    return slaves


def fmu_call(slaves):
    def call(rng):
        stem = list(slaves)[rng.integers(len(slaves))]
        slave = slaves[stem]
        c = slave._contact
        values = perturbed(rng, FMU_BASE)
        h = extreme(rng) if rng.random() < 0.2 else 1e-3
        for name, v in zip(FMU_INPUTS, values):
            setattr(c, name, float(v))
        n_log = len(slave.log_queue)
        try:
            slave.do_step(0.0, h)
        except ValueError:
            errors = [m for m in slave.log_queue[n_log:] if int(m.status) >= 3]
            if not errors:
                raise RuntimeError("ValueError without an error log line") from None
            raise
        slave._auxiliary("stick_area_fraction")     # the outputs computed when read
        lazy = (c.stick_area_fraction, c.stick_width_ratio, c.r_a0, c.Mz)
        LAST.extend([f"scene {stem}, step size {h:g}", ("Fx", c.Fx), ("Fy", c.Fy), lazy,
                     ("a0", c.a0), ("b0", c.b0), ("p0", c.p0), ("mu", c.friction_coefficient)])
        return finite(c.Fx, c.Fy, c.a0, c.b0, c.p0, *lazy) and coulomb(c.Fx, c.Fy, c.friction_coefficient,
                                                                c.normal_force)
    return call


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=20000)
    parser.add_argument("--seed", type=int, default=14)
    parser.add_argument("--show", type=int, default=10, help="failures printed")
    opts = parser.parse_args(argv)
    rng = np.random.default_rng(opts.seed)
    tables = (CreepTable.from_file(), load_exact_table())
    cases = make_cases(tables)
    cases["FMU slave do_step"] = fmu_call(make_slaves())
    names = list(cases)
    counts = collections.Counter()
    per_case = collections.defaultdict(collections.Counter)
    shown = 0
    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        np.seterr(all="ignore")                     # counted by the outcome, not the warning
        for _ in range(opts.calls):
            name = names[rng.integers(len(names))]
            try:
                outcome = "finite" if cases[name](rng) else "other"
                detail = "non-finite output or |T| > mu N"
            except ValueError as exc:
                # the house style names the parameter: "<name> must be in <range> ..."
                outcome = "ValueError" if " must " in str(exc) else "other"
                detail = f"ValueError not in the house style: {exc}"
            except Exception as exc:  # noqa: BLE001 - counted and shown
                outcome, detail = "other", f"{type(exc).__name__}: {exc}"
            counts["calls"] += 1
            counts[outcome] += 1
            per_case[name][outcome] += 1
            if outcome == "other" and shown < opts.show:
                shown += 1
                print(f"OTHER in {name}: {detail[:300]}; arguments {LAST}")
    elapsed = time.perf_counter() - start
    print(f"\nseed {opts.seed}: {counts['calls']} calls in {elapsed:.1f} s: "
          f"{counts['finite']} finite, {counts['ValueError']} ValueError, "
          f"{counts['other']} other")
    width = max(len(n) for n in names)
    for name in names:
        c = per_case[name]
        print(f"  {name:<{width}}  {sum(c.values()):6d} calls  {c['finite']:6d} finite  "
              f"{c['ValueError']:6d} ValueError  {c['other']:4d} other")
    return 0 if counts["other"] == 0 else 1


if __name__ == "__main__":
    sys.exit(main())

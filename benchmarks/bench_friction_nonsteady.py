"""Accuracy and speed of railcontact.friction (Ch. 5) and railcontact.nonsteady (Ch. 7).

Run::

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_friction_nonsteady.py

(With a multi-threaded BLAS on a loaded machine the small dense products of the friction solver
are ~50 times slower; set the variable.) Prints tables; no assertions.

Friction: the creep force of the smooth law (5.16) against the polynomial degree (the error is
measured against degree 1024) and against the discretised half-space reference solver
(rising law, where its continuation converges), with the time per creep-curve point.
Non-steady: time per point of the vectorised transfer function on a (a0/L, r_a0) grid.
"""

from __future__ import annotations

import time

import numpy as np

from railcontact.friction import (SmoothFriction, velocity_friction_creep_force_normalised,
                                  velocity_friction_peak_normalised)
from railcontact.hertz import hertz_2d
from railcontact.nonsteady import (gross_thebing_transfer_function_normalised,
                                   nonsteady_transfer_function_normalised)
from railcontact.reference.halfspace2d import solve_rolling_2d

E, NU, R, N, MU0 = 210e9, 0.28, 0.5, 1.0e6, 0.3


def bench_degree():
    print("\n== smooth law: force error against degree (reference: degree 1024) ==")
    chi = np.array([0.1, 0.3, 0.6, 0.9, 1.5])
    for m, kap in ((0.6, 5.0), (1.4, 10.0), (0.6, 50.0)):
        ref = velocity_friction_creep_force_normalised(chi, m, kap, degree=1024)
        print(f"m = {m}, kappa xi_c0 = {kap}")
        for deg in (32, 64, 128, 256, 512):
            t0 = time.perf_counter()
            f = velocity_friction_creep_force_normalised(chi, m, kap, degree=deg)
            dt = (time.perf_counter() - t0) / chi.size
            print(f"  degree {deg:4d}: max |dT|/(mu0 N) = {np.max(np.abs(f - ref)):.2e}, "
                  f"{dt * 1e3:7.1f} ms per point")


def bench_reference():
    print("\n== smooth law vs discretised reference solver "
          "(rising law m = 1.4, kappa xi_c0 = 10) ==")
    h = hertz_2d(N, R, E, NU)
    a0, p0 = float(h.a0), float(h.p0)
    xic = MU0 * a0 / R
    m, kap = 1.4, 10.0
    law = SmoothFriction(MU0, m * MU0, kap / xic)
    chi = np.array([0.1, 0.3, 0.5, 0.8, 1.2])
    t0 = time.perf_counter()
    ours = -velocity_friction_creep_force_normalised(chi, m, kap)
    t_ours = (time.perf_counter() - t0) / chi.size
    refs = {}
    for nel in (100, 200, 400):
        dx = 2 * a0 / nel
        x = np.arange(-a0 + dx / 2, a0, dx)
        p = p0 * np.sqrt(np.clip(1 - (x / a0) ** 2, 0, None))
        t0 = time.perf_counter()
        ref = np.array([-solve_rolling_2d(x, p, E, NU, creepage=c * xic, friction=law)
                       .tangential_force / (MU0 * N) for c in chi])
        t_ref = (time.perf_counter() - t0) / chi.size
        refs[nel] = ref
        err = np.max(np.abs(ours - ref))
        print(f"  {nel:4d} elements: max |T_poly - T_ref|/(mu0 N) = {err:.2e}"
              f" ({t_ref * 1e3:.0f} ms per point; polynomial degree 128: {t_ours * 1e3:.0f} ms)")
    rich = 2 * refs[400] - refs[200]
    print(f"  Richardson 2 T_400 - T_200: max |T_poly - T_ref| = {np.max(np.abs(ours - rich)):.2e}")


def bench_peak():
    print("\n== creepage at the creep-curve maximum (onset of negative damping) ==")
    m = np.array([0.5, 0.6, 0.7, 0.8, 0.9])
    for kap in (2.0, 5.0, 20.0):
        t0 = time.perf_counter()
        c, f = velocity_friction_peak_normalised(m, kap)
        dt = (time.perf_counter() - t0) / m.size
        print(f"  kappa xi_c0 = {kap:5.1f}: xi_peak/xi_c0 = {np.round(c, 3)}, "
              f"T_peak/(mu0 N) = {np.round(f, 3)} ({dt * 1e3:.0f} ms per point)")


def bench_nonsteady():
    print("\n== non-steady transfer function (vectorised over a 400 x 50 grid of a0/L, r_a0) ==")
    wr = np.linspace(0, 2, 400)[:, None]
    r = np.linspace(0.02, 1, 50)[None, :]
    for model in ("carter", "johnson"):
        t0 = time.perf_counter()
        h = nonsteady_transfer_function_normalised(wr, r, model=model)
        dt = (time.perf_counter() - t0) / h.size
        g = gross_thebing_transfer_function_normalised(wr, stick_ratio=r)
        print(f"  {model:8s}: {dt * 1e9:.0f} ns per point; max |H - H_GT(a0*)| = "
              f"{np.max(np.abs(h - g)):.3f}, max | |H|/|H_GT| - 1 | = "
              f"{np.max(np.abs(np.abs(h) / np.abs(g) - 1)):.3f}")


if __name__ == "__main__":
    bench_degree()
    bench_reference()
    bench_peak()
    bench_nonsteady()

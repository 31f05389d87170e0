"""Conditioning and speed of the polynomial approach (railcontact.polynomial, railcontact.roughness).

1. Accuracy versus degree N (normalised coordinates, a = 1):
   * ``|[A][A]^-1 - I|``, the condition number of ``[A]``;
   * the PV integral (3.4) of random coefficients vs a 40-digit mpmath quadrature, inside and
     outside the strip, and the literal outside form (cancellation) for comparison;
   * the base change ``[D(1)]`` (shift by one half-width) vs exact evaluation (digits lost);
   * physical units (a = 5 mm): the index where ``(a/2)^(2k)`` underflows.
2. A high-degree non-Hertzian problem: gap ``Z = (cosh(kX) - 1)/k^2`` truncated at degree N,
   normal + tangential solution; the answers must converge with N until rounding takes over.
3. Speed: polynomial solvers vs the discretised reference solver, same run (ratios).

Run:  OPENBLAS_NUM_THREADS=1 python benchmarks/bench_polynomial.py [--quick]
"""

import argparse
import os
import sys
import time

import mpmath as mp
import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
from _timing import per_call  # noqa: E402

from railcontact import polynomial as P  # noqa: E402
from railcontact import roughness as Rg  # noqa: E402
from railcontact.reference.halfspace2d import solve_normal_2d, solve_rolling_2d  # noqa: E402

E, NU, N, MU = 2.1e11, 0.28, 2e5, 0.3


def pv_mpmath(coef, s, dps=40):
    with mp.workdps(dps):
        c = [mp.mpf(float(v)) for v in coef]   # ascending powers
        s = mp.mpf(s)
        if abs(s) > 1:
            return mp.quad(lambda t: mp.polyval(c, mp.cos(t), asc=True) / (s - mp.cos(t)),
                           [0, mp.pi])
        t0 = mp.acos(s)

        def g(t):
            return (mp.polyval(c, mp.cos(t), asc=True)
                    / (mp.sin((t + t0) / 2) * mp.sinc((t - t0) / 2)))

        g0 = g(t0)
        return (mp.quad(lambda t: (g(t) - g0) / (t - t0), [0, t0, mp.pi])
                + g0 * mp.log((mp.pi - t0) / t0))


def accuracy_vs_degree(degrees):
    print("1. accuracy vs degree (normalised a = 1; errors relative to sum|b|)")
    print(f"{'N':>5} {'|AA^-1-I|':>10} {'cond(A)':>9} {'PV in':>9} {'PV out':>9} "
          f"{'literal out':>11} {'D(1) err':>9}")
    rng = np.random.default_rng(0)
    for n in degrees:
        amat, ainv = P.transform_matrix(n), P.inverse_transform_matrix(n)
        ident = np.abs(amat @ ainv - np.eye(n)).max()
        cond = np.linalg.cond(amat)
        b = rng.normal(size=n + 1)
        scale = np.abs(b).sum()
        err_in = max(abs(P.principal_value_integral(b, s) - float(pv_mpmath(b, s)))
                     for s in (-0.7, 0.2, 0.95)) / scale
        s_out = 1.5
        ref_out = float(pv_mpmath(b, s_out))
        err_out = abs(P.principal_value_integral(b, s_out) - ref_out) / scale
        literal = (np.polynomial.polynomial.polyval(s_out, amat @ b[1:])
                   + np.pi / np.sqrt(s_out**2 - 1) * np.polynomial.polynomial.polyval(s_out, b))
        err_lit = abs(literal - ref_out) / scale
        gamma = P.base_change_matrix(n, 1.0) @ b
        with mp.workdps(60):
            exact = float(mp.polyval([mp.mpf(v) for v in b], mp.mpf(-0.5) + 1, asc=True))
        err_d = abs(np.polynomial.polynomial.polyval(-0.5, gamma) - exact) / scale
        print(f"{n:5d} {ident:10.2e} {cond:9.2e} {err_in:9.2e} {err_out:9.2e} {err_lit:11.2e} "
              f"{err_d:9.2e}")
    coef = P.transform_coefficients(400, 5e-3)
    k_under = int(np.argmax(coef == 0.0))
    print(f"   physical units, a = 5 mm: (a/2)^(2k) underflows to 0 from k = {k_under} "
          f"(degree {2 * k_under + 1}); normalised: never (A_k ~ -sqrt(pi/k)).")


def cosh_gap(n, kappa):
    """Taylor coefficients of (cosh(kappa X) - 1)/kappa^2 up to degree n."""
    from math import factorial
    z = np.zeros(n + 1)
    for j in range(2, n + 1, 2):
        z[j] = kappa ** (j - 2) / factorial(j)
    return z


def high_degree_problem(degrees):
    print("\n2. gap (cosh(k X) - 1)/k^2 truncated at degree N, N = 2e5 N/m; k a ~ 2.3")
    kappa = 2000.0
    print(f"{'N':>5} {'a [mm]':>16} {'xi(a*/a=0.5)':>22} {'T(a*/a=0.5)/muN':>18}")
    for n in degrees:
        nc = P.solve_normal_polynomial(cosh_gap(n, kappa), N, E, NU, centre_guess=0.0)
        xi, t = P.tangential_state_polynomial(nc, MU, 0.5)
        print(f"{n:5d} {nc.half_width * 1e3:16.12f} {float(xi):22.15e} "
              f"{float(t) / (MU * N):18.15f}")


def speed():
    print("\n3. speed (median wall time per call, same run)")
    z4 = np.array([0.0, 0.0, 1.0, 300.0, 2e5])
    t_poly = per_call(lambda: P.solve_normal_polynomial(z4, N, E, NU))
    nc = P.solve_normal_polynomial(z4, N, E, NU)
    t_tan = per_call(lambda: P.solve_tangential_polynomial(nc, MU, creepage=-3e-4))
    c_lam = (2.0, 300.0, 2e5)
    t_asp = per_call(lambda: Rg.asperity_normal_contact(N, *c_lam, E, NU))
    c = Rg.asperity_normal_contact(N, *c_lam, E, NU)
    t_asp_t = per_call(lambda: Rg.asperity_tangential_contact(c, MU, creepage=-3e-4))
    print(f"   polynomial normal (quartic gap)        {t_poly * 1e3:8.2f} ms")
    print(f"   polynomial tangential (given xi)       {t_tan * 1e3:8.2f} ms")
    print(f"   asperity Table 6.1 (numerical case)    {t_asp * 1e3:8.2f} ms")
    print(f"   asperity tangential (6.38)-(6.39)      {t_asp_t * 1e3:8.2f} ms")
    for n in (400, 800):
        t0 = time.perf_counter()
        ref = solve_normal_2d(lambda x: np.polynomial.polynomial.polyval(x, z4), N, E, NU,
                              -1.6e-3, 1.4e-3, n)
        t_ref = time.perf_counter() - t0
        x = nc.centre + np.linspace(-nc.half_width, nc.half_width, n + 1)
        x = 0.5 * (x[1:] + x[:-1])
        t0 = time.perf_counter()
        solve_rolling_2d(x, nc.pressure(x), E, NU, creepage=-3e-4, friction=MU)
        t_ref_t = time.perf_counter() - t0
        a_err = abs(0.5 * (ref.contact_end - ref.contact_start) / nc.half_width - 1)
        print(f"   reference n = {n:4d}: normal {t_ref * 1e3:8.1f} ms ({t_ref / t_poly:6.0f}x "
              f"polynomial; |a error| {a_err:.1e}), rolling {t_ref_t * 1e3:8.1f} ms "
              f"({t_ref_t / t_tan:6.0f}x)")
    l2 = -20.0
    z = Rg.double_asperity_coefficients(l2)
    d = 1 / (16 * abs(l2))
    t0 = time.perf_counter()
    two = Rg.two_patch_normal_contact(z, 4e6, E, NU, (-d, d))
    t_two = time.perf_counter() - t0
    t0 = time.perf_counter()
    Rg.two_patch_tangential_contact(two, MU, -3e-3)
    t_two_t = time.perf_counter() - t0
    t0 = time.perf_counter()
    Rg.two_patch_normal_contact(z, 2e6, E, NU, (-d, d), load_split="compatible")
    t_comp = time.perf_counter() - t0
    print(f"   two patches normal {t_two:.2f} s, tangential {t_two_t:.2f} s, compatible split "
          f"{t_comp:.2f} s (single runs)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer degrees")
    args = parser.parse_args()
    degrees = (4, 8, 16, 32) if args.quick else (4, 8, 16, 32, 64, 128)
    accuracy_vs_degree(degrees)
    high_degree_problem((4, 8, 12, 16, 20, 24, 32, 40, 48) if not args.quick else (4, 8, 16))
    speed()


if __name__ == "__main__":
    main()

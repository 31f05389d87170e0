"""Accuracy versus time of the 2-D half-space reference solver (railcontact.reference.halfspace2d).

For n = 100 ... 1600 elements on a domain not aligned with the contact edges, prints the wall
time of the normal solve (Hertz) and of the steady-rolling solve (Carter, xi = -0.37 xi_c), and
their errors against the closed forms (Hertz (2.40)-(2.42), Carter (2.48)-(2.53)).

Then times a velocity-dependent law (5.16) (mu_k = 0.6 mu_0, kappa = 1e3) and the transient
solver (constant force, 6 transits of the contact).

Run:  OPENBLAS_NUM_THREADS=1 python benchmarks/bench_reference2d.py [--repeat 3]
(on a loaded machine a multi-threaded OpenBLAS makes the many small dense solves 10-50x slower).
"""

import argparse
import time

import numpy as np

from railcontact.reference.halfspace2d import (
    solve_normal_2d,
    solve_rolling_2d,
    solve_transient_rolling_2d,
)

E, NU, R, N, MU = 2.1e11, 0.28, 0.5, 1.0e6, 0.3
K = 4 * (1 - NU**2) / (np.pi * E)
A0 = np.sqrt(8 * N * R * (1 - NU**2) / (np.pi * E))
P0 = 2 * N / (np.pi * A0)
XI = -0.37 * MU * A0 / R
A_STAR = A0 + R * XI / MU
T_CARTER = MU * N * (1 - (A_STAR / A0) ** 2)


def _best_time(fn, repeat):
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--sizes", type=int, nargs="*", default=[100, 200, 400, 800, 1600])
    args = parser.parse_args(argv)
    print(f"Hertz a0 = {A0 * 1e3:.4f} mm, p0 = {P0 / 1e6:.1f} MPa; Carter xi = {XI:.3e}, "
          f"T/(mu N) = {T_CARTER / (MU * N):.4f}")
    print(f"{'n':>5} {'t_normal[s]':>11} {'t_rolling[s]':>12} {'|a/a0-1|':>9} {'|pmax/p0-1|':>11} "
          f"{'|d/d_H-1|':>9} {'|T/T_C-1|':>9} {'|dx_stick|/a':>12} {'rms dq/mu p0':>12}")
    for n in args.sizes:
        tn, r = _best_time(lambda: solve_normal_2d(lambda x: x**2 / (2 * R), N, E, NU,
                                                   -1.23 * A0, 1.31 * A0, n), args.repeat)
        tr, rr = _best_time(lambda: solve_rolling_2d(r.x, r.pressure, E, NU, creepage=XI,
                                                     friction=MU), args.repeat)
        err_a = abs(0.5 * (r.contact_end - r.contact_start) / A0 - 1)
        err_p = abs(r.pressure.max() / P0 - 1)
        err_d = abs(r.approach / (K * N * (0.5 - np.log(A0 / 2))) - 1)
        err_t = abs(rr.tangential_force / T_CARTER - 1)
        err_s = abs(rr.stick_start - (A0 - 2 * A_STAR)) / A0
        xc = A0 - A_STAR
        q_ex = MU * P0 / A0 * (np.sqrt(np.clip(A0**2 - rr.x**2, 0, None))
                               - np.sqrt(np.clip(A_STAR**2 - (rr.x - xc) ** 2, 0, None)))
        err_q = np.sqrt(np.mean((rr.traction - q_ex)[rr.contact_mask] ** 2)) / (MU * P0)
        print(f"{n:5d} {tn:11.4f} {tr:12.4f} {err_a:9.2e} {err_p:11.2e} {err_d:9.2e} "
              f"{err_t:9.2e} {err_s:12.2e} {err_q:12.2e}")
    law = lambda s: (MU - 0.6 * MU) / (1 + abs(1e3 * s)) + 0.6 * MU  # noqa: E731  (5.16)
    print(f"\n{'n':>5} {'t_law(5.16)[s]':>14} {'T/N':>7} {'steps':>6} {'t_transient[s]':>14} "
          f"{'|q-q_steady|/p0':>15}")
    for n in [m for m in args.sizes if m <= 400]:
        r = solve_normal_2d(lambda x: x**2 / (2 * R), N, E, NU, -1.23 * A0, 1.31 * A0, n)
        tl, rl = _best_time(lambda: solve_rolling_2d(r.x, r.pressure, E, NU, creepage=XI,
                                                     friction=law), args.repeat)
        steps = int(6 * np.count_nonzero(r.pressure))
        force = 0.4 * MU * N
        tt, tr = _best_time(lambda: solve_transient_rolling_2d(
            r.x, r.pressure, E, NU, tangential_force=np.full(steps, force), friction=MU,
            reference_length=0.1), 1)
        st = solve_rolling_2d(r.x, r.pressure, E, NU, tangential_force=force, friction=MU)
        dq = np.max(np.abs(tr.traction[-1] - st.traction)) / P0
        print(f"{n:5d} {tl:14.4f} {rl.tangential_force / N:7.4f} {steps:6d} {tt:14.4f} {dq:15.2e}")


if __name__ == "__main__":
    main()

"""Speed of the closed-form 3-D creep-force methods: ns per point of a 1e5-point creep curve.

Run: ``python benchmarks/bench_creep3d.py``. Prints one table; no assertions (timings depend on
the machine). Two cases per method: one ellipse (Kalker coefficients evaluated once) and a
different ellipse at every point (1e5 evaluations of the C2 Kalker interpolant).
"""

import time

import numpy as np

from railcontact import creep_force_3d, hertz_3d, kalker_coefficients
from railcontact.creep3d import METHODS

N_POINTS = 100_000
REPEAT = 5
E, NU, MU = 210e9, 0.28, 0.3


def _best(func):
    func()                                        # warm-up (spline construction, caches)
    times = []
    for _ in range(REPEAT):
        t0 = time.perf_counter()
        func()
        times.append(time.perf_counter() - t0)
    return min(times)


def main():
    a0, b0, _ = hertz_3d(1e5, 1.0, 2.5, E, NU)
    xi = np.linspace(-1e-2, 1e-2, N_POINTS)
    xi_y = 0.3 * xi
    spin = np.linspace(-0.1, 0.1, N_POINTS)
    ratio = np.geomspace(0.05, 20, N_POINTS)
    a_var = np.sqrt(a0 * b0 * ratio)
    b_var = a_var / ratio
    print(f"{N_POINTS} points, best of {REPEAT}")
    print(f"{'method':16s} {'one ellipse [ns/pt]':>20s} {'varying ellipse [ns/pt]':>24s}")
    for method in METHODS:
        t_one = _best(lambda: creep_force_3d(xi, xi_y, spin, 1e5, a0, b0, E, NU, MU,
                                             method=method))
        t_var = _best(lambda: creep_force_3d(xi, xi_y, spin, 1e5, a_var, b_var, E, NU, MU,
                                             method=method))
        print(f"{method:16s} {t_one / N_POINTS * 1e9:20.1f} {t_var / N_POINTS * 1e9:24.1f}")
    t_k = _best(lambda: kalker_coefficients(ratio, NU))
    print(f"{'kalker_coeffs':16s} {'':20s} {t_k / N_POINTS * 1e9:24.1f}")
    # scalar calls (as an FMU step makes them): per-call overhead of the numpy machinery
    n_calls = 2000
    for method in METHODS:
        t_s = _best(lambda: [creep_force_3d(1e-3, 2e-4, 0.01, 1e5, a0, b0, E, NU, MU,
                                            method=method) for _ in range(n_calls)])
        print(f"scalar call {method:16s} {t_s / n_calls * 1e6:8.1f} us/call")


if __name__ == "__main__":
    main()

"""Speed benchmark of the corrugation / wear / evolution models (Nielsen Ch. 4).

Run: ``python benchmarks/bench_corrugation.py``. Prints wall-clock figures; nothing is asserted.

1. W1, W2 over a 200 x 200 (r_a0, L/a0) grid, each wear model (closed forms, vectorised).
2. Evolution of a 1000-harmonic white-noise surface over 1e5 passages (closed form of the map
   (4.103), no loop over passages), surface returned at 100 passage counts, and the same map
   applied passage by passage (vectorised over harmonics) for comparison.
3. Exact nonlinear contact (a, Delta, a*, T) with M = 100 harmonics at 10 000 rail positions.
"""

import time

import numpy as np

from railcontact import corrugation as cg
from railcontact import evolution as ev
from railcontact import wear


def timed(fun, repeat=3):
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fun()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main():
    r = np.linspace(0.01, 0.99, 200)
    la = np.linspace(2.0, 30.0, 200)
    print("1. W1, W2 on a 200 x 200 (r_a0, L/a0) grid")
    for model in wear.WEAR_MODELS:
        t, w = timed(lambda: wear.wear_coefficients(1 / la[None, :], r[:, None], model))
        print(f"   {model:20s} {t * 1e3:8.1f} ms  ({t / w.size * 1e6:.2f} us per point)")

    print("2. 1000-harmonic white-noise surface, 1e5 passages")
    a0, rr, eps = 0.006, 0.5, 1e-4
    lam, za, zb = ev.white_noise_surface(1000, 2 * a0, 40 * a0, 1e-6, seed=0)
    t_w, w = timed(lambda: eps * wear.wear_coefficients(a0 / lam, rr, "nielsen1998"))
    passes = np.linspace(0, 1e5, 100)
    t_e, (zan, zbn) = timed(lambda: ev.evolve_harmonics(za, zb, w.real, w.imag, passes))

    def loop():
        z = za + 1j * zb
        f = 1 - w.real - 1j * w.imag
        for _ in range(100000):
            z = z * f
        return z

    t_l, z_loop = timed(loop, repeat=1)
    err = np.max(np.abs(z_loop - (zan[-1] + 1j * zbn[-1]))) / np.max(np.abs(z_loop))
    print(f"   coefficients {t_w * 1e3:.1f} ms; closed form (100 snapshots) {t_e * 1e3:.1f} ms; "
          f"passage-by-passage loop {t_l:.2f} s (ratio {t_l / t_e:.0f}x, max rel. diff {err:.1e})")
    dom = lam[np.argmax(np.hypot(zan[-1], zbn[-1]))] / a0
    print(f"   dominant L/a0 after 1e5 passages (nielsen1998, r = 0.5): {dom:.2f}")

    print("3. exact contact, M = 100 harmonics, 10 000 rail positions")
    e, nu, big_r, mu, n = 2.1e11, 0.28, 0.5, 0.3, 1e6
    lam = np.linspace(0.02, 0.3, 100)
    k = 2 * np.pi / lam
    amp = 1e-7 / (k * k * big_r) * 0 + 2e-7
    ph = np.random.default_rng(0).uniform(0, 2 * np.pi, 100)
    x = np.linspace(0, 1, 10000)
    for method in ("exact", "linear"):
        t, _ = timed(lambda: cg.corrugated_contact(x, n, big_r, e, nu, mu, 5e-4,
                                                   amp * np.cos(ph), amp * np.sin(ph), lam,
                                                   method=method), repeat=1)
        print(f"   {method:6s} {t * 1e3:8.1f} ms ({t / x.size * 1e6:.1f} us per position)")


if __name__ == "__main__":
    main()

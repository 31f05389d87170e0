"""Creep curves of the closed-form 3-D methods against CONTACT's exact curve.

Run with no arguments: ``python examples/creep_curve_demo.py``. Writes
``out/creep_curve_demo.png`` and prints a small table of T_x/(mu N) and the errors against
CONTACT (Kalker's exact theory, Vollebregt's implementation, Apache-2.0; the Eurosprinter case
a/b = 0.5, a = 6.304 mm, b = 12.61 mm, Fn = 106.7 kN, mu = 0.33, G = 82 GPa, nu = 0.28).
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from railcontact import creep_force_3d, saturation_creepage_3d  # noqa: E402
from railcontact.creep3d import METHODS  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
CONTACT_CSV = ROOT / "tests" / "data" / "contact_tractcurv_series1_coulomb.csv"
OUT = ROOT / "out"

G_MOD, NU, MU = 82e9, 0.28, 0.33
E = 2 * G_MOD * (1 + NU)
A0, B0, N = 6.304e-3, 12.61e-3, 106.7e3
LABELS = {"linear": "Kalker linear (2.61)", "she": "SHE (2.63)-(2.65)",
          "strip": "strip theory (2.87)", "modified_strip": "modified strip (2.90)-(2.96)"}


def main():
    contact = np.loadtxt(CONTACT_CSV, delimiter=",", comments="#", skiprows=5)
    xi_sat = saturation_creepage_3d(N, A0, B0, E, NU, MU)
    xi = np.linspace(0.0, 0.006, 601)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for method in METHODS:
        tx = creep_force_3d(xi, 0.0, 0.0, N, A0, B0, E, NU, MU, method=method).tx / (MU * N)
        ax.plot(xi * 1e3, -tx, label=LABELS[method], ls="--" if method == "linear" else "-")
    ax.plot(contact[:, 0] * 1e3, -contact[:, 1], "ko", ms=4, label="CONTACT (exact theory)")
    ax.axvline(xi_sat * 1e3, color="grey", lw=0.8, ls=":")
    ax.text(xi_sat * 1e3, 0.55, "saturation of the\nmodified strip theory ", fontsize=8, ha="right")
    ax.set(xlim=(0, 6), ylim=(0, 1.1), xlabel=r"longitudinal creepage $\xi_x$ [‰]",
           ylabel=r"$-T_x/(\mu N)$ [-]",
           title="Creep curves, a/b = 0.5, Fn = 106.7 kN, mu = 0.33 (Eurosprinter)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    OUT.mkdir(exist_ok=True)
    png = OUT / "creep_curve_demo.png"
    fig.tight_layout()
    fig.savefig(png, dpi=120)

    rows = contact[contact[:, 0] <= 0.006]
    table = {m: creep_force_3d(rows[:, 0], 0.0, 0.0, N, A0, B0, E, NU, MU, method=m).tx
             / (MU * N) for m in METHODS if m != "linear"}
    print(f"saturation creepage (modified strip): {xi_sat:.6f}")
    print(f"{'xi_x':>8s} {'CONTACT':>9s} " + " ".join(f"{m:>15s}" for m in table))
    for i, x in enumerate(rows[:, 0]):
        print(f"{x:8.4f} {rows[i, 1]:9.4f} " + " ".join(f"{table[m][i]:15.4f}" for m in table))
    all_err = {m: np.max(np.abs(creep_force_3d(contact[:, 0], 0.0, 0.0, N, A0, B0, E, NU, MU,
                                                 method=m).tx / (MU * N) - contact[:, 1]))
               for m in table}
    print("max |error| over all 30 CONTACT points [% of mu N]: "
          + ", ".join(f"{m} {100 * e:.2f}" for m, e in all_err.items()))
    print(f"wrote {png}")


if __name__ == "__main__":
    main()

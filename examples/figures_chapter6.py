"""Regenerate figures 6.3, 6.6, 6.7, 6.8 and 6.9 of Nielsen (1998), chapter 6 (PNG).

Run: ``python examples/figures_chapter6.py [--out DIR]`` (default ``docs/figures/ch6``), a few
seconds. Also prints our version of Table 6.2.

The thesis does not print the parameters of its figures (the asperities A1..A4, N~, N0, xi0);
the values below are our own choice, picked so that the effects are visible:

* A1..A4 (Fig. 6.2/6.3/6.7/6.8): l2 = 2 1/m, l3 in {0, 300} 1/m^2, l4 in {0, 1e5} 1/m^3 with
  A1 - A2 - A3 + A4 = 0 (6.11), N = 2e5 N/m, E = 210 GPa, nu = 0.28, mu = 0.3.
* Asperity A (Fig. 6.5/6.6/6.9): l2 = -20 1/m, l3 = 0, l4 = -1536 l2^3, N0 = 1.6e6 N/m,
  xi0 = 0.3 x (smallest critical creepage of the two patches at N0), equal load split.

Package orientation: the leading edge is at +x (the thesis draws it at -x), so the stick zones
are on the right of each patch and the thesis' "first" patch is the right one.
"""

import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from railcontact import polynomial as P  # noqa: E402
from railcontact import roughness as Rg  # noqa: E402

E, NU, MU = 2.1e11, 0.28, 0.3
N_ASP = 2e5
L2, L3, L4 = 2.0, 1500.0, 2e6
ASPERITIES = {"A1": (L2, 0.0, 0.0), "A2": (L2, L3, 0.0), "A3": (L2, 0.0, L4),
              "A4": (L2, L3, L4)}
L2_A = -20.0
N0 = 1.6e6
LOADS = (1.0, 1.5, 2.0, 2.5)


def _style(name):
    return dict(ls="--", color="k") if name == "A1" else dict(ls="-")


def fig_6_3(out):
    fig, ax = plt.subplots(figsize=(6, 4))
    for name, lam in ASPERITIES.items():
        c = Rg.asperity_normal_contact(N_ASP, *lam, E, NU)
        x = np.linspace(c.shift - 1.05 * c.half_width, c.shift + 1.05 * c.half_width, 801)
        ax.plot(x * 1e3, c.pressure(x) / 1e6, label=f"{name}: a = {c.half_width * 1e3:.4f} mm, "
                f"$\\Delta$ = {c.shift * 1e6:+.1f} $\\mu$m", **_style(name))
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("p [MPa]")
    ax.set_title("Fig. 6.3: normal pressure of asperities A1..A4 (A1 dashed)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig6_3_asperity_pressure.png"), dpi=120)
    plt.close(fig)


def fig_6_7_6_8(out):
    fig7, ax7 = plt.subplots(figsize=(6, 4))
    fig8, ax8 = plt.subplots(figsize=(6, 4))
    for name, lam in ASPERITIES.items():
        c = Rg.asperity_normal_contact(N_ASP, *lam, E, NU)
        t = Rg.asperity_tangential_contact(c, MU, tangential_force=0.75 * MU * N_ASP)
        x = np.linspace(c.shift - c.half_width, c.shift + c.half_width, 801)
        ax7.plot(x * 1e3, t.traction(x) / 1e6, label=f"{name}: a*/a = {t.stick_ratio:.3f}",
                 **_style(name))
        r = np.linspace(1.0, 0.0, 200)  # full stick -> full slip
        xi, force = Rg.asperity_tangential_state(c, MU, r)  # branch xi <= 0, T >= 0
        xs = np.concatenate((-xi, [1.5 * -xi[-1]]))
        fs = np.concatenate((force, [MU * N_ASP]))
        ax8.plot(xs * 1e3, fs / (MU * N_ASP), label=name, **_style(name))
        ax8.plot(-t.creepage * 1e3, 0.75, "D", color=ax8.lines[-1].get_color())
    ax7.set_xlabel("x [mm]")
    ax7.set_ylabel("q [MPa]")
    ax7.set_title("Fig. 6.7: traction for T = 0.75 mu N (leading edge +x)")
    ax7.legend(fontsize=7)
    fig7.tight_layout()
    fig7.savefig(os.path.join(out, "fig6_7_asperity_traction.png"), dpi=120)
    ax8.set_xlabel("-creepage [1e-3]")
    ax8.set_ylabel("T / (mu N)")
    ax8.set_title("Fig. 6.8: creep curves of A1..A4 (diamonds: Fig. 6.7)")
    ax8.legend(fontsize=7)
    fig8.tight_layout()
    fig8.savefig(os.path.join(out, "fig6_8_asperity_creep_curves.png"), dpi=120)
    plt.close(fig7)
    plt.close(fig8)


def _double_asperity():
    z = Rg.double_asperity_coefficients(L2_A)
    d = 1.0 / (16.0 * abs(L2_A))
    return z, d


def fig_6_6_6_9(out):
    z, d = _double_asperity()
    fig6, axes6 = plt.subplots(2, 2, figsize=(8, 6), sharex=True)
    fig9, axes9 = plt.subplots(2, 2, figsize=(8, 6), sharex=True)
    two0 = Rg.two_patch_normal_contact(z, N0, E, NU, (-d, d))
    xi0 = 0.3 * min(-P.tangential_state_polynomial(p, MU, 0.0)[0] for p in two0.patches)
    x = np.linspace(-1.4 * d, 1.4 * d, 4001)
    for ax6, ax9, f in zip(axes6.ravel(), axes9.ravel(), LOADS):
        with_ci = Rg.two_patch_normal_contact(z, f * N0, E, NU, (-d, d))
        without = Rg.two_patch_normal_contact(z, f * N0, E, NU, (-d, d), cross_influence=False)
        ax6.plot(x * 1e3, with_ci.pressure(x) / 1e6, "-", label="with cross influence")
        ax6.plot(x * 1e3, without.pressure(x) / 1e6, "--", label="without")
        ax6.set_title(f"N = {f:g} N0", fontsize=9)
        tc = Rg.two_patch_tangential_contact(with_ci, MU, -xi0)
        tn = Rg.two_patch_tangential_contact(with_ci, MU, -xi0, cross_influence=False)
        ax9.plot(x * 1e3, tc.traction(x) / 1e6, "-", label="with cross influence")
        ax9.plot(x * 1e3, tn.traction(x) / 1e6, "--", label="without")
        ax9.set_title(f"N = {f:g} N0: r_T1 = {tn.forces[1] / tc.forces[1]:.4f}, "
                      f"r_T2 = {tn.forces[0] / tc.forces[0]:.4f}, "
                      f"r_T = {tn.tangential_force / tc.tangential_force:.4f}", fontsize=7)
    for axes, fig, ylabel, title, name in (
            (axes6, fig6, "p [MPa]", "Fig. 6.6: two patches of asperity A", "fig6_6_two_patch_pressure.png"),
            (axes9, fig9, "q [MPa]", f"Fig. 6.9: traction at xi = -xi0 = {-xi0:.3g}",
             "fig6_9_two_patch_traction.png")):
        for ax in axes[1]:
            ax.set_xlabel("X [mm]")
        for ax in axes[:, 0]:
            ax.set_ylabel(ylabel)
        axes[0, 0].legend(fontsize=7)
        fig.suptitle(title)
        fig.tight_layout()
        fig.savefig(os.path.join(out, name), dpi=120)
        plt.close(fig)
    return xi0


def table_6_2(xi0):
    z, d = _double_asperity()
    thesis = {  # Nielsen (1998) Table 6.2: (r_T1, r_T2, r_T)
        (0.5, 1.0): (1.1108, 0.9087, 0.9966), (0.5, 2.5): (1.2392, 0.8402, 0.9916),
        (1.0, 1.0): (1.0857, 0.9271, 0.9961), (1.0, 2.5): (1.1953, 0.8593, 0.9885),
        (1.5, 1.0): (1.0630, 0.9497, 0.9986), (1.5, 2.5): (1.1639, 0.8781, 0.9884),
        (2.0, 1.0): (1.0481, 0.9774, 1.0067), (2.0, 2.5): (1.1356, 0.8995, 0.9918)}
    print("Table 6.2 (ours; thesis in brackets where printed here). r_T1 = leading patch")
    contacts = {f: Rg.two_patch_normal_contact(z, f * N0, E, NU, (-d, d)) for f in LOADS}
    for fx in (0.5, 1.0, 1.5, 2.0):
        cells = []
        for f in LOADS:
            tc = Rg.two_patch_tangential_contact(contacts[f], MU, -fx * xi0)
            tn = Rg.two_patch_tangential_contact(contacts[f], MU, -fx * xi0,
                                                 cross_influence=False)
            ours = (tn.forces[1] / tc.forces[1], tn.forces[0] / tc.forces[0],
                    tn.tangential_force / tc.tangential_force)
            ref = thesis.get((fx, f))
            cells.append(" ".join(f"{v:.4f}" for v in ours)
                         + (" [" + " ".join(f"{v:.4f}" for v in ref) + "]" if ref else ""))
        print(f"xi = {fx:g} xi0: " + " | ".join(cells))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "..", "docs",
                                                      "figures", "ch6"))
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    fig_6_3(args.out)
    fig_6_7_6_8(args.out)
    xi0 = fig_6_6_6_9(args.out)
    table_6_2(xi0)


if __name__ == "__main__":
    main()

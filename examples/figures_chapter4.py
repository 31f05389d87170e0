"""Regenerate the figures of Nielsen (1998), chapter 4, from railcontact (PNG, docs/figures/ch4/).

Run: ``python examples/figures_chapter4.py [--out DIR] [--reference]``

Figures 4.3, 4.4, 4.6, 4.8, 4.10, 4.11, 4.13, 4.14, 4.15, 4.17, 4.18, 4.20, 4.21, plus
``wear_models.png`` (the finding of docs/wear_finding.md; ``--reference`` adds brute-force points
from the discretised half-space solver, about a minute).

Phases are plotted in the thesis' orientation (rolling towards -X, phase = arctan(Q2/Q1) of its
(4.64), (4.73)), i.e. minus the phase of the package orientation. The wear figures show the
thesis' own model (``wear_model="nielsen1998"``), the patch-coordinate integral, and the default
model (4.74) at a material point, which levels every wave length.
"""

import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402

from railcontact import corrugation as cg  # noqa: E402
from railcontact import evolution as ev  # noqa: E402
from railcontact import filters as fl  # noqa: E402
from railcontact import wear  # noqa: E402
from railcontact.reference.wear_direct import wear_first_harmonic_reference  # noqa: E402

RATIOS = np.linspace(1e-3, 0.5, 400)
STICK = (0.1, 0.3, 0.5, 0.7, 0.9)
MODELS = (("nielsen1998", "thesis (4.92), nielsen1998", "C1", "-"),
          ("patch_coordinate", "patch coordinate (no dwell)", "C2", "--"),
          ("material_point", "(4.74) at a material point (default)", "C0", "-"))


def _logx(ax):
    ax.set_xscale("log")
    ax.xaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xticks([2, 3, 5, 10, 20, 30])


def _save(fig, out, name):
    path = os.path.join(out, name)
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    print("wrote", path)


def _amp_phase(ax_a, ax_p, c, label, **kw):
    ax_a.plot(RATIOS, np.abs(c), label=label, **kw)
    ax_p.plot(RATIOS, np.degrees(np.angle(np.conj(c))), **kw)


def fig_4_3_4_4(out):
    cd, ca = cg.normal_response(RATIOS)
    for name, c, title in (
            ("fig4_3.png", cd, "Fig. 4.3: amplitude of Delta / (k R |Z|) = |J0(k a0)|"),
            ("fig4_4.png", ca, "Fig. 4.4: amplitude of a / (k R |Z|) = |J1(k a0)|")):
        fig, ax = plt.subplots(figsize=(6, 3.5))
        ax.plot(RATIOS, np.abs(c))
        ax.set_xlabel("a0 / L")
        ax.set_ylabel("normalised amplitude")
        ax.set_title(title, fontsize=9)
        ax.grid(alpha=0.3)
        if name == "fig4_4.png":
            ax.plot([0.2930], [0.5819], "o", color="C3")
            ax.annotate("max 0.582 at a0/L = 0.293", (0.2930, 0.5819), xytext=(0.32, 0.45))
        _save(fig, out, name)


def fig_4_6_4_8(out):
    for name, fun, title in (
            ("fig4_6.png", cg.stick_zone_response,
             "Fig. 4.6: a* amplitude / (k R |Z|) and phase"),
            ("fig4_8.png", cg.tangential_force_response,
             "Fig. 4.8: T amplitude / (|Z| mu pi E / (4 (1 - nu^2))) and phase")):
        fig, (ax_a, ax_p) = plt.subplots(2, 1, figsize=(6, 6), sharex=True)
        for r in STICK:
            _amp_phase(ax_a, ax_p, fun(RATIOS, r), f"r_a0 = {r}")
        ax_a.legend(fontsize=7)
        ax_a.set_title(title, fontsize=9)
        ax_p.set_xlabel("a0 / L")
        ax_p.set_ylabel("phase (thesis orientation) [deg]")
        ax_a.grid(alpha=0.3)
        ax_p.grid(alpha=0.3)
        _save(fig, out, name)


def fig_4_10(out, eps=0.01):
    la = np.linspace(1.5, 30, 600)
    fig, ax = plt.subplots(figsize=(6, 3.8))
    for model, label, color, ls in MODELS:
        ax.plot(la, ev.growth_factor(1 / la, 0.6, eps, model), color=color, ls=ls, label=label)
    ax.axhline(1, color="k", lw=0.6)
    ax.set_ylim(0.985, 1.015)
    ax.set_xlabel("L / a0")
    ax.set_ylabel("1 - 2 W1")
    ax.set_title(f"Fig. 4.10: 1 - 2 W1 at r_a0 = 0.6 (wear number K mu^2 N / a0 = {eps})",
                 fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    _save(fig, out, "fig4_10.png")


def fig_4_11_4_14_4_15_4_21(out):
    r = np.linspace(0.05, 0.95, 91)
    fig, ax = plt.subplots(figsize=(6, 4))
    for model, label, color, ls in MODELS[:2]:
        ax.plot(r, ev.stability_boundary(r, model), color=color, ls=ls, label=label)
    ax.text(0.3, 25, "(4.74) at a material point: W1 > 0 everywhere\n(no amplifying zone)",
            fontsize=7, color="C0")
    ax.set_ylim(0, 30)
    ax.set_xlabel("r_a0 = a0*/a0")
    ax.set_ylabel("L / a0 at W1 = 0")
    ax.set_title("Fig. 4.11: levelling (below) / amplifying (above)", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    _save(fig, out, "fig4_11.png")

    fig, ax = plt.subplots(figsize=(6, 4))
    for model, label, color, ls in MODELS[:2]:
        best, _, interior = ev.characteristic_wavelength(r, model)
        ax.plot(r, np.where(interior, best, np.nan), color=color, ls=ls, label=label)
    ax.axhspan(5, 10, color="0.9", label="thesis text: 5 - 10")
    ax.set_ylim(0, 20)
    ax.set_xlabel("r_a0")
    ax.set_ylabel("characteristic L / a0 (max of 1 - 2 W1)")
    ax.set_title("Fig. 4.14: characteristic wave length (none for the material point)", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    _save(fig, out, "fig4_14.png")

    fig, ax = plt.subplots(figsize=(6, 4))
    for model, label, color, ls in MODELS:
        ax.plot(r, ev.phase_change_boundary(r, model), color=color, ls=ls, label=label)
    ax.set_ylim(0, 30)
    ax.set_xlabel("r_a0")
    ax.set_ylabel("L / a0 at W2 = 0")
    ax.set_title("Fig. 4.15: limit between decreasing and increasing phase", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    _save(fig, out, "fig4_15.png")

    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(r, ev.stability_boundary(r, "nielsen1998"), "C1", label="polynomial approach (4.92)")
    ax.plot(r, 1 / fl.filter_stability_limit(r), "k--", label="filter, L/a0 = 4 r_a0 (4.127)")
    ax.set_ylim(0, 12)
    ax.set_xlabel("r_a0")
    ax.set_ylabel("L / a0 at W1 = 0")
    ax.set_title("Fig. 4.21: amplifying / levelling limit", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    _save(fig, out, "fig4_21.png")


def fig_4_13(out):
    a0, r, eps = 0.006, 0.5, 2e-3
    lam, za, zb = ev.white_noise_surface(600, 1.5 * a0, 40 * a0, 1e-6, seed=4)
    x = np.linspace(0, 100 * a0, 3000)
    fig, axes = plt.subplots(2, 2, figsize=(10, 5.5))
    for col, model in enumerate(("nielsen1998", "material_point")):
        w = eps * wear.wear_coefficients(a0 / lam, r, model)
        zan, zbn = ev.evolve_harmonics(za, zb, w.real, w.imag, [0, 3000])
        for i, (ls, lab) in enumerate((("--", "initial"), ("-", "after 3000 passages"))):
            scale = 1.0 if i == 0 else np.max(np.hypot(za, zb)) / np.max(np.hypot(zan[i], zbn[i]))
            axes[0, col].plot(x / a0, 1e6 * scale * ev.surface_profile(x, lam, zan[i], zbn[i]),
                              ls, lw=0.8, label=lab + ("" if i == 0 else f" (x {scale:.2g})"))
            axes[1, col].plot(lam / a0, 1e6 * np.hypot(zan[i], zbn[i]), ls, label=lab)
        axes[0, col].set_title(f"Fig. 4.13, wear_model = {model} (r_a0 = {r})", fontsize=9)
        axes[0, col].set_xlabel("X / a0")
        axes[0, col].set_ylabel("surface [um] (rescaled)")
        axes[1, col].set_xlabel("L / a0")
        axes[1, col].set_ylabel("amplitude [um]")
        _logx(axes[1, col])
        axes[0, col].legend(fontsize=7)
    _save(fig, out, "fig4_13.png")


def fig_4_17(out):
    q = np.linspace(0, 1.2, 400)
    fig, ax = plt.subplots(figsize=(6, 3.8))
    ax.plot(q, fl.remington_filter(q), "k--", label="Remington F_R (4.113)")
    ax.plot(q, fl.hempelmann_filter(q), "k-", label="Hempelmann F_RM (4.114)")
    ax.axhline(0, color="0.5", lw=0.5)
    ax.set_xlabel("a0 / L")
    ax.set_ylabel("filter")
    ax.set_title("Fig. 4.17: contact filters", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    _save(fig, out, "fig4_17.png")


def fig_4_18(out):
    fig, axes = plt.subplots(3, 3, figsize=(10, 8), sharex=True)
    for ax, r in zip(axes.ravel(), np.linspace(0.1, 0.9, 9)):
        ax.plot(RATIOS, np.abs(cg.stick_zone_response(RATIOS, r)), "k-", label="polynomial")
        ax.plot(RATIOS, np.abs(fl.filter_solution(RATIOS, r)[1]), "k--", label="filter")
        ax.set_title(f"r_a0 = {r:.1f}", fontsize=8)
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=7)
    fig.suptitle("Fig. 4.18: amplitude of a* / (k R |Z|) vs a0/L", fontsize=9)
    _save(fig, out, "fig4_18.png")


def fig_4_20(out):
    ratio, r = 1 / 3, 0.3
    x = np.linspace(0, 2, 400)          # X / L
    z = np.cos(2 * np.pi * x)
    ct = cg.tangential_force_response(ratio, r)
    ctf = fl.filter_solution(ratio, r)[2]
    fig, (ax_t, ax_w) = plt.subplots(2, 1, figsize=(6, 6), sharex=True)
    for c, ls, lab in ((ct, "-", "polynomial approach"), (ctf, "--", "filter solution")):
        ax_t.plot(x, np.real(c * np.exp(-2j * np.pi * x)), "k" + ls, label=lab)
    for model, lab, color, ls in MODELS:
        cw = wear.wear_coefficients(ratio, r, model)
        ax_w.plot(x, np.real(cw * np.exp(-2j * np.pi * x)), color=color, ls=ls, label=lab)
    cwf = fl.filter_wear_coefficients(ratio, r)
    ax_w.plot(x, np.real(cwf * np.exp(-2j * np.pi * x)), "k--", label="filter solution (4.123)")
    for ax in (ax_t, ax_w):
        ax.plot(x, 0.3 * z * np.max(np.abs(ax.get_ylim())), color="0.7", lw=0.8,
                label="surface (scaled)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6)
    ax_t.set_ylabel("T - T0 (per unit Z, mu/C units)")
    ax_w.set_ylabel("W - W0 (per unit Z, K mu^2 N / a0)")
    ax_w.set_xlabel("X / L (package orientation: rolling towards +X)")
    ax_t.set_title("Fig. 4.20: L/a0 = 3, r_a0 = 0.3", fontsize=9)
    _save(fig, out, "fig4_20.png")


def fig_wear_models(out, reference=False):
    la = np.geomspace(2, 30, 300)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for ax, r in zip(axes, (0.3, 0.6)):
        for model, label, color, ls in MODELS:
            ax.plot(la, wear.wear_coefficients(1 / la, r, model).real, color=color, ls=ls,
                    label=label)
        ax.plot(la, wear.wear_coefficients(1 / la, r, "time_domain_carter").real, color="C4",
                ls=":", label="(4.92) with consistent kinematics")
        if reference:
            pts = np.array([2.5, 4.0, 6.0, 10.0, 16.0])
            ref = [wear_first_harmonic_reference(1 / p, r, 0.05, n_positions=16,
                                                 n_elements=300) for p in pts]
            ax.plot(pts, [q["material_point"].real for q in ref], "o", color="C0",
                    label="half-space solver, (4.74) at material points")
            ax.plot(pts, [q["patch_coordinate"].real for q in ref], "s", mfc="none",
                    color="C2", label="half-space solver, patch coordinate")
        ax.axhline(0, color="k", lw=0.6)
        _logx(ax)
        ax.set_ylim(-0.6, 1.2)
        ax.set_xlabel("L / a0")
        ax.set_ylabel("W1 a0 / (K mu^2 N)   (> 0 levels, < 0 amplifies)")
        ax.set_title(f"r_a0 = {r}", fontsize=9)
        ax.grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=7)
    _save(fig, out, "wear_models.png")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--out", default=os.path.join(here, "..", "docs", "figures", "ch4"))
    parser.add_argument("--reference", action="store_true",
                        help="add half-space-solver points to wear_models.png")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    fig_4_3_4_4(args.out)
    fig_4_6_4_8(args.out)
    fig_4_10(args.out)
    fig_4_11_4_14_4_15_4_21(args.out)
    fig_4_13(args.out)
    fig_4_17(args.out)
    fig_4_18(args.out)
    fig_4_20(args.out)
    fig_wear_models(args.out, args.reference)


if __name__ == "__main__":
    main()

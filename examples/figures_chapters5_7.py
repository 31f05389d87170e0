"""Regenerate the figures of Nielsen (1998) Ch. 5 (5.1-5.5) and Ch. 7 (7.2, 7.3) as PNG.

Run from the repository root::

    python examples/figures_chapters5_7.py            # writes docs/figures/ch5/, docs/figures/ch7/
    python examples/figures_chapters5_7.py --out DIR  # another output folder

Conventions: creepage normalised by Carter's critical creepage for the static coefficient,
``xi_c0 = mu_0 a0 / R``; forces by ``mu_0 N`` and shown as magnitudes (the force on the wheel
opposes the creepage); x by ``a0`` with the leading edge at +1 (the thesis draws the mirror image).
The smooth law (5.16) uses ``kappa xi_c0 = 5`` (the thesis does not state its kappa). Ch. 7 uses
``b = 20 a0`` (as the thesis) and ``nu = 0.28``.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from railcontact.friction import (  # noqa: E402
    ohyama_creep_force_normalised, ohyama_traction_normalised, solve_velocity_friction_normalised,
    step_law_traction_normalised,
    velocity_friction_creep_force_normalised, velocity_friction_peak_normalised)
from railcontact.nonsteady import (  # noqa: E402
    gross_thebing_transfer_function_normalised, nonsteady_transfer_function_normalised)

KAPPA = 5.0
CASES = {"A": 0.6, "B": 1.4}


def _carter(chi, m=1.0):
    r = np.clip(1.0 - np.abs(chi) / m, 0.0, 1.0)
    return m * (1.0 - r * r)


def _carter_q(x, chi, m=1.0):
    r = np.clip(1.0 - abs(chi) / m, 0.0, 1.0)
    return m * (np.sqrt(np.clip(1 - x * x, 0, None))
                - np.sqrt(np.clip(r * r - (x - 1 + r) ** 2, 0, None)))


def fig_5_1(out):
    x = np.linspace(-1, 1, 801)
    fig, axs = plt.subplots(2, 1, figsize=(6, 6), sharex=True)
    for ax, (lab, m) in zip(axs, CASES.items()):
        ax.plot(x, -ohyama_traction_normalised(x, 0.4, m), "k-", label="Ohyama")
        ax.plot(x, m * np.sqrt(1 - x * x), "k:", lw=0.8, label=r"$\mu_k p$")
        ax.plot(x, np.sqrt(1 - x * x), "k--", lw=0.8, label=r"$\mu_0 p$")
        ax.set_title(f"({lab}) $\\mu_k = {m}\\mu_0$, $\\xi/\\xi_{{c0}} = 0.4$")
        ax.set_ylabel(r"$q/(\mu_0 p_0)$")
        ax.legend(fontsize=8)
    axs[-1].set_xlabel(r"$x/a_0$ (leading edge +1)")
    fig.suptitle("Fig. 5.1  Tangential stress according to Ohyama (step law)")
    fig.tight_layout()
    fig.savefig(out / "fig5_1_ohyama_stress.png", dpi=120)
    plt.close(fig)


def fig_5_2(out):
    chi = np.linspace(0, 1.6, 401)
    fig, axs = plt.subplots(2, 1, figsize=(6, 6), sharex=True)
    for ax, (lab, m) in zip(axs, CASES.items()):
        ax.plot(chi, -ohyama_creep_force_normalised(chi, m), "k-", label="Ohyama")
        ax.plot(chi, _carter(chi), "k--", lw=0.8, label=r"Carter $\mu_0$")
        ax.plot(chi, _carter(chi, m), "k-.", lw=0.8, label=r"Carter $\mu_k$ (= corrected step law)")
        ax.set_title(f"({lab}) $\\mu_k = {m}\\mu_0$")
        ax.set_ylabel(r"$|T|/(\mu_0 N)$")
        ax.legend(fontsize=8)
    axs[-1].set_xlabel(r"$|\xi|/\xi_{c0}$")
    fig.suptitle("Fig. 5.2  Creep curves of the step law")
    fig.tight_layout()
    fig.savefig(out / "fig5_2_ohyama_creep_curves.png", dpi=120)
    plt.close(fig)


def fig_5_3(out):
    chi, m = 0.3, 0.6
    x = np.linspace(-1, 1, 801)
    rk = 1 - chi / m
    xb = 1 - 2 * rk
    fig, ax = plt.subplots(figsize=(6, 3.5))
    ax.plot(x, -step_law_traction_normalised(x, chi, m), "k-", label=r"Carter $\mu_k$")
    pb = np.sqrt(1 - xb * xb)
    ax.plot([xb, xb], [m * pb, -float(step_law_traction_normalised(xb, chi, m))], "k-", lw=1.5,
            label=r"peak $\mu_0 p$ at the stick/slip limit (zero integral)")
    ax.plot(x, np.sqrt(1 - x * x), "k--", lw=0.8, label=r"$\mu_0 p$")
    ax.set_xlabel(r"$x/a_0$ (leading edge +1)")
    ax.set_ylabel(r"$q/(\mu_0 p_0)$")
    ax.set_title(r"Fig. 5.3  Step law, $\mu_k = 0.6\mu_0$, $\xi/\xi_{c0} = 0.3$: minimum solution")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "fig5_3_step_law_minimum_solution.png", dpi=120)
    plt.close(fig)


def fig_5_4(out):
    chi = np.concatenate([np.linspace(0, 1.6, 49)[1:], [2.0, 2.5, 3.0]])
    fig, axs = plt.subplots(2, 1, figsize=(6, 6.5), sharex=True)
    for ax, (lab, m) in zip(axs, CASES.items()):
        f = -velocity_friction_creep_force_normalised(chi, m, KAPPA)
        ax.plot(np.r_[0, chi], np.r_[0, f], "k-", label="creep curve (5.16)")
        ax.plot(chi, (1 - m) / (1 + KAPPA * chi) + m, "k--", lw=0.8,
                label=r"$\mu(\xi)/\mu_0$")
        ax.plot(chi, _carter(chi), "k:", lw=0.8, label=r"Carter $\mu_0$, $\mu_k$")
        ax.plot(chi, _carter(chi, m), "k:", lw=0.8)
        if m < 1:
            cp, fp = velocity_friction_peak_normalised(m, KAPPA)
            ax.plot([cp], [fp], "ko", ms=4, label=f"maximum at $\\xi/\\xi_{{c0}}$ = {cp:.3f}")
        ax.set_title(f"({lab}) $\\mu_k = {m}\\mu_0$, $\\kappa\\xi_{{c0}} = {KAPPA:g}$")
        ax.set_ylabel(r"$|T|/(\mu_0 N)$")
        ax.legend(fontsize=8)
    axs[-1].set_xlabel(r"$|\xi|/\xi_{c0}$")
    fig.suptitle("Fig. 5.4  Creep curves with velocity-dependent friction")
    fig.tight_layout()
    fig.savefig(out / "fig5_4_smooth_law_creep_curves.png", dpi=120)
    plt.close(fig)


def fig_5_5(out):
    chi = 0.4
    x = np.linspace(-1, 1, 801)
    fig, axs = plt.subplots(2, 1, figsize=(6, 6), sharex=True)
    for ax, (lab, m) in zip(axs, CASES.items()):
        sol = solve_velocity_friction_normalised(chi, m, KAPPA, degree=768)
        ax.plot(x, -sol.traction(x), "k-", label="(5.16), Sec. 5.3 iteration")
        ax.plot(x, _carter_q(x, chi), "k--", lw=0.8, label=r"Carter $\mu_0$, $\mu_k$")
        ax.plot(x, _carter_q(x, chi, m), "k--", lw=0.8)
        ax.axvline(1 - 2 * sol.stick_ratio, color="0.6", lw=0.6)
        ax.set_title(f"({lab}) $\\mu_k = {m}\\mu_0$, $\\kappa\\xi_{{c0}} = {KAPPA:g}$, "
                     f"$\\xi/\\xi_{{c0}} = {chi}$")
        ax.set_ylabel(r"$q/(\mu_0 p_0)$")
        ax.legend(fontsize=8)
    axs[-1].set_xlabel(r"$x/a_0$ (leading edge +1)")
    fig.suptitle("Fig. 5.5  Tangential stress with velocity-dependent friction")
    fig.tight_layout()
    fig.savefig(out / "fig5_5_smooth_law_stress.png", dpi=120)
    plt.close(fig)


def fig_7_2(out):
    wr = np.linspace(1e-3, 2.0, 800)
    h = nonsteady_transfer_function_normalised(wr, 1.0, model="johnson")
    hp = nonsteady_transfer_function_normalised(wr, 1.0, model="johnson", variant="printed")
    g = gross_thebing_transfer_function_normalised(wr)
    fig, axs = plt.subplots(2, 1, figsize=(6, 6), sharex=True)
    axs[0].plot(wr, np.abs(h), "k-", label="modified Johnson (derived)")
    axs[0].plot(wr, np.abs(hp), "k:", lw=0.8, label="modified Johnson (7.47)-(7.48) as printed")
    axs[0].plot(wr, np.abs(g), "k--", label="Gross-Thebing (7.57)")
    axs[0].set_ylabel(r"$|\hat T/\hat\xi|\,/\,(a_0^*\pi E/(4(1-\nu^2)))$")
    axs[0].legend(fontsize=8)
    axs[1].plot(wr, np.degrees(np.angle(h)), "k-")
    axs[1].plot(wr, np.degrees(np.angle(g)), "k--")
    axs[1].set_ylabel(r"$\phi_T - \phi_\xi$ [deg]")
    axs[1].set_xlabel(r"$a_0/L$")
    from scipy.special import jn_zeros
    for z in jn_zeros(0, 6) / (2 * np.pi):
        if z < wr[-1]:
            for ax in axs:
                ax.axvline(z, color="0.7", lw=0.6)
    fig.suptitle(r"Fig. 7.2  Non-steady contact, $r_{a_0} = 1$, $b = 20 a_0$ (grey: $J_0(ka_0)=0$)")
    fig.tight_layout()
    fig.savefig(out / "fig7_2_johnson_vs_gross_thebing.png", dpi=120)
    plt.close(fig)


def fig_7_3(out):
    wr = np.linspace(1e-3, 2.0, 600)
    ratios = np.round(np.arange(0.1, 1.0, 0.1), 1)
    for what in ("amplitude", "phase"):
        fig, axs = plt.subplots(3, 3, figsize=(10, 8), sharex=True)
        for ax, r, lab in zip(axs.ravel(), ratios, "ABCDEFGHI"):
            h = nonsteady_transfer_function_normalised(wr, r, model="carter")
            g = gross_thebing_transfer_function_normalised(wr, stick_ratio=r)
            if what == "amplitude":
                ax.plot(wr, np.abs(h), "k-")
                ax.plot(wr, np.abs(g), "k--")
            else:
                ax.plot(wr, np.degrees(np.angle(h)), "k-")
                ax.plot(wr, np.degrees(np.angle(g)), "k--")
            ax.set_title(f"({lab}) $r_{{a_0}} = {r}$", fontsize=9)
        for ax in axs[-1]:
            ax.set_xlabel(r"$a_0/L$")
        axs[1, 0].set_ylabel(r"$|\hat T/\hat\xi|$ normalised" if what == "amplitude"
                             else r"$\phi_T - \phi_\xi$ [deg]")
        fig.suptitle(f"Fig. 7.3  {what}: Carter-based (solid) vs Gross-Thebing with "
                     r"$a_0 \to a_0^*$ (dashed), $b = 20a_0$")
        fig.tight_layout()
        fig.savefig(out / f"fig7_3_carter_vs_gross_thebing_{what}.png", dpi=120)
        plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=None, help="output root (default docs/figures)")
    args = parser.parse_args(argv)
    root = Path(args.out) if args.out else Path(__file__).resolve().parents[1] / "docs" / "figures"
    ch5, ch7 = root / "ch5", root / "ch7"
    ch5.mkdir(parents=True, exist_ok=True)
    ch7.mkdir(parents=True, exist_ok=True)
    for fig in (fig_5_1, fig_5_2, fig_5_3, fig_5_4, fig_5_5):
        fig(ch5)
    for fig in (fig_7_2, fig_7_3):
        fig(ch7)
    print(f"wrote {len(os.listdir(ch5))} figures to {ch5} and {len(os.listdir(ch7))} to {ch7}")


if __name__ == "__main__":
    main()

r"""Brute-force wear per passage on a corrugated rail with the discretised half-space solver.

The validation tools of :mod:`railcontact.wear` (Nielsen Sec. 4.3, Eq. (4.74)): the frictional
work ``|q s|`` of the solver's elements (:mod:`railcontact.reference.halfspace2d`) summed at
material points over the rail positions, quasi-statically (:func:`wear_first_harmonic_reference`)
or from a time-stepped non-steady rolling simulation (:func:`wear_first_harmonic_transient`).
They check the linearised wear coefficients and the exact wear integral of
:mod:`railcontact.wear` (``tests/test_reference_wear_direct.py``, ``docs/wear_finding.md``);
the FMU never calls them.
"""

from __future__ import annotations

import numpy as np

from .._validation import check_range
from .halfspace2d import (solve_normal_2d, solve_quasistatic_corrugated_2d, solve_rolling_2d,
                          solve_transient_rolling_2d)

__all__ = ["wear_first_harmonic_reference", "wear_first_harmonic_transient"]


def _representative_case(a0_over_wavelength, stick_ratio, relative_amplitude, phase):
    """One physical contact (E = 210 GPa, nu = 0.28, R = 0.5 m, mu = 0.3, a0 = 6 mm) for the
    normalised inputs of the brute-force wear studies; the results are normalised back, so the
    choice does not matter. Returns (a0/L, r, eps, E, nu, R, mu, 4(1-nu^2)/(pi E), a0, N, L, k,
    Z_A, Z_B, xi)."""
    ratio = float(check_range("a0_over_wavelength", a0_over_wavelength, "-", 0.0, None,
                              lower_closed=False))
    r = float(check_range("stick_ratio", stick_ratio, "-", 0.0, 1.0, lower_closed=False,
                          upper_closed=False))
    eps = float(check_range("relative_amplitude", relative_amplitude, "-", 0.0, None,
                            lower_closed=False))
    e_mod, nu, big_r, mu = 2.1e11, 0.28, 0.5, 0.3
    comp = 4 * (1 - nu * nu) / (np.pi * e_mod)
    a0 = 0.006
    n_load = a0 * a0 / (2 * big_r * comp)
    lam = a0 / ratio
    k = 2.0 * np.pi / lam
    amp = eps * a0 / (k * big_r)
    za, zb = amp * np.cos(phase), amp * np.sin(phase)
    xi = mu * a0 * (1 - r) / big_r
    return ratio, r, eps, e_mod, nu, big_r, mu, comp, a0, n_load, lam, k, za, zb, xi


def wear_first_harmonic_reference(a0_over_wavelength, stick_ratio, relative_amplitude, *,
                                  phase=0.0, n_positions=16, n_elements=200,
                                  domain_half_width=1.6):
    r"""Brute-force wear first harmonic with the discretised half-space solver (reference check).

    At ``n_positions`` axis positions per wave length the normal and the steady-rolling
    tangential problems are solved by :mod:`railcontact.reference.halfspace2d`
    (``n_elements`` on ``[-domain_half_width a0, domain_half_width a0]`` around the axis, gap
    ``xb^2/(2R) - Z2(X_c + xb)``, constant creepage ``mu (a0 - a0*)/R``). The frictional work
    ``|q s|`` of every element is then integrated

    * at material points (4.74): ``int W e^{-ikX0} dX0 = K sum_c dX_c sum_j dx |q s|_j
      e^{-ik(X_c + xb_j)}`` (no derivative of anything is needed), and
    * over the patch coordinate: the same with the weight ``1 + Delta'(X_c)``, Delta from the
      solver's contact edges, differentiated spectrally over the positions.

    Parameters
    ----------
    a0_over_wavelength, stick_ratio, relative_amplitude, phase
        As in :func:`railcontact.wear.wear_first_harmonic_exact`.
    n_positions : int
        Rail positions per wave length (>= 4). [-]
    n_elements : int
        Elements of the reference solver. [-]
    domain_half_width : float
        Solver domain half-width in units of a0. [-]

    Returns
    -------
    dict
        ``{"material_point": w, "patch_coordinate": w, "half_width": c_a/(kR),
        "patch_shift": c_Delta/(kR), "stick_half_width": c_a*/(kR)}``, first harmonics
        normalised as in :func:`railcontact.wear.wear_coefficients` and :mod:`railcontact.corrugation`.
    """
    (ratio, r, eps, e_mod, nu, big_r, mu, comp, a0, n_load, lam, k, za, zb,
     xi) = _representative_case(a0_over_wavelength, stick_ratio, relative_amplitude, phase)
    npos = int(check_range("n_positions", n_positions, "-", 4, 100000))
    xc = np.arange(npos) * lam / npos
    first, a_s, d_s, as_s = [], [], [], []
    hw = domain_half_width * a0
    for xcv in xc:
        def gap(xb, xcv=xcv):
            arg = k * (xcv + xb)
            return xb * xb / (2 * big_r) - (za * np.cos(arg) + zb * np.sin(arg))
        nsol = solve_normal_2d(gap, n_load, e_mod, nu, -hw, hw, n_elements)
        rsol = solve_rolling_2d(nsol.x, nsol.pressure, e_mod, nu, creepage=-xi, friction=mu)
        dens = np.abs(rsol.traction * rsol.slip)
        first.append(np.sum(dens * np.exp(-1j * k * (xcv + nsol.x))) * nsol.element_width)
        a_s.append(0.5 * (nsol.contact_end - nsol.contact_start))
        d_s.append(0.5 * (nsol.contact_end + nsol.contact_start))
        as_s.append(0.5 * (rsol.stick_end - rsol.stick_start))
    first = np.asarray(first)
    d_s = np.asarray(d_s)
    kk = np.fft.fftfreq(npos, d=lam / npos) * 2.0 * np.pi
    d_prime = np.real(np.fft.ifft(1j * kk * np.fft.fft(d_s)))
    zeta = za - 1j * zb
    scale = n_load / a0                            # K mu^2 N / a0 with K = 1 ... times mu^2
    out = {}
    for name, weight in (("material_point", 1.0), ("patch_coordinate", 1.0 + d_prime)):
        f1 = np.mean(weight * first)
        out[name] = np.conj(2 * f1 / zeta) / (mu * mu * scale)

    def harmonic(vals):
        h = 2 * np.mean(np.asarray(vals) * np.exp(-1j * k * xc)) / zeta
        return np.conj(h) / (k * big_r)

    out["half_width"] = harmonic(a_s)
    out["patch_shift"] = harmonic(d_s)
    out["stick_half_width"] = harmonic(as_s)
    return out


def wear_first_harmonic_transient(a0_over_wavelength, stick_ratio, relative_amplitude, *,
                                  phase=0.0, n_elements=200, domain_half_width=1.6,
                                  reference_length_over_a0=10.0, n_periods=1, run_in=6.0):
    r"""Wear first harmonic from a *transient* (non-steady) rolling simulation (study tool).

    Beyond the thesis' quasi-static model: the wheel axis advances one element width per time
    step over the corrugated rail; the pressure of every step is the quasi-static normal
    solution there, and the tangential problem is time-stepped with the ``du/dt`` term of (2.16)
    by :func:`railcontact.reference.halfspace2d.solve_transient_rolling_2d` (so the patch's
    motion relative to the material, the dwell, and the memory of the traction are all in).
    The frictional work ``|q s|`` is then summed at material points, as (4.74) says. After a
    run-in of one contact length, ``n_periods`` wave lengths are analysed.

    Parameters
    ----------
    a0_over_wavelength, stick_ratio, relative_amplitude, phase
        As in :func:`railcontact.wear.wear_first_harmonic_exact`.
    n_elements : int
        Elements of the solver grid (axis frame). [-]
    domain_half_width : float
        Grid half-width in units of a0. [-]
    reference_length_over_a0 : float
        Datum of the 2-D log kernel (the non-steady 2-D problem depends on it, Nielsen after
        (2.46) and Ch. 7), in units of a0. [-]
    n_periods : int
        Wave lengths analysed. [-]
    run_in : float
        Run-in before the analysis, in grid lengths (the time stepping approaches the steady
        state only slowly when the datum is large). [-]

    Returns
    -------
    dict
        ``{"material_point": w, "mean": W0 R / (K mu^2 N a0)}``, normalised as in
        :func:`railcontact.wear.wear_first_harmonic_exact` (the mean is (1 - r)^2 (1 + r) for Carter). [-]
    """
    (ratio, r, eps, e_mod, nu, big_r, mu, comp, a0, n_load, lam, k, za, zb,
     xi) = _representative_case(a0_over_wavelength, stick_ratio, relative_amplitude, phase)
    hw = domain_half_width * a0
    dx = 2 * hw / n_elements
    per_period = int(round(lam / dx))
    dx_rail = lam / per_period                   # rail step = grid spacing (adjusted)
    hw = 0.5 * n_elements * dx_rail
    run_in = int(np.ceil(run_in * 2 * hw / dx_rail)) + 1
    steps = run_in + n_periods * per_period
    xc = np.arange(steps) * dx_rail - run_in * dx_rail
    qs = solve_quasistatic_corrugated_2d(
        xc, lambda xr: za * np.cos(k * xr) + zb * np.sin(k * xr), big_r, n_load, e_mod, nu,
        -hw, hw, n_elements)
    tr = solve_transient_rolling_2d(qs.x, qs.pressure, e_mod, nu,
                                    creepage=np.full(steps, -xi), friction=mu,
                                    reference_length=reference_length_over_a0 * a0)
    dens = np.abs(tr.traction * tr.slip)[run_in:]
    xcs = xc[run_in:]
    first = np.sum(dens * np.exp(-1j * k * (xcs[:, None] + qs.x[None, :]))) * dx_rail * dx_rail
    first = first / (n_periods * lam)
    zeta = za - 1j * zb
    mean = np.sum(dens) * dx_rail * dx_rail / (n_periods * lam) / (mu * mu * n_load)
    return {"material_point": np.conj(2 * first / zeta) / (mu * mu * n_load / a0),
            "mean": float(mean * big_r / a0)}

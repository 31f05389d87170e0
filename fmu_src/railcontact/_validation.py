"""One range-check helper for every public function of :mod:`railcontact`.

Every public function validates its inputs through :func:`check_range`, so the error messages
have one form::

    poisson_ratio must be in [0, 0.5) [-]; got 0.6

The message names the parameter, its allowed range, its unit and the (first) offending value.
NaN and inf are always rejected.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["check_range", "check_choice", "check_contact_inputs", "check_creep_inputs",
           "check_corrugated_contact_inputs", "load_underflows", "check_load_not_underflowing"]


def _fmt(value) -> str:
    return f"{value:g}" if isinstance(value, (int, float, np.floating, np.integer)) else str(value)


def check_range(name, value, unit, lower=None, upper=None, *, lower_closed=True,
                upper_closed=True, condition=None):
    """Return ``value`` as a float ndarray after checking it lies in a range.

    Parameters
    ----------
    name : str
        Parameter name as the user passed it (snake_case API name).
    value : array_like
        Value(s) to check.
    unit : str
        Unit shown in the message, e.g. ``"N"``, ``"-"``, ``"1/m"``.
    lower, upper : float or None
        Bounds; ``None`` means unbounded on that side.
    lower_closed, upper_closed : bool
        Whether the bound itself is allowed.
    condition : str, optional
        Name of the validity condition of an approximation (e.g. ``"Eq. (4.2): no loss of
        contact"``), appended to the message.

    Returns
    -------
    ndarray
        ``np.asarray(value, dtype=float)``.

    Raises
    ------
    ValueError
        ``"<name> must be in <range> [<unit>]; got <value>"`` for the first offending element,
        including NaN and inf.
    """
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a real number [{unit}]; got {value!r}") from exc
    ok = np.isfinite(arr)
    if lower is not None:
        ok &= (arr >= lower) if lower_closed else (arr > lower)
    if upper is not None:
        ok &= (arr <= upper) if upper_closed else (arr < upper)
    if not np.all(ok):
        bad = arr[~ok].ravel()[0] if arr.ndim else arr.item()
        lo = "-inf" if lower is None else _fmt(lower)
        hi = "inf" if upper is None else _fmt(upper)
        interval = (("[" if lower_closed and lower is not None else "(") + f"{lo}, {hi}"
                    + ("]" if upper_closed and upper is not None else ")"))
        count = "" if arr.ndim == 0 else f" ({int(np.count_nonzero(~ok))} of {arr.size} values)"
        extra = f" ({condition})" if condition else ""
        raise ValueError(f"{name} must be in {interval} [{unit}]{extra}; got {_fmt(bad)}{count}")
    return arr


def check_choice(name, value, choices):
    """Return ``value`` if it is one of ``choices``, else raise ``ValueError`` naming them."""
    if value not in choices:
        raise ValueError(f"{name} must be one of {sorted(choices)}; got {value!r}")
    return value


def check_contact_inputs(normal_load, a0, b0, youngs_modulus, poisson_ratio,
                         friction_coefficient):
    """The contact inputs every 3-D creep method takes, checked: N, a0, b0, mu >= 0, E > 0,
    nu in [0, 0.5] (0.5: incompressible, for which Kalker tabulates his coefficients). Returns
    them as float arrays in that order."""
    return (check_range("normal_load", normal_load, "N", 0.0, None),
            check_range("a0", a0, "m", 0.0, None),
            check_range("b0", b0, "m", 0.0, None),
            check_range("youngs_modulus", youngs_modulus, "Pa", 0.0, None, lower_closed=False),
            check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5),
            check_range("friction_coefficient", friction_coefficient, "-", 0.0, None))


def check_creep_inputs(creepage_longitudinal, creepage_lateral, spin, normal_load, a0, b0,
                       youngs_modulus, poisson_ratio, friction_coefficient,
                       creepage_bound=None):
    """The inputs of a 3-D creep-force function, checked: finite creepages (within
    ``+-creepage_bound`` if given) and spin, then :func:`check_contact_inputs`. Returns the nine
    as float arrays in that order."""
    bound = (None, None) if creepage_bound is None else (-creepage_bound, creepage_bound)
    return (check_range("creepage_longitudinal", creepage_longitudinal, "-", *bound),
            check_range("creepage_lateral", creepage_lateral, "-", *bound),
            check_range("spin", spin, "1/m"),
            *check_contact_inputs(normal_load, a0, b0, youngs_modulus, poisson_ratio,
                                  friction_coefficient))


def check_corrugated_contact_inputs(normal_load, radius, youngs_modulus, poisson_ratio,
                                    friction_coefficient, creepage, amplitudes_cos,
                                    amplitudes_sin, wavelengths):
    """Range-checked physical inputs of one line contact on a corrugated rail (Nielsen Ch. 4:
    :func:`railcontact.corrugation.corrugated_contact`, :func:`~railcontact.corrugation.
    contact_distributions`, :func:`railcontact.wear.corrugated_wear_depth`): N, R, E, mu > 0,
    nu in [0, 0.5), finite creepage, harmonics 1-D of equal length with wavelengths > 0.
    Returns ``N, R, E, nu, mu`` (floats), ``|creepage|`` and the three harmonic arrays."""
    n_load = float(check_range("normal_load", normal_load, "N/m", 0.0, None, lower_closed=False))
    big_r = float(check_range("radius", radius, "m", 0.0, None, lower_closed=False))
    e_mod = float(check_range("youngs_modulus", youngs_modulus, "Pa", 0.0, None,
                              lower_closed=False))
    nu = float(check_range("poisson_ratio", poisson_ratio, "-", 0.0, 0.5, upper_closed=False))
    mu = float(check_range("friction_coefficient", friction_coefficient, "-", 0.0, None,
                           lower_closed=False))
    xi = abs(float(check_range("creepage", creepage, "-")))
    za = np.atleast_1d(check_range("amplitudes_cos", amplitudes_cos, "m"))
    zb = np.atleast_1d(check_range("amplitudes_sin", amplitudes_sin, "m"))
    lam = np.atleast_1d(check_range("wavelengths", wavelengths, "m", 0.0, None,
                                    lower_closed=False))
    if not (za.shape == zb.shape == lam.shape) or za.ndim != 1:
        raise ValueError("amplitudes_cos, amplitudes_sin, wavelengths must be 1-D of equal "
                         f"length [m]; got shapes {za.shape}, {zb.shape}, {lam.shape}")
    return n_load, big_r, e_mod, nu, mu, xi, za, zb, lam


_TINY = 2.2250738585072014e-308   # smallest normal double


def load_underflows(n_load, e_mod, nu):
    """True if the normalised load ``8 (1 - nu^2) N / (pi E)`` of a line contact is below the
    smallest normal double (or not a number): the condition :func:`check_load_not_underflowing`
    rejects and the FMU's line-contact effects treat as no contact."""
    return not 8.0 * (1.0 - nu * nu) * n_load / (math.pi * e_mod) >= _TINY


def check_load_not_underflowing(n_load, e_mod, nu):
    """Reject a load whose normalised value ``8 (1 - nu^2) N / (pi E)`` (the text after
    Nielsen (6.10); ``a0^2 / R``) is below the smallest normal double: ``a0`` and ``a0*/a0``
    would underflow or lose their precision (at 5e-324 N/m ``a0 = 0`` and ``a0*/a0`` divides
    by zero). The same limit as :func:`railcontact.roughness.rough_rail_contact`; the FMU's
    effects treat such a load as no contact."""
    if load_underflows(n_load, e_mod, nu):
        raise ValueError("normal_load must be > 0 with a normalised load 8 (1 - nu^2) N / (pi E) "
                         "of at least 2.2e-308 m (below it is subnormal or zero: a0 loses its "
                         f"precision or underflows; no contact) [N/m]; got {n_load:g}")

"""Overflow-safe products, quotients and roots: values carried as (mantissa, exponent).

Every quantity of the contact theories is a product or quotient of the inputs (w = C xi,
w_sat ~ mu N / (a0 b0 E), Hertz's a0 ~ (N R / E)^(1/3), ...). With inputs anywhere in the
float range such a product overflows or underflows although the result it leads to (a force
bounded by mu N, a ratio) does not. Here a value is carried as x = m 2^e (np.frexp:
0.5 <= |m| < 1 or m = 0, integer e): multiplying and dividing mantissas and adding exponents
has the same rounding as the plain left-to-right expression (scaling by a power of two is
exact), so the results equal the plain expressions bit for bit wherever those stay in the
normal range. Only the final value is rounded into the float range (:func:`value`: inf or 0
where it really is out of range; the callers turn an infinite result into a ValueError).
"""

from __future__ import annotations

import numpy as np

TINY_SUBNORMAL = float(np.nextafter(0.0, 1.0))
NO_EXP = -(2**40)          # exponent of an exact zero (below every other)


def scaled(factors, divisors=()):
    """prod(factors) / prod(divisors), evaluated left to right, as (m, e) with
    0.5 <= |m| < 1 (or m = 0); an item may itself be an (m, e) pair. No divisor may be 0.

    The mantissas carry the same rounding as the plain left-to-right expression (scaling by
    powers of two is exact), so the result equals it bit for bit wherever that expression
    stays in the normal range."""
    m, e = 1.0, np.int64(0)
    for items, sign in ((factors, 1), (divisors, -1)):
        for f in items:
            if isinstance(f, tuple):
                fm, fe = f
            else:
                fm, fe = np.frexp(f)
            m = m * fm if sign > 0 else m / fm
            m, de = np.frexp(m)
            e = e + de.astype(np.int64) + sign * np.asarray(fe).astype(np.int64)
    return m, np.where(m == 0.0, NO_EXP, e)


def value(m, e):
    """m 2^e rounded into the float range (inf on overflow, 0 on underflow, sign kept)."""
    with np.errstate(over="ignore", under="ignore"):
        return np.ldexp(m, np.clip(e, -4000, 4000).astype(np.int32))



def hypot_scaled(x, y):
    """hypot(x, y) as (m, e) (see scaled), without overflow for any finite x, y; x and y may
    be (m, e) pairs."""
    mx, ex = x if isinstance(x, tuple) else scaled((x,))
    my, ey = y if isinstance(y, tuple) else scaled((y,))
    top = np.maximum(ex, ey)
    top = np.where(top == NO_EXP, 0, top)
    h = np.hypot(value(mx, ex - top), value(my, ey - top))
    m, e = np.frexp(h)
    return m, np.where(m == 0.0, NO_EXP, top + e.astype(np.int64))


def root_ab(a0, b0):
    """sqrt(a0 b0) as (m, e): ``np.sqrt(a0 * b0)`` (the scalar paths' rounding) where a0 b0 is
    a normal float, sqrt(a0) sqrt(b0) where it would overflow or underflow."""
    with np.errstate(over="ignore", under="ignore"):
        ab = a0 * b0
    ok = (ab >= np.finfo(float).tiny) & (ab < np.inf)
    return scaled((np.where(ok, np.sqrt(np.where(ok, ab, 1.0)), np.sqrt(a0)),
                    np.where(ok, 1.0, np.sqrt(b0))))


def root(pair, n):
    """The real n-th root (n = 2 or 3) of m 2^e >= 0, as a float (inf/0 outside the range):
    ``np.sqrt`` / ``np.cbrt`` of the mantissa times an exact power of two."""
    m, e = pair
    e = np.where(m == 0.0, 0, e)
    r = np.mod(e, n)
    base = np.sqrt if n == 2 else np.cbrt
    return value(base(np.ldexp(m, r.astype(np.int32))), (e - r) // n)


def overflow_error(what, unit, values, names):
    """ValueError for the first non-finite element of ``values`` (a result that overflows the
    float range), naming the inputs that produce it (``names``: name -> array)."""
    bad = ~np.isfinite(values)
    arrays = np.broadcast_arrays(values, *names.values())
    i = np.flatnonzero(np.broadcast_to(bad, arrays[0].shape))[0]
    at = ", ".join(f"{n} = {a.flat[i]:g}" for n, a in zip(names, arrays[1:]))
    return ValueError(f"{what} must be in [0, {np.finfo(float).max:g}] [{unit}]; got inf "
                      f"(overflow at {at})")


def finite_or_scaled(plain, scaled, exact_zero):
    """``plain`` where it is a normal finite float (or 0 where ``exact_zero``: a zero factor),
    else ``scaled()`` there (the overflow-safe evaluation, computed only if needed): plain
    results stay bit for bit."""
    plain = np.asarray(plain, dtype=float)
    ok = np.isfinite(plain) & (((plain == 0.0) & exact_zero)
                               | (np.abs(plain) >= np.finfo(float).tiny))
    if np.all(ok):
        return plain
    return np.where(ok, plain, scaled())


#: Magnitudes the plain float arithmetic of the scalar paths handles without overflow or
#: underflow in its intermediates; other values take the (mantissa, exponent) array paths.
MODERATE_MIN, MODERATE_MAX = 1e-50, 1e50


def moderate(*values, _lo=MODERATE_MIN, _hi=MODERATE_MAX):
    """True if every value is 0 or of magnitude in [1e-50, 1e50] (False for NaN, inf)."""
    for v in values:
        if v != 0.0 and not _lo <= abs(v) <= _hi:
            return False
    return True

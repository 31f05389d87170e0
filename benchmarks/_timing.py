"""Shared timing helper of the benchmarks: median of repeats, single call and batch, same run.

Absolute times on a shared machine are noisy (other processes); the *median* of several
repeats is robust against a few slow outliers, and ratios of times measured in the same run
are what a comparison should use.
"""

from __future__ import annotations

import math
import statistics
import time

__all__ = ["median_time", "per_call", "per_point"]


def median_time(func, repeat=5, number=1, warmup=1, budget=None):
    """Median wall time of ``number`` calls of ``func()``, over ``repeat`` repeats. [s]

    Parameters
    ----------
    func : callable
        Called without arguments.
    repeat : int
        Number of timed repeats (the median is returned). [-]
    number : int
        Calls per repeat (the time of one repeat is divided by it). [-]
    warmup : int
        Untimed calls first (caches, numba dispatch, spline construction). [-]
    budget : float, optional
        Stop repeating once this much time has been spent (at least one repeat is made). [s]

    Returns
    -------
    float
        Median time per call. [s]
    """
    for _ in range(warmup):
        func()
    times = []
    start = time.perf_counter()
    for _ in range(max(1, int(repeat))):
        t0 = time.perf_counter()
        for _ in range(number):
            func()
        times.append((time.perf_counter() - t0) / number)
        if budget is not None and time.perf_counter() - start > budget:
            break
    return statistics.median(times)


def per_call(func, target=0.05, repeat=5, budget=2.0):
    """Median time of one call, with ``number`` chosen so one repeat lasts about ``target``. [s]

    The first (warm-up) call also calibrates ``number``.
    """
    t0 = time.perf_counter()
    func()
    first = max(time.perf_counter() - t0, 1e-9)
    number = max(1, min(100_000, int(math.ceil(target / first))))
    return median_time(func, repeat=repeat, number=number, warmup=0, budget=budget)


def per_point(func, n_points, repeat=3, budget=5.0):
    """Median time of one batch call divided by its number of points. [s per point]"""
    return median_time(func, repeat=repeat, number=1, warmup=1, budget=budget) / n_points

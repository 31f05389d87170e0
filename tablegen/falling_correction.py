"""The falling-friction correction table: Kalker's exact theory with the smooth law (5.16)
minus the package's fast model on the Coulomb exact table, over the law's normalised
parameters (issue 38; read by :mod:`railcontact.falling_table`).

    python -m tablegen.falling_correction build [--workers 2] [--workdir DIR] [--output F]
    python -m tablegen.falling_correction recover [--source F] [--workdir DIR]
    python -m tablegen.falling_correction build --law polach [--partial-from F] ...

``--law polach`` (since 2026-11-30) builds the table of Polach's exponential law (2005,
:data:`LAW_FAMILIES`) in its own work directory, file ``falling_correction_polach.nc``: solved
at theta every 30 degrees (:data:`THETA_NODES`), with one s node more, 0.375
(:data:`CREEPAGE_NODES_ADDED`), and one mu_k/mu_0 node more, 0.45
(:data:`FRICTION_RATIO_NODES_ADDED`), and written on the smooth law's table (``--base``,
default ``--partial-from``, else the package's): its difference to that table, interpolated
along theta onto the smooth table's nodes and added to it (at the added s node, to the
smooth table's spline along s, at the added mu_k/mu_0 node to its line along mu_k/mu_0;
:func:`on_base`); 0 where not solved yet, so that a partial table (``--partial-from`` the
smooth law's table: solves nothing) is the smooth table there, the reader's fallback for
Polach's law before its own table, flagged ``source_node``; an unconverged node the ladder
has not reached yet is filled from its neighbours. 2026-11-30: about 3 h of exact solves on
2 cores for every node, 73 min more for the node 0.45 (its rows copied from the work
directory before with the node pending, :func:`_pending`, as ``recover`` writes them, which
does not take a family's file); the ladder, 1-500 s an (ln(a0/b0), nu) block, done at tau
0-0.75 and in part at 1-2.5.

The shipped file is the package data ``fmu_src/railcontact/data/falling_correction.nc``
(``--output`` that path to replace it; default ``./tables-build/falling_correction.nc``). It is
not one of the shipped ``tables/``: two of its axes are linear (nu and mu_k/mu_0, a material's
and a law's constants, with 2 and 3 nodes), where the tables' format, which the C and Fortran
readers take, is cubic along every axis. About 4.5 h of exact solves on 2 cores (2026-11-28:
65 min for 13 tau nodes, 20 min for the two added later, 37 min for the nu node 0.25;
2026-11-29: 40 min for five more tau nodes, 33 min for the ln(a0/b0) node; 2026-11-29: 45
and 37 min for the ln(a0/b0) nodes 0.25 and 0.75 ln 5), most of it the
cases of the most strongly falling laws that the exact solver does not converge on (each runs
to its iteration limit), then the ladder at the nodes that did not converge (:func:`ladder_point`;
2026-11-29: 80 min on 2 cores for those of tau <= 2, 2,432 nodes, 2,011 of them estimated;
some 95 min for those of tau 2.25-5.5, 2,406 nodes, 1,988 estimated; the 1,266 of larger tau
not yet), then seconds for the model at the nodes.

What is tabulated, at every node of (ln(a0/b0), nu, s, theta, tau, mu_k/mu_0, kappa mu_0 p0/G)
(the exact table's coordinates of :func:`railcontact.exact_table.exact_table_coordinates`,
at the law's mu_0, and the law's two numbers):

* ``(T_exact - T_model) / (mu_0 N)`` for T_x and T_y, and ``(M_exact - M_model) /
  (mu_0 N sqrt(a0 b0))`` for the spin moment, where ``T_exact`` is
  ``creep_solution_3d(..., SmoothFriction(mu_0, mu_k, kappa), method="exact")`` (the public
  default grid) and ``T_model`` is :func:`railcontact.falling_table.falling_friction_table`
  (uncorrected) on the same inputs of the reference contact
  (:data:`railcontact.creep3d.REFERENCE_CONTACT`, as the Coulomb table).

Only the nodes that are not known are solved: mu_k/mu_0 = 1 and kappa = 0 are Coulomb
friction, where the model is the Coulomb table (its correction is taken as 0: the table is
within 0.3 % of the exact theory); s = 1 is infinite creepage (full sliding without spin's
share: the model's limit is exact, 0); at s = 0 theta is void (one solve per theta row);
negative tau are the mirror images (y -> -y: theta -> -theta, tau -> -tau, T_y and M_z change
sign), made by the reader. A case the exact solver does not converge on is stored as NaN and
filled when the spline is fitted (:func:`railcontact.falling_table._filled`: along theta,
then the line along the kappa number, then the line along mu_k/mu_0; the table records how
many).

Resumable, in three stages under the work directory (``<workdir>/falling_correction-<hash>/``),
each file saved as soon as it is done; running the same command again computes only what is
missing:

1. the exact solves (the hours): each (ln(a0/b0), nu, tau, s) row of nodes (every theta,
   mu_k/mu_0 and kappa number) is one chunk ``exact_g<ln(a0/b0)>_<i_nu>_tau<tau>_s<s>.npy``,
   a (ln(a0/b0), nu, tau) block's missing rows one job. The hash covers the solver and the
   nodes of every axis but :data:`CHUNK_AXES` (ln(a0/b0), tau and s); a chunk's file is
   named by those three nodes' values, so that a node of any of them added to :data:`NODES`
   costs only its own solves (since 2026-11-29: the chunks were first named by the index of
   their ln(a0/b0) node, then by (ln(a0/b0), nu, tau) blocks of every s; each time they were
   copied or split to the new names, the values unchanged; the tau node 0.75 then took
   2.5 min on 2 cores, the s node 0.05 50 min (its second half with its nodes between two
   unconverged ones were not
   tried, :func:`_between_unconverged`)). A node added along an axis within the rows
   (:data:`ROW_AXES`: theta, mu_k/mu_0, the kappa number; since 2026-11-29) changes the hash:
   ``recover`` from the file of the nodes before writes the new work directory's rows with
   the new nodes pending (``pending_<row file>``), and the build solves those only (a new
   theta node between two unconverged ones is not tried, as along s; the ladder tries it);
2. the ladder (since 2026-11-29, :func:`ladder_point`): at the nodes of step 1 that did not
   converge, of tau <= :data:`LADDER_TAU_MAX`, the exact theory on a ladder of coarser grids
   extrapolated to zero element size, one file ``ladder<tag>_exact_...npy`` per row of
   step 1 (the tag names the ladder's grids); a node whose ladder converges is stored as
   the exact theory's value and flagged in the file (``ladder_node``); ``recover`` brings
   these back into the ladder's files. Measured: see :data:`LADDER_GRIDS`;
3. the model at the nodes (7-11 s for the whole command on 2 cores, 2026-11-28, since the
   model keeps the table's spin coordinate on its axis,
   :func:`railcontact.falling_table.spin_floor`; 30 min before, when the nodes of large
   spin and low mu_e took the exact solver beyond that axis), one file per tau node named
   by the ln(a0/b0) nodes and the model's hash (the code of
   :func:`railcontact.falling_table.falling_friction_table`, ``spin_floor`` and ``table_mu``
   and the module's constants): a changed model costs this stage only, not the exact solves.

The table is the difference of the two. (The shipped file's exact solves were made by an
earlier builder that kept the difference to the model of the time; they were recovered as
that difference plus that model at the nodes, 2026-11-28; the nu node 0.25 was solved
afresh.)
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import os
import sys
import time
import warnings
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

import numpy as np

__all__ = ["NODES", "AXES", "CHUNK_AXES", "exact_row", "model_points", "build"]

#: Nodes of the computed grid (tau >= 0; the reader mirrors tau < 0). Along s the creepage
#: coordinate (2/pi) atan(rho / w), denser at small s, where spin dominates and the model's
#: error is largest; tau graded where the spin's force develops (the model's error rises there
#: within 0.5 of tau: the example in the docstring of railcontact.falling_table); 1.25
#: and 1.75 added after a first build: pure spin with a strongly falling law jumps from 1 % to
#: 13 % of mu_0 N between tau 1.25 and 1.75; 1.125, 1.375, 1.625, 1.875 and 2.25 added
#: 2026-11-29 (that rise sits between tau 1.3 and 2.1 as a0/b0 and the law vary, some 0.4
#: wide: the spline along tau missed by up to 0.8 % across it with nodes 0.25 apart);
#: kappa in squares (the correction rises fast from kappa = 0); ln(a0/b0) = -0.75 ln 5
#: (a0/b0 0.30) added 2026-11-29: with large spin the correction changes from 2 % to 7-9 % of
#: mu_0 N between a0/b0 0.2 and 0.45, and the spline along ln(a0/b0) missed a random case
#: (seed 20's case 98, pure spin, a0/b0 0.26, tau -2.9) by 2.2 % (0.31 % with the node). Its
#: mirror node 0.75 ln 5 (a0/b0 3.34, solved too) gained nothing over 7,482 random cases
#: (seeds 11-60: within 1 % 7,463 against 7,464 without it, max 2.12 against 2.20 %) and took
#: a case beside the unconverged nodes (seed 14's case 7) from 0.19 to 1.52 %: left out.
#: tau = 0.75 added 2026-11-29 with the model's blend with spin
#: (railcontact.falling_table.SPIN_BLEND, tau 0.75-1.25): the nodes 0.5 and 1 apart missed a
#: case inside the blend by 1.33 % (1.03 % with the node). s = 0.05 added 2026-11-29 too: the
#: spline along s between 0 and 0.1 with spin missed by up to 1.6 % of mu_0 N at s 0.04
#: (seeds 11-40: 4,483 within 1 % against 4,481 without it; seeds 41-60 max 1.31 against
#: 1.83 %; seed 14's case 7, beside unconverged nodes, 0.17 against 1.005 %). ln(a0/b0) =
#: 0.25 ln 5 and 0.75 ln 5 (a0/b0 1.50 and 3.34) added 2026-11-29, 45 and 37 min on 2 cores
#: (recovered first from the shipped file: ``recover``): in the region where the stick zone
#: collapses with spin under a strong law (benchmarks/bench_falling_friction_3d.py --region
#: collapse --n 300 --seeds 101-102) half the misses were the spline along ln(a0/b0) (near
#: pure spin at tau about 2, benchmarks/diagnose_falling_misses.py; a0/b0 1 has unconverged
#: nodes there); with both nodes 581 of 587 within 1 % (575 before), max 2.40 % (2.52),
#: RMS 0.27 % (0.33); seeds 11-40 4,487 of 4,491 (4,483), max 1.32 % (1.37); seeds 41-60
#: 2,989 of 2,991 (the same), max 1.33 % (1.31); Polach's law, seeds 11-20, 1,467 of 1,493
#: (1,466), max 1.90 % (1.95). The node 0.25 ln 5 alone: 581, 4,486, 2,989, 1,468; max
#: 2.43, 1.33, 1.34, 1.90 %. (The node 3.34 alone, solved 2026-11-29 with the earlier model
#: and again with the blend, had gained nothing: see above.) Theta every 15 degrees (was 30)
#: since 2026-11-29: with spin the correction swings along theta faster than a cubic through
#: nodes 30 degrees apart follows (at the new nodes, a spline through the old ones missed by
#: up to 1.5-2.0 % of mu_0 N at tau 1.125-1.25, 0.1 % at tau 0); solved so far at tau <= 7.5
#: (the rest of the new nodes, and the 6,168 the default grid did not converge on, waiting
#: for the ladder, are the 30-degree table's spline there, flagged source_node: a partial
#: build, see :func:`build`). Collapse region 591 of 591 within 1 % (589), max 0.91 % (1.79);
#: seeds 11-40 4,489 (4,487), 1.02 % (1.32); seeds 41-60 2,991 (2,990), 1.08 % (1.08);
#: Polach's law 1,473 (1,471), 1.80 % (1.90).
NODES = {
    "log_aspect_ratio": np.log(5.0) * np.array([-1.0, -0.75, -0.5, 0.0, 0.25, 0.5, 0.75, 1.0]),
    "poisson_ratio": np.array([0.0, 0.25, 0.5]),
    "creepage_coordinate": np.array([0.0, 0.05, 0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0]),
    "creepage_angle": np.linspace(-np.pi, np.pi, 25)[:-1],
    "spin_coordinate": np.array([0.0, 0.5, 0.75, 1.0, 1.125, 1.25, 1.375, 1.5, 1.625, 1.75, 1.875,
                                 2.0, 2.25, 2.5, 3.0, 4.0, 5.5, 7.5, 10.0, 14.0, 20.0]),
    "friction_ratio": np.array([0.3, 0.65, 1.0]),
    "friction_decay_number": np.array([0.0, 0.125, 0.5, 1.125, 2.0]),
}
from railcontact.falling_table import CORRECTION_AXES as AXES  # noqa: E402
from railcontact.falling_table import CORRECTION_VARIABLES as VARIABLES  # noqa: E402

assert tuple(NODES) == AXES
SOLVER = "creep_solution_3d(method='exact'), default grid"

#: The law families a table is built for (``--law``): the smooth law (5.16)
#: ``mu_0 (m + (1 - m) / (1 + kappa s))`` and Polach's ``mu_0 (m + (1 - m) exp(-kappa s))``
#: (2005; ``A = m``, ``B V = kappa``, in the slip s = w / V), both with the table's two
#: numbers ``m = mu_k / mu_0`` and the kappa number ``kappa mu_0 p0 / G``: the same slope at
#: zero slip. Each family is its own work directory (the smooth one's hash as before) and file.
LAW_FAMILIES = ("smooth", "polach")
#: The family being built (set by :func:`set_law_family`).
LAW_FAMILY = "smooth"
#: Rolling speed of Polach's law in the builder's exact solves (its ``B = kappa / V``): the
#: law in the slip does not depend on it. [m/s]
POLACH_BUILD_SPEED = 1.0


#: Creepage-angle nodes of each family's table: the smooth law's every 15 degrees; Polach's
#: every 30 degrees (2026-11-30: its first build, half the solves; the smooth law's table
#: with nodes 30 degrees apart was within 1 % of mu_0 N on 4,487 of 4,491 random cases, max
#: 1.32 %, against 4,489 and 1.02 % every 15 degrees).
THETA_NODES = {"smooth": 24, "polach": 12}
#: Creepage-coordinate nodes a family's table has beyond :data:`NODES`': Polach's s = 0.375
#: (2026-11-30: at tau = 0 its table missed Kalker's exact theory by up to 1.27 % of mu_0 N
#: where a strongly falling law's creep curve peaks between the nodes 0.3 and 0.45). The s
#: axis names the chunks, so an added node reuses every chunk solved before.
CREEPAGE_NODES_ADDED = {"smooth": (), "polach": (0.375,)}
#: mu_k/mu_0 nodes a family's table has beyond :data:`NODES`': Polach's 0.45 (2026-11-30: the
#: reader is linear along mu_k/mu_0, and between the nodes 0.3 and 0.65 the exact correction
#: is not: with large spin it falls steeply just above 0.3, where the solver stops converging,
#: and is nearly flat from 0.4 up; at ln(a0/b0) 0, nu 0, pure spin, tau 2.25, kappa number
#: 1.125 it is -0.31 / 0.08 / 0.24 / 0.46 / 0.73 / 0.80 % of mu_0 N at mu_k/mu_0 0.3 (the
#: ladder) / 0.32 / 0.35 / 0.4 / 0.5 / 0.65, the line between the nodes missing 0.5 by
#: 0.41 %; both of the table's misses over 1 % on seeds 11-50 were pure spin at mu_k/mu_0
#: 0.50-0.51). A row axis: the node changes the work directory's hash.
FRICTION_RATIO_NODES_ADDED = {"smooth": (), "polach": (0.45,)}


def set_law_family(family):
    """Build the table of ``family`` (:data:`LAW_FAMILIES`) from now on in this process (its
    work directory, file name, law, theta, s and mu_k/mu_0 nodes, :data:`THETA_NODES`,
    :data:`CREEPAGE_NODES_ADDED`, :data:`FRICTION_RATIO_NODES_ADDED`)."""
    global LAW_FAMILY
    if family not in LAW_FAMILIES:
        raise ValueError(f"law family must be one of {LAW_FAMILIES}; got {family!r}")
    LAW_FAMILY = family
    NODES["creepage_angle"] = np.linspace(-np.pi, np.pi, THETA_NODES[family] + 1)[:-1]
    for axis, nodes_added in (("creepage_coordinate", CREEPAGE_NODES_ADDED),
                              ("friction_ratio", FRICTION_RATIO_NODES_ADDED)):
        added = np.concatenate([np.asarray(v, dtype=float) for v in nodes_added.values()])
        x = NODES[axis]
        NODES[axis] = np.union1d(x[~np.isin(x, added)], nodes_added[family])


def _law(mu0, mu_k, kappa):
    """The family's law object and the keywords its exact solve needs."""
    from railcontact.friction import PolachFriction, SmoothFriction

    if LAW_FAMILY == "polach":
        return (PolachFriction(mu0, mu_k / mu0, kappa / POLACH_BUILD_SPEED),
                {"rolling_speed": POLACH_BUILD_SPEED})
    return SmoothFriction(mu0, mu_k, kappa), {}


def _law_in_slip(m0, mk, kp):
    """The family's law in the slip s [-], for the model: a function of arrays."""
    if LAW_FAMILY == "polach":
        return lambda slip: (m0 - mk) * np.exp(-kp * np.abs(slip)) + mk
    return lambda slip: (m0 - mk) / (1.0 + kp * np.abs(slip)) + mk


def _case(lg, nu, s, th, tau, m, kn):
    """The inputs on the reference contact of table coordinates (arrays or floats):
    ``(args, mu_0, mu_k, kappa)``."""
    from railcontact.creep3d import REFERENCE_CONTACT
    from railcontact.exact_table import exact_table_inverse

    keys = ("creepage_longitudinal", "creepage_lateral", "spin", "normal_load", "a0", "b0",
            "youngs_modulus", "poisson_ratio", "friction_coefficient")
    ph = exact_table_inverse(lg, nu, s, th, tau, REFERENCE_CONTACT)
    ones = np.ones(np.shape(lg))
    a = [np.asarray(ph[k], dtype=float) * ones for k in keys]
    a = [float(v) for v in a] if not np.ndim(lg) else a
    shear = a[6] / (2.0 * (1.0 + nu))
    p0 = 1.5 * a[3] / (np.pi * a[4] * a[5])
    mu0 = a[8]
    return a, mu0, m * mu0, kn / (mu0 * p0 / shear)


def exact_point(lg, nu, s, th, tau, m, kn, **options):
    """``(T_x, T_y) / (mu_0 N)`` and ``M_z / (mu_0 N sqrt(a0 b0))`` of the exact theory with
    the smooth law at one node; NaN where the exact solver does not converge or the node is
    beyond its domain. ``options``: of ``creep_solution_3d(method="exact")`` (default: its
    default grid)."""
    from railcontact import creep_solution_3d
    from railcontact.errors import RollingConvergenceError

    a, mu0, mu_k, kappa = _case(lg, nu, s, th, tau, m, kn)
    law, kw = _law(mu0, mu_k, kappa)
    try:
        ex = creep_solution_3d(*a[:8], law, method="exact", **kw, **options)
    except (RollingConvergenceError, ValueError):
        return np.full(3, np.nan)
    scale = mu0 * a[3]
    return np.array([ex.tx / scale, ex.ty / scale,
                     ex.spin_moment / (scale * math.sqrt(a[4] * a[5]))])


#: The ladder (since 2026-11-29): at a node where the default grid of ``method="exact"`` does
#: not converge (its two grids of the Richardson step, 30 and 60 elements along x, at two
#: shifts), the exact theory on the grids of these numbers of elements along x (the lateral
#: ones in proportion, as the default's), each the mean of the shifts -1/4 and +1/4, those
#: that converge (at least :data:`LADDER_MIN_GRIDS`) extrapolated to zero element size by a
#: straight line in 1/mx (least squares): the default's own Richardson step, over more and
#: coarser grids. Measured against the default on 30 converged nodes of the falling laws
#: (tau 1-4, 2026-11-29): max 0.16 % of mu_0 N for the forces and 0.35 % for the moment
#: (over mu_0 N sqrt(a0 b0)), RMS 0.03-0.07 %; at the unconverged nodes around seed 101's
#: case 294 of the collapse region it differs from the fill of :func:`_filled` by up to
#: 3.7 % of mu_0 N.
LADDER_GRIDS = (20, 24, 30, 36, 40, 48)
LADDER_MIN_GRIDS = 3
#: The ladder is tried at the unconverged nodes of tau <= this: first tau <= 2, where the stick
#: zone collapses with spin under a strong law (80 min on 2 cores, 2,432 nodes, 2,011
#: estimated), then to 5.5 (2026-11-29: 2,406 nodes, 1,988 estimated, some 95 min on 2
#: cores); the 1,266 unconverged nodes of tau 7.5-20 are left to the fill. At 12 converged
#: nodes of tau 5.5-20 (2026-11-29) the ladder is within 0.28 % of mu_0 N of the default
#: grid (RMS 0.08 / 0.03 / 0.08 % for T_x, T_y, M_z).
LADDER_TAU_MAX = 5.5


def ladder_point(lg, nu, s, th, tau, m, kn):
    """The exact theory with the smooth law at one node by the ladder of grids
    (:data:`LADDER_GRIDS`), normalised as :func:`exact_point`; NaN where fewer than
    :data:`LADDER_MIN_GRIDS` of its grids converge."""
    from railcontact.creep3d import exact_default_grid

    a = _case(lg, nu, s, th, tau, m, kn)[0]
    mx0, my0 = exact_default_grid(a[4], a[5], tau)
    with warnings.catch_warnings():     # (a coarse grid may touch the area's edge)
        warnings.simplefilter("ignore", RuntimeWarning)
        vals = np.array([exact_point(lg, nu, s, th, tau, m, kn,
                                     grid=(mx, max(4, int(round(my0 * mx / mx0)))),
                                     extrapolate=False, grid_shifts=2)
                         for mx in LADDER_GRIDS])
    ok = np.isfinite(vals[:, 0])
    if ok.sum() < LADDER_MIN_GRIDS:
        return np.full(3, np.nan)
    inv = 1.0 / np.asarray(LADDER_GRIDS, dtype=float)[ok]
    design = np.stack([np.ones(inv.size), inv], axis=1)
    return np.linalg.lstsq(design, vals[ok], rcond=None)[0][0]


def _known(m, kn, s):
    """The nodes whose correction is known (0): Coulomb friction and s = 1."""
    return (np.asarray(m) >= 1.0) | (np.asarray(kn) == 0.0) | (np.asarray(s) >= 1.0)


def exact_row(i_g, i_nu, i_tau, i_s, skip=None, todo=None, row=None, point=None):
    """The exact theory on one (ln(a0/b0), nu, tau, s) row of nodes: array (3, n_theta, n_m,
    n_kn) as :func:`exact_point` (0 at the known nodes; at s = 0 one solve for every theta).
    ``skip``: a boolean array (n_theta, n_m, n_kn) of nodes not attempted (NaN, as a node the
    solver does not converge on). ``todo`` (the same shape) and ``row`` (the row so far): only
    the nodes of ``todo`` are computed, the others kept from ``row`` (nodes pending after
    :func:`recover` from a file with fewer nodes along :data:`ROW_AXES`). ``point``: the
    solve at a node (default :func:`exact_point`; the ladder passes :func:`ladder_point`)."""
    warnings.simplefilter("ignore")
    point = point or exact_point
    n = NODES
    lg, nu, tau, s = (n["log_aspect_ratio"][i_g], n["poisson_ratio"][i_nu],
                      n["spin_coordinate"][i_tau], n["creepage_coordinate"][i_s])
    shape = tuple(n[k].size for k in ROW_AXES)
    out = np.zeros((3,) + shape) if row is None else np.array(row, dtype=float)
    todo = np.ones(shape, dtype=bool) if todo is None else todo
    for i_t, i_m, i_k in zip(*np.nonzero(todo)):
        th, m, kn = (n["creepage_angle"][i_t], n["friction_ratio"][i_m],
                     n["friction_decay_number"][i_k])
        if s == 0.0 and i_t > 0:            # (theta is void at s = 0: theta 0's node)
            out[:, i_t, i_m, i_k] = out[:, 0, i_m, i_k]
        elif _known(m, kn, s):
            out[:, i_t, i_m, i_k] = 0.0
        elif skip is not None and skip[i_t, i_m, i_k]:
            out[:, i_t, i_m, i_k] = np.nan
        else:
            out[:, i_t, i_m, i_k] = point(lg, nu, s, th, tau, m, kn)
    return out


def model_points(lg, nu, s, th, tau, m, kn):
    """The model (:func:`railcontact.falling_table.falling_friction_table`, uncorrected) at
    table coordinates (1-D arrays), normalised as :func:`exact_point`: array (3, n). One
    vectorised call; where that raises (a point beyond the table's or the solver's domain),
    point by point, NaN for the points that raise."""
    from railcontact.creep3d import load_exact_table
    from railcontact.errors import RollingConvergenceError
    from railcontact.falling_table import falling_friction_table

    warnings.simplefilter("ignore")
    table = load_exact_table()
    a, mu0, mu_k, kappa = _case(lg, nu, s, th, tau, m, kn)

    def one(sel):
        args = [v[sel] for v in a[:8]]

        def values(mu):
            sol = table.creep_solution_3d(*args, mu, sensitivities=False)
            return tuple(np.asarray(getattr(sol, k), dtype=float) for k in (
                "tx", "ty", "spin_moment", "stick_area_fraction", "normalised_creepage"))

        m0, mk, kp = (v[sel][:, None] for v in (mu0, mu_k, kappa))
        law_s = _law_in_slip(m0, mk, kp)    # (the family's law, one per point)

        tx, ty, mz = falling_friction_table(values, *args[:6], law_s, mu0[sel],
                                             material=(args[6], args[7]))[:3]
        scale = mu0[sel] * args[3]
        return np.stack([tx / scale, ty / scale, mz / (scale * np.sqrt(args[4] * args[5]))])

    out = np.full((3, np.size(lg)), np.nan)
    try:
        out[:] = one(slice(None))
    except (RollingConvergenceError, ValueError):
        for i in range(np.size(lg)):
            try:
                out[:, i] = one(slice(i, i + 1))[:, 0]
            except (RollingConvergenceError, ValueError):
                pass
    return out


def _model_hash():
    """The model's hash: the source of its function and its constants (a model changed later
    costs only its evaluation at the nodes, seconds, not the exact solves)."""
    import ast
    import inspect

    from railcontact import falling_table as ft

    h = hashlib.sha256()
    for f in (ft.falling_friction_table, ft.spin_floor, ft.table_mu, ft._floor_at,
              ft.static_spin_coordinate, ft.spin_blend_weight):
        fun = ast.parse(inspect.getsource(f)).body[0]
        fun.body = fun.body[1:]     # (its code: neither the docstring nor comments count)
        h.update(ast.unparse(fun).encode())
    h.update(repr((ft.EFFECTIVE_MU_STEPS, ft.GAUSS_POINTS, ft.SLIP_SHARE_MIN,
                   ft.SPIN_POLE_SMOOTHING, ft.SPIN_COORDINATE_EDGE, ft.TABLE_MU_BLEND,
                   ft.SPIN_BLEND)).encode())
    return h.hexdigest()[:12]


#: The axes whose nodes name the chunks of exact solves (a node added to one of them later
#: costs only its own solves); the others are in the work directory's hash.
CHUNK_AXES = ("log_aspect_ratio", "spin_coordinate", "creepage_coordinate")
#: The axes of the nodes within a chunk (a row): a node added to one of them later costs only
#: its own solves too, after :func:`recover` from the file of the nodes before (the new nodes
#: are pending in the recovered rows, :func:`_pending`).
ROW_AXES = ("creepage_angle", "friction_ratio", "friction_decay_number")


def _hash():
    """The work directory's hash: the solver and every axis but :data:`CHUNK_AXES`, whose
    nodes name the chunks (a node of one of them added later reuses every chunk computed
    before)."""
    h = hashlib.sha256(SOLVER.encode())
    if LAW_FAMILY != "smooth":      # (the smooth law's work directory as before)
        h.update(f"law family {LAW_FAMILY}".encode())
    for k, v in NODES.items():
        if k not in CHUNK_AXES:
            h.update(k.encode())
            h.update(np.asarray(v, dtype=float).tobytes())
    return h.hexdigest()[:12]


def _chunk(workdir, i_g, i_nu, i_tau, i_s):
    """The file of one chunk of exact solves, a row of :func:`exact_row`: named by its
    ln(a0/b0), tau and s nodes' values."""
    lg = float(NODES["log_aspect_ratio"][i_g])
    tau = float(NODES["spin_coordinate"][i_tau])
    s = float(NODES["creepage_coordinate"][i_s])
    return Path(workdir) / f"exact_g{lg!r}_{i_nu}_tau{tau!r}_s{s!r}.npy"


def _pending(path):
    """The file of a row's pending nodes (a boolean array (n_theta, n_m, n_kn)) beside the
    row's file ``path``: nodes :func:`recover` found no value for in its source, which has
    fewer nodes along :data:`ROW_AXES` (the build computes them, then removes the file)."""
    return path.with_name("pending_" + path.name)


def _block_missing(workdir, i_g, i_nu, i_tau):
    """The s rows of a (ln(a0/b0), nu, tau) block whose chunk is not there yet or has
    pending nodes."""
    return [i_s for i_s in range(NODES["creepage_coordinate"].size)
            if not _chunk(workdir, i_g, i_nu, i_tau, i_s).exists()
            or _pending(_chunk(workdir, i_g, i_nu, i_tau, i_s)).exists()]


def _ladder_tag():
    return hashlib.sha256(repr((LADDER_GRIDS, LADDER_MIN_GRIDS)).encode()).hexdigest()[:6]


def _ladder_chunk(workdir, i_g, i_nu, i_tau, i_s):
    """The file of one row's ladder estimates (:func:`ladder_point`; NaN where the exact
    solve converged or the ladder did not), named like its chunk of exact solves."""
    return _chunk(workdir, i_g, i_nu, i_tau, i_s).with_name(
        "ladder" + _ladder_tag() + "_" + _chunk(workdir, i_g, i_nu, i_tau, i_s).name)


def _ladder_blocks():
    """The (ln(a0/b0), nu, tau) blocks the ladder is tried on, by tau."""
    n = NODES
    return [(i, j, k) for k in range(n["spin_coordinate"].size)
            if n["spin_coordinate"][k] <= LADDER_TAU_MAX
            for i in range(n["log_aspect_ratio"].size) for j in range(n["poisson_ratio"].size)]


def _ladder_todo(workdir, i_g, i_nu, i_tau, i_s):
    """A row's nodes for the ladder and its ladder values so far: the nodes that did not
    converge where the row has no ladder file yet (values NaN), those of them pending
    (:func:`_pending`) where its file has pending nodes, none where its file is done."""
    path = _ladder_chunk(workdir, i_g, i_nu, i_tau, i_s)
    bad = np.isnan(np.load(_chunk(workdir, i_g, i_nu, i_tau, i_s))[0])
    if not path.exists():
        return bad, np.full((3,) + bad.shape, np.nan)
    if _pending(path).exists():
        return bad & np.load(_pending(path)), np.load(path)
    return np.zeros_like(bad), None


def _ladder_missing(workdir, i_g, i_nu, i_tau):
    """The s rows of a block with nodes for the ladder (:func:`_ladder_todo`)."""
    return [i_s for i_s in range(NODES["creepage_coordinate"].size)
            if _ladder_todo(workdir, i_g, i_nu, i_tau, i_s)[0].any()]


def _ladder_work(workdir, i_g, i_nu, i_tau):
    """The ladder at the unconverged nodes of one block's rows, each row saved when done."""
    t = time.perf_counter()
    for i_s in _ladder_missing(workdir, i_g, i_nu, i_tau):
        bad, out = _ladder_todo(workdir, i_g, i_nu, i_tau, i_s)
        path = _ladder_chunk(workdir, i_g, i_nu, i_tau, i_s)
        _save(path, exact_row(i_g, i_nu, i_tau, i_s, todo=bad, row=out, point=ladder_point))
        _pending(path).unlink(missing_ok=True)
    name = _ladder_chunk(workdir, i_g, i_nu, i_tau, 0).name.rsplit("_s", 1)[0]
    return name, time.perf_counter() - t


def _model_chunk(workdir, i_tau, solved):
    """The file of the model at one tau node's nodes (named by the model's hash, the
    ln(a0/b0) and s nodes', and the nodes solved, ``solved`` of :func:`_solved_tau`, which the
    ladder adds to)."""
    tau = float(NODES["spin_coordinate"][i_tau])
    nodes = hashlib.sha256()
    for k in ("log_aspect_ratio", "creepage_coordinate") + ROW_AXES:
        nodes.update(np.asarray(NODES[k], dtype=float).tobytes())
    nodes.update(np.isfinite(solved[0]).tobytes())
    return Path(workdir) / f"model_{_model_hash()}_g{nodes.hexdigest()[:6]}_tau{tau!r}.npy"


def _save(path, vals):
    tmp = path.with_suffix(".tmp.npy")
    np.save(tmp, vals)
    os.replace(tmp, path)


def _between_unconverged(workdir, i_g, i_nu, i_tau, i_s):
    """The nodes of a row whose two neighbouring rows along s are both there and both
    unconverged (NaN), or None: a row added later between two solved ones is not attempted
    there. Such a solve runs to the solver's iteration limit and, measured on the s node 0.05
    between 0 and 0.1 (2026-11-29, 4 blocks), failed at every such node too; it made those
    blocks 3-8 times slower (14 s for a block without them, 45-112 s with 12 of them)."""
    rows = []
    for j in (i_s - 1, i_s + 1):
        path = _chunk(workdir, i_g, i_nu, i_tau, j) if 0 <= j < NODES[
            "creepage_coordinate"].size else None
        if path is None or not path.exists():
            return None
        bad = np.isnan(np.load(path)[0])
        if _pending(path).exists():     # (a pending node is not known to be unconverged)
            bad &= ~np.load(_pending(path))
        rows.append(bad)
    return rows[0] & rows[1]


def _after_unconverged_tau(workdir, i_g, i_nu, i_tau, i_s):
    """The nodes of a row that did not converge at the tau node below (its row there is
    solved), or None: not attempted (the ladder tries them). Such a solve runs to the
    solver's iteration limit (some 3-7 s against 0.05-0.1 s); measured on Polach's law
    (2026-11-30), of the nodes unconverged at tau 0.75, 97 of 102 did not converge at tau 1
    either, and from tau 1 to 1.125 232 of 236: most of that build's time was such solves."""
    if i_tau == 0:
        return None
    path = _chunk(workdir, i_g, i_nu, i_tau - 1, i_s)
    if not path.exists() or _pending(path).exists():
        return None
    return np.isnan(np.load(path)[0])


def _between_unconverged_theta(row, todo):
    """The pending nodes of a row (``todo``) whose two neighbours along theta (periodic) are
    both not pending and both unconverged: not attempted, as :func:`_between_unconverged`
    along s (the ladder tries them)."""
    bad = np.isnan(row[0]) & ~todo
    return todo & np.roll(bad, 1, axis=0) & np.roll(bad, -1, axis=0)


def _work(workdir, i_g, i_nu, i_tau):
    """The missing rows of one (ln(a0/b0), nu, tau) block, or their pending nodes, each
    saved when done (nodes between two unconverged ones along s, or along theta for the
    pending ones, and those unconverged at the tau node below, not attempted:
    :func:`_between_unconverged`, :func:`_between_unconverged_theta`,
    :func:`_after_unconverged_tau`)."""
    t = time.perf_counter()
    for i_s in _block_missing(workdir, i_g, i_nu, i_tau):
        path = _chunk(workdir, i_g, i_nu, i_tau, i_s)
        pending = _pending(path)
        if pending.exists() and path.exists():
            row, todo = np.load(path), np.load(pending)
            skip = _between_unconverged_theta(row, todo)
            if SKIP_AFTER_UNCONVERGED_TAU:
                below = _after_unconverged_tau(workdir, i_g, i_nu, i_tau, i_s)
                skip = skip if below is None else skip | (todo & below)
            row = exact_row(i_g, i_nu, i_tau, i_s, skip, todo, row)
            _save(path, row)
            ladder = _pending(_ladder_chunk(workdir, i_g, i_nu, i_tau, i_s))
            if ladder.exists():     # (the ladder's pending nodes: those that did not converge)
                left = np.load(ladder) & np.isnan(row[0])
                if left.any():
                    _save(ladder, left)
                else:
                    ladder.unlink()
            pending.unlink()
            continue
        skip = _between_unconverged(workdir, i_g, i_nu, i_tau, i_s)
        if SKIP_AFTER_UNCONVERGED_TAU:
            below = _after_unconverged_tau(workdir, i_g, i_nu, i_tau, i_s)
            skip = below if skip is None else skip if below is None else skip | below
        _save(path, exact_row(i_g, i_nu, i_tau, i_s, skip))
        pending.unlink(missing_ok=True)
    name = _chunk(workdir, i_g, i_nu, i_tau, 0).name.rsplit("_s", 1)[0]
    return name, time.perf_counter() - t


def _exact_tau(workdir, i_tau):
    """The exact solves of one tau node: (3, n_g, n_nu, n_s, n_theta, n_m, n_kn)."""
    n = NODES
    row = tuple(n[k].size for k in ROW_AXES)

    def load(path):     # (a chunk not solved yet: NaN, pending in a partial table)
        return np.load(path) if path.exists() else np.full((3,) + row, np.nan)

    return np.stack([np.stack([np.stack([load(_chunk(workdir, i, j, i_tau, k))
                                         for k in range(n["creepage_coordinate"].size)],
                                        axis=1)
                               for j in range(n["poisson_ratio"].size)], axis=1)
                     for i in range(n["log_aspect_ratio"].size)], axis=1)


def _ladder_tau(workdir, i_tau):
    """The ladder's estimates of one tau node, shaped as :func:`_exact_tau` (NaN where none,
    and at every node of tau > :data:`LADDER_TAU_MAX`: files of a larger tau, from a run with
    a larger bound, are not read)."""
    n = NODES
    out = np.full((3, n["log_aspect_ratio"].size, n["poisson_ratio"].size,
                   n["creepage_coordinate"].size, n["creepage_angle"].size,
                   n["friction_ratio"].size, n["friction_decay_number"].size), np.nan)
    if n["spin_coordinate"][i_tau] > LADDER_TAU_MAX:
        return out
    for i in range(out.shape[1]):
        for j in range(out.shape[2]):
            for k in range(out.shape[3]):
                path = _ladder_chunk(workdir, i, j, i_tau, k)
                if path.exists():
                    out[:, i, j, k] = np.load(path)
    return out


def _solved_tau(workdir, i_tau):
    """The exact solves of one tau node, the ladder's estimates where they did not converge:
    (values, mask of the ladder's nodes)."""
    ex = _exact_tau(workdir, i_tau)
    ld = _ladder_tau(workdir, i_tau)
    use = np.isnan(ex[0]) & np.isfinite(ld[0])
    return np.where(use, ld, ex), use


def _model_where(on, points, tau, fill):
    """The model (:func:`model_points`) at the points ``points`` (lg, nu, s, theta, m, kn: 1-D
    arrays) where ``on``, at spin coordinate ``tau``: array (3, n), ``fill`` elsewhere."""
    lg, nu, s, th, m, kn = points
    out = np.full((3, lg.size), fill)
    i = np.flatnonzero(on)
    for k in range(0, i.size, 2000):    # (bounded memory: 50 Gauss points a node)
        j = i[k:k + 2000]
        out[:, j] = model_points(lg[j], nu[j], s[j], th[j], np.full(j.size, tau), m[j], kn[j])
    return out


def _model_work(workdir, i_tau, solved=None):
    """The model at one tau node's nodes where the exact theory is known (NaN elsewhere;
    ``solved``: those solves, default the work directory's now)."""
    ex = _solved_tau(workdir, i_tau)[0] if solved is None else solved
    path = _model_chunk(workdir, i_tau, ex)
    if not path.exists():
        t = time.perf_counter()
        n = NODES
        tau = n["spin_coordinate"][i_tau]
        lg, nu, s, th, m, kn = (g.ravel() for g in np.meshgrid(
            *(n[k] for k in AXES if k != "spin_coordinate"), indexing="ij"))
        on = ~_known(m, kn, s) & np.isfinite(ex[0].ravel())
        out = _model_where(on, (lg, nu, s, th, m, kn), tau, np.nan)
        _save(path, out.reshape(ex.shape))
        return path.name, time.perf_counter() - t
    return path.name, 0.0


def _pending_tau(workdir, i_tau, ladder=True):
    """The nodes of one tau node not computed yet, shaped as :func:`_exact_tau` without the
    variables: pending in their chunk of exact solves (:func:`_pending`), or (``ladder``)
    unconverged and pending in their ladder's file (tau <= :data:`LADDER_TAU_MAX`)."""
    n = NODES
    shape = tuple(n[k].size for k in AXES if k != "spin_coordinate")
    out = np.zeros(shape, dtype=bool)
    for i in range(shape[0]):
        for j in range(shape[1]):
            for k in range(shape[2]):
                path = _chunk(workdir, i, j, i_tau, k)
                if not path.exists():       # (not solved yet: every node)
                    out[i, j, k] = True
                elif _pending(path).exists():
                    out[i, j, k] = np.load(_pending(path))
                elif ladder and n["spin_coordinate"][i_tau] <= LADDER_TAU_MAX:
                    out[i, j, k] = _ladder_todo(workdir, i, j, i_tau, k)[0]
    return out


def _nodes_and_values(path, name, free=("creepage_angle",)):
    """A table file's nodes of the axes ``free`` (a dict) and its node values (3, ...),
    checked to have the builder's nodes on every other axis (``name``: the argument, for the
    error)."""
    import xarray as xr  # noqa: PLC0415

    with xr.open_dataset(path) as ds:
        for k in AXES:
            got = np.asarray(ds[k].values, dtype=float)
            same = got.size == NODES[k].size and np.allclose(got, NODES[k], rtol=0.0,
                                                              atol=1e-12)
            if k not in free and not same:
                raise ValueError(f"{name}: the file's nodes of {k} {got.tolist()} are not the "
                                 f"builder's {NODES[k].tolist()} (only {', '.join(free)} "
                                 "may differ)")
        return ({k: np.asarray(ds[k].values, dtype=float) for k in free},
                np.stack([ds[v].values.astype(float) for v in VARIABLES]))


def _on_nodes(nodes, wanted, name, axis):
    """Indices of the nodes ``wanted`` among ``nodes`` (each there to 1e-12), else a
    ValueError naming the file ``name`` and the ``axis``."""
    at = [np.flatnonzero(np.isclose(nodes, t, rtol=0.0, atol=1e-12)) for t in wanted]
    if not all(i.size == 1 for i in at):
        raise ValueError(f"{name}: its {axis} nodes {nodes.tolist()} do not include "
                         f"{np.asarray(wanted).tolist()}")
    return np.array([int(i[0]) for i in at])


def source_fill(source):
    """The correction of a table file with fewer theta nodes (every other axis the builder's,
    its theta nodes among :data:`NODES`'), at the builder's nodes: the file's node values
    (unconverged ones filled as the reader fills them,
    :func:`railcontact.falling_table._filled`) along theta by the periodic spline the reader
    fits (:func:`railcontact.falling_table.pack_correction`), which is the file's table at
    those nodes. Array (3, ...) of :data:`AXES`. The value :func:`build` gives a node not
    computed yet when it writes a partial table (``partial_from``)."""
    from scipy.interpolate import make_interp_spline  # noqa: PLC0415

    from railcontact.falling_table import _filled  # noqa: PLC0415

    free, vals = _nodes_and_values(source, "source")
    theta = free["creepage_angle"]
    vals = _filled(vals, NODES["friction_ratio"], NODES["friction_decay_number"])
    sp = make_interp_spline(np.append(theta, np.pi), np.concatenate(
        [vals, vals[:, :, :, :, :1]], axis=4), k=3, bc_type="periodic", axis=4)
    return sp(NODES["creepage_angle"])


def on_base(values, pending, base, ladder=None):
    """A law family's table written on the smooth law's table ``base`` (a file with these
    nodes on every axis but theta, s and mu_k/mu_0, whose theta nodes include these and whose
    s and mu_k/mu_0 nodes are among these: at the others, its not-a-knot spline along s and
    its straight line along mu_k/mu_0, as the reader interpolates): the base's node values
    plus the family's difference to it, ``D = C_family - C_base`` at this family's nodes,
    interpolated along theta by the reader's periodic spline onto the base's theta nodes.
    ``D`` is 0 at the nodes not computed yet (``pending``: the base's value, which the reader
    took for the family before its table), and where the family's exact solve did not
    converge it is filled from its neighbours (:func:`railcontact.falling_table._filled`:
    along theta, then the kappa number, then mu_k/mu_0). The difference is smoother along
    theta than the correction itself (Polach's law, 2026-11-30: at tau 0.5-1 a spline
    through every other 30-degree node missed the 30-degree nodes between by RMS 0.8-0.9e-3
    of mu_0 N for D against 1.7-3.3e-3 for the correction, max 0.022 against 0.050), so the
    base's 15-degree resolution along theta carries over. Returns ``(values, nodes,
    source, ladder)``: the values on the base's grid, its nodes, and the mask of its nodes whose
    ``D`` is all fallback (a 15-degree node between two 30-degree ones: either pending), and
    ``ladder`` (a mask on this family's nodes, default none) on the base's grid."""
    from scipy.interpolate import make_interp_spline  # noqa: PLC0415

    from railcontact.falling_table import _filled  # noqa: PLC0415

    free, vals = _nodes_and_values(base, "base", ("creepage_angle", "creepage_coordinate",
                                                   "friction_ratio"))
    theta = free["creepage_angle"]
    at = _on_nodes(theta, NODES["creepage_angle"], "base", "theta")
    m_base = free["friction_ratio"]
    # the base at the family's other nodes as the reader interpolates it: its not-a-knot
    # spline along s, its straight line along mu_k/mu_0
    for name, label, k in (("creepage_coordinate", "s", 3), ("friction_ratio", "mu_k/mu_0", 1)):
        got = free[name]
        on = _on_nodes(NODES[name], got, "base", label)
        if got.size < NODES[name].size:
            axis = 1 + AXES.index(name)
            filled = _filled(vals, m_base, NODES["friction_decay_number"])
            wider = make_interp_spline(got, filled, k=k, axis=axis)(NODES[name])
            wider[(slice(None),) * axis + (on,)] = vals     # (its own nodes as they were)
            vals = wider
    d = np.where(pending, 0.0, values - vals[:, :, :, :, at])
    d = _filled(d, NODES["friction_ratio"], NODES["friction_decay_number"])
    th = NODES["creepage_angle"]
    sp = make_interp_spline(np.append(th, np.pi), np.concatenate([d, d[:, :, :, :, :1]],
                                                                  axis=4),
                            k=3, bc_type="periodic", axis=4)
    nodes = dict(NODES, creepage_angle=theta)
    # a base node's D is all fallback where the family's nodes on either side are pending
    k = np.searchsorted(np.append(th, np.pi), theta, side="right") - 1
    left, right = k % th.size, (k + 1) % th.size
    on = np.isin(np.arange(theta.size), at)
    src = np.where(on[None, None, None, :, None, None, None],
                   pending[:, :, :, np.clip(np.searchsorted(at, np.arange(theta.size)), 0,
                                            at.size - 1)],
                   pending[:, :, :, left] | pending[:, :, :, right])
    ladder_on_base = np.zeros(src.shape, dtype=bool)
    if ladder is not None:
        ladder_on_base[:, :, :, at] = ladder
    return vals + sp(theta), nodes, src, ladder_on_base


def assemble(workdir, fill=None, ladder_pending=True):
    """The whole grid of corrections (3, n_g, n_nu, n_s, n_theta, n_tau, n_m, n_kn): the exact
    solves (the ladder's where they did not converge) minus the model (0 at the known nodes,
    NaN where either is missing), and the mask of the ladder's nodes; or None while any
    model chunk is missing. ``fill`` (the grid's shape, :func:`source_fill`): the values of
    the nodes not computed yet (:func:`_pending_tau`), then also returned as their mask (and
    a missing model chunk computed: a build running beside changes what is solved).
    ``ladder_pending`` False: an unconverged node the ladder has not reached yet is not
    pending but unconverged (NaN: the reader fills it from its neighbours)."""
    n = NODES
    shape = tuple(n[k].size for k in AXES)
    out = np.empty((3,) + shape)
    ladder = np.zeros(shape, dtype=bool)
    pending = np.zeros(shape, dtype=bool)
    grids = np.meshgrid(*(n[k] for k in AXES if k != "spin_coordinate"), indexing="ij")
    known = _known(grids[4], grids[5], grids[2])
    for i_tau in range(shape[4]):
        if fill is not None:    # (first: a build running beside may finish a row meanwhile)
            pending[:, :, :, :, i_tau] = _pending_tau(workdir, i_tau, ladder_pending) & ~known
        solved, ladder[:, :, :, :, i_tau] = _solved_tau(workdir, i_tau)
        path = _model_chunk(workdir, i_tau, solved)
        if not path.exists() and fill is not None:
            _model_work(workdir, i_tau, solved)
        if not path.exists():
            return None
        out[:, :, :, :, :, i_tau] = np.where(known, 0.0, solved - np.load(path))
    if fill is None:
        return out, ladder
    return np.where(pending, fill, out), ladder, pending


def write(values, path, seconds=None, ladder=None, source=None, nodes=None, base=None):
    """The table file (netCDF-4): the axes, the three variables on the computed grid
    (float32), ``ladder_node`` (1 where the value is the ladder's, :func:`ladder_point`;
    ``ladder``: that mask, default none), ``source_node`` (1 where the node was not computed
    yet and the value is an earlier table's, :func:`source_fill`; ``source``: (that mask, the
    earlier file's name), default none), and ``packed_bspline``, the fitted spline the reader
    evaluates (:func:`railcontact.falling_table.pack_correction`: its layout in the
    attribute)."""
    import xarray as xr  # noqa: PLC0415

    from railcontact.falling_table import pack_correction  # noqa: PLC0415

    nodes = NODES if nodes is None else nodes
    packed = pack_correction(values, nodes)
    coords = {k: (k, np.asarray(v, dtype=float)) for k, v in nodes.items()}
    ds = xr.Dataset({name: (AXES, values[i].astype(np.float32)) for i, name in
                     enumerate(VARIABLES)}, coords=coords)
    ladder = np.zeros(values.shape[1:], dtype=bool) if ladder is None else ladder
    ds["ladder_node"] = (AXES, ladder.astype(np.int8))
    ds["ladder_node"].attrs["meaning"] = (
        "1: the exact theory by the ladder of grids " + repr(LADDER_GRIDS) + " (at least "
        f"{LADDER_MIN_GRIDS} converged, extrapolated in 1/mx) where the default grid did not "
        "converge; 0: the default grid, or known, or NaN (not converged: filled by the reader)")
    if source is not None:
        ds["source_node"] = (AXES, source[0].astype(np.int8))
        ds["source_node"].attrs["meaning"] = (
            "1: not computed yet (a partial build): the value is the table " + str(source[1])
            + " (fewer theta nodes) at the node, its spline along theta; 0: computed")
    from railcontact.falling_table import CORRECTION_HEADER  # noqa: PLC0415

    counts = packed[:CORRECTION_HEADER].astype(int)
    n_head = CORRECTION_HEADER + int(sum(counts[:5]) + 20 + counts[5] + counts[6])
    ds["packed_bspline"] = ("packed", packed[:n_head])
    # (the coefficients in float32: 6e-8 of a correction of at most ~0.1 mu_0 N)
    ds["packed_bspline_coefficients"] = ("packed_coefficients",
                                         packed[n_head:].astype(np.float32))
    ds["packed_bspline"].attrs["layout"] = (
        "header (7): coefficient counts of the cubic axes ln(a0/b0), s, theta, tau, kappa "
        "number; node counts of the linear axes nu, mu_k/mu_0; then the five knot vectors "
        "(count + 4 each), the nu and mu_k/mu_0 nodes, and the coefficients (n_nu, n_m, n_g, "
        "n_s, n_theta, n_tau, n_kn, 3) in C order (variables last: dT_x, dT_y over mu_0 N, "
        "dM_z over mu_0 N sqrt(a0 b0)), these in packed_bspline_coefficients (float32); tau "
        "mirrored to [-20, 20], theta periodic")
    ds.attrs.update(
        title="railcontact falling-friction correction: exact theory with " + (
            "Polach's law (2005, exponential in the slip)" if LAW_FAMILY == "polach"
            else "the smooth law (5.16)") + " minus the fast model on the Coulomb exact table",
        law_family=LAW_FAMILY,
        method=SOLVER + "; model falling_friction_table " + _model_hash(),
        grid_hash=_hash(), n_unconverged=int(np.isnan(values[0]).sum()),
        n_ladder=int(ladder.sum()), ladder_tau_max=float(LADDER_TAU_MAX),
        n_source_nodes=int(0 if source is None else source[0].sum()),
        references="J.B. Nielsen 1998, Eq. (5.16); J.J. Kalker 1990 (exact theory); "
                   "railcontact.falling_table (the model)",
        spin_coordinate_symmetry="tau < 0: mirror y -> -y (theta -> -theta, tau -> -tau; "
                                 "the lateral force and spin moment corrections change sign)")
    if base is not None:
        ds.attrs["base_table"] = base
    if seconds is not None:
        ds.attrs["build_seconds"] = float(seconds)
    enc = {name: dict(zlib=True, complevel=6) for name in VARIABLES + (
        "ladder_node", "packed_bspline", "packed_bspline_coefficients")}
    ds.to_netcdf(path, encoding=enc)


def recover(source, workdir=None):
    """Recover the chunks of exact solves from a table file (the shipped one, on a machine
    without the work directory): the exact theory at a node is the file's correction plus the
    model at that node (0 at the known nodes; NaN, unconverged, where the file has NaN). The
    file must be of the current model (its ``method`` attribute names the model's hash) and of
    the current nodes on every axis but :data:`CHUNK_AXES` and :data:`ROW_AXES`, whose nodes
    in the file must be nodes of :data:`NODES`: the nodes of a row the file does not have are
    written pending (:func:`_pending`, in the ladder's files too), which the build then
    computes, and only those; so are the file's own nodes not computed yet (a partial
    table's ``source_node``, :func:`build`). A chunk already there is kept. The values come back to
    float32's rounding of the correction (some 1e-9 of mu_0 N). Returns (n_written,
    workdir)."""
    import xarray as xr  # noqa: PLC0415

    workdir = Path(workdir or Path.cwd() / "tables-build-work") / f"falling_correction-{_hash()}"
    workdir.mkdir(parents=True, exist_ok=True)
    with xr.open_dataset(source) as ds:
        if ds.attrs.get("law_family", "smooth") != "smooth" or LAW_FAMILY != "smooth":
            raise ValueError(f"source: recover takes the smooth law's table; got law family "
                             f"{ds.attrs.get('law_family', 'smooth')!r} (building "
                             f"{LAW_FAMILY!r}): a family's table is written on the smooth "
                             "one (on_base), its own solves are in its work directory only")
        model = ds.attrs.get("method", "").rsplit(" ", 1)[-1]
        if model != _model_hash():
            raise ValueError(f"source: the file's model {model!r} is not the current model "
                             f"{_model_hash()!r}; recover with the code that built it")
        index = {}
        for k in AXES:
            got = np.asarray(ds[k].values, dtype=float)
            pos = [np.flatnonzero(np.isclose(NODES[k], v, rtol=0.0, atol=1e-12)) for v in got]
            if k not in CHUNK_AXES + ROW_AXES and (got.size != NODES[k].size or not all(
                    p.size == 1 and p[0] == i for i, p in enumerate(pos))):
                raise ValueError(f"source: the file's nodes of {k} {got.tolist()} are not the "
                                 f"builder's {NODES[k].tolist()}")
            if not all(p.size == 1 for p in pos):
                raise ValueError(f"source: the file's nodes of {k} {got.tolist()} are not all "
                                 f"nodes of the builder's {NODES[k].tolist()}")
            index[k] = [int(p[0]) for p in pos]
        corr = np.stack([ds[v].values.astype(float) for v in VARIABLES])
        nodes = {k: np.asarray(ds[k].values, dtype=float) for k in AXES}
        ladder = (ds["ladder_node"].values.astype(bool) if "ladder_node" in ds
                  else np.zeros(corr.shape[1:], dtype=bool))
        ladder_tau_max = float(ds.attrs.get("ladder_tau_max", -1.0))
        source = (ds["source_node"].values.astype(bool) if "source_node" in ds
                  else np.zeros(corr.shape[1:], dtype=bool))
    written = 0
    at_row = np.ix_(*(index[k] for k in ROW_AXES))
    todo = np.ones(tuple(NODES[k].size for k in ROW_AXES), dtype=bool)
    todo[at_row] = False

    def put(path, vals, src):
        # a row of the file's nodes into the builder's, the rest pending, and pending too the
        # file's nodes it took from its source (``src``: its source_node)
        row = np.full((3,) + todo.shape, np.nan)
        row[(slice(None),) + at_row] = np.where(src, np.nan, vals)
        pending = todo.copy()
        pending[at_row] |= src
        if pending.any():   # (first: a row is never there without its pending nodes)
            _save(_pending(path), pending)
        _save(path, row)

    for j_tau, i_tau in enumerate(index["spin_coordinate"]):
        c = corr[:, :, :, :, :, j_tau]     # (3, g, nu, s, theta, m, kn)
        lg, nu, s, th, m, kn = (g.ravel() for g in np.meshgrid(
            *(nodes[k] for k in AXES if k != "spin_coordinate"), indexing="ij"))
        on = ~_known(m, kn, s) & np.isfinite(c[0].ravel())
        model = _model_where(on, (lg, nu, s, th, m, kn), nodes["spin_coordinate"][j_tau], 0.0)
        exact = np.where(_known(m, kn, s), 0.0, c.reshape(3, -1) + model).reshape(c.shape)
        lad = ladder[:, :, :, :, j_tau]
        tried = nodes["spin_coordinate"][j_tau] <= ladder_tau_max
        for j_g, i_g in enumerate(index["log_aspect_ratio"]):
            for i_nu in range(nodes["poisson_ratio"].size):
                for j_s, i_s in enumerate(index["creepage_coordinate"]):
                    row, at = exact[:, j_g, i_nu, j_s], lad[j_g, i_nu, j_s]
                    src = source[j_g, i_nu, j_s, :, j_tau]
                    path = _chunk(workdir, i_g, i_nu, i_tau, i_s)
                    if not path.exists():   # (the ladder's nodes were not converged)
                        put(path, np.where(at, np.nan, row), src)
                        written += 1
                    path = _ladder_chunk(workdir, i_g, i_nu, i_tau, i_s)
                    if tried and not path.exists():
                        put(path, np.where(at, row, np.nan), src)
    return written, workdir


def table_name():
    """The family's table (file) name: the package data ``railcontact/data/<name>.nc``."""
    from railcontact.falling_table import CORRECTION_TABLE  # noqa: PLC0415

    return CORRECTION_TABLE + ("" if LAW_FAMILY == "smooth" else "_" + LAW_FAMILY)


#: Whether a node unconverged at the tau node below is not attempted
#: (:func:`_after_unconverged_tau`; since 2026-11-30, Polach's build from tau 1.25: the
#: smooth law's table was built without it).
SKIP_AFTER_UNCONVERGED_TAU = True


def _in_family(family, fun, *args):
    """``fun(*args)`` in a worker with the law family ``family`` (a worker started by spawn
    or forkserver does not inherit the parent's)."""
    if family != LAW_FAMILY:    # (a forked worker has it already, and the parent's nodes)
        set_law_family(family)
    return fun(*args)


def build(workdir=None, workers=2, output=None, limit=None, partial_from=None, base=None):
    """Compute the missing chunks of exact solves, a (ln(a0/b0), nu, tau) block's missing s
    rows a job (``limit``: at most that many blocks in this run), then the model at the nodes
    (per tau node, kept under the model's hash), and, once all are there, write the file.
    Returns (n_done, n_missing, path or None): jobs done and blocks still missing.

    ``partial_from`` (a table file with fewer theta nodes, the one the work directory was
    recovered from): nothing is solved; the file is written now, the nodes not computed yet
    taking that file's values (:func:`source_fill`, flagged ``source_node``), so that a
    refinement along theta of many hours ships what is done at the end of a session.
    Returns (n_done, n_source_nodes, path).
    A law family other than the smooth law's (:func:`set_law_family`) is written on the
    smooth law's table ``base`` (default ``partial_from``, else the package's; its theta
    nodes, :func:`on_base`): its difference to that table, 0 where not computed yet; an
    unconverged node the ladder has not reached yet is filled from its neighbours, as the
    reader fills one (the base's value there would be the smooth law's correction)."""
    workdir = Path(workdir or Path.cwd() / "tables-build-work") / f"falling_correction-{_hash()}"
    workdir.mkdir(parents=True, exist_ok=True)
    n = NODES
    n_tau = n["spin_coordinate"].size
    blocks = [(i, j, k) for k in range(n_tau) for i in range(n["log_aspect_ratio"].size)
              for j in range(n["poisson_ratio"].size)]
    t0 = time.perf_counter()
    done = 0

    def run(fun, jobs):
        nonlocal done
        with ProcessPoolExecutor(max_workers=workers) as pool:
            futs = [pool.submit(_in_family, LAW_FAMILY, fun, workdir, *job) for job in jobs]
            for f in as_completed(futs):
                name, sec = f.result()
                done += 1
                print(f"{name} {sec:.1f} s ({done}, {time.perf_counter() - t0:.0f} s)",
                      flush=True)

    if partial_from is None:    # (a partial table solves nothing)
        todo = [b for b in blocks if _block_missing(workdir, *b)][:limit]
        if todo:
            run(_work, todo)
        missing = sum(bool(_block_missing(workdir, *b)) for b in blocks)
        if missing:
            return done, missing, None
        ladder = [b for b in _ladder_blocks() if _ladder_missing(workdir, *b)]
        if limit is not None:
            ladder = ladder[:max(0, limit - len(todo))]
        if ladder:
            run(_ladder_work, ladder)
        missing = sum(bool(_ladder_missing(workdir, *b)) for b in _ladder_blocks())
        if missing:
            return done, missing, None
    models = [(k,) for k in range(n_tau)
              if not _model_chunk(workdir, k, _solved_tau(workdir, k)[0]).exists()]
    if models:
        run(_model_work, models)
    output = Path(output or Path.cwd() / "tables-build" / f"{table_name()}.nc")
    output.parent.mkdir(parents=True, exist_ok=True)
    if LAW_FAMILY != "smooth":  # (on the smooth law's table: on_base)
        from railcontact import falling_table  # noqa: PLC0415

        base = Path(base or partial_from or Path(falling_table.__file__).parent / "data"
                    / f"{falling_table.CORRECTION_TABLE}.nc")
        values, ladder_mask, pending = assemble(workdir, np.nan, ladder_pending=False)
        values, nodes, source, ladder_on_base = on_base(values, pending, base, ladder_mask)
        write(values, output, source=(source, base.name) if source.any() else None,
              nodes=nodes, base=base.name, ladder=ladder_on_base)
        if not pending.any():
            _mark_done(workdir, output)
        return done, int(source.sum()), output
    if partial_from is not None:
        values, ladder_mask, pending = assemble(workdir, source_fill(partial_from))
        write(values, output, ladder=ladder_mask, source=(pending, Path(partial_from).name))
        return done, int(pending.sum()), output
    values, ladder_mask = assemble(workdir)
    write(values, output, ladder=ladder_mask)
    _mark_done(workdir, output)
    return done, 0, output


def _mark_done(workdir, output):
    """Record in the work directory that the table ``output`` is complete (``done.json``)."""
    (workdir / "done.json").write_text(json.dumps({"output": str(output),
                                                   "model": _model_hash()}))


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m tablegen.falling_correction")
    p.add_argument("command", choices=["build", "recover"])
    p.add_argument("--source", default=None, help="recover: the table file (default: the "
                   "shipped one)")
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--workdir", default=None)
    p.add_argument("--output", default=None)
    p.add_argument("--limit", type=int, default=None, help="at most this many chunks now")
    p.add_argument("--law", choices=LAW_FAMILIES, default="smooth", help="the law family "
                   "(default the smooth law (5.16); polach: Polach's exponential law)")
    p.add_argument("--partial-from", default=None, help="build: write the table now, the nodes "
                   "not computed yet from this file (fewer theta nodes; solves nothing); "
                   "with --law polach: the smooth law's table it is written on")
    p.add_argument("--base", default=None, help="build --law polach: the smooth law's table "
                   "it is written on (default --partial-from, else the package's)")
    a = p.parse_args(argv)
    if a.law != LAW_FAMILY:
        set_law_family(a.law)
    if a.command == "recover":
        from railcontact import falling_table  # noqa: PLC0415

        shipped = Path(falling_table.__file__).parent / "data" / f"{table_name()}.nc"
        n, where = recover(a.source or shipped, a.workdir)
        print(f"{n} chunks recovered into {where}")
        return 0
    done, missing, path = build(a.workdir, a.workers, a.output, a.limit, a.partial_from,
                                a.base)
    if a.partial_from:
        print(f"wrote {path}; {missing} nodes from {a.partial_from}")
        return 0
    print(f"{done} chunks computed; {missing} missing" + (f"; wrote {path}" if path else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())

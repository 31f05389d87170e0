r"""Run a scene through the WheelRailContact FMU with fmpy: ``python -m railcontact.run SCENE``.

Usage::

    python -m railcontact.run examples/scenes/creep_only_analytic.toml [--out DIR] [--fmu PATH]

The command

1. reads and validates the scene (:func:`railcontact.scene.load_scene`);
2. locates ``WheelRailContact.fmu`` (``--fmu``, else the one at the top of the source checkout)
   and builds it with :func:`railcontact.fmu_build.build` (what ``build_fmu.py`` runs) if it is
   missing or older than the sources;
3. simulates it with :func:`fmpy.simulate_fmu`, feeding the input signals the scene defines,
   with the scene passed as the FMU parameter ``scene_file``;
4. writes ``<out>/<scene name>.csv`` (time, inputs, outputs) and ``<out>/<scene name>.png``.

The FMU's warnings are printed as notes (the run went on: a model or table used at its
limits), wrapped; its errors go to stderr. The summary lists the last row's outputs that the
scene computes and names those it does not. The plot (:func:`figure_results`) draws the
driven inputs and the computed outputs against time, and for a creep scene the force over mu N
against the creepage; it lists the constants and the outputs not computed instead of drawing
them, and names the cause where ``creep_within_validity`` drops. An invalid scene stops with a
message naming the key (exit status 2), a failed simulation with exit status 1.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from . import fmu_build
from .scene import INPUTS, SceneError, load_scene

__all__ = ["locate_fmu", "simulate_scene", "write_results", "output_units", "plot_layout",
           "plot_results", "figure_results", "not_computed", "creep_curves", "validity_causes",
           "validity_note", "VALIDITY_NOTES", "summary_lines", "message_lines", "main"]

_STATUS = {0: "ok", 1: "warning", 2: "discard", 3: "error", 4: "fatal", 5: "pending"}


def locate_fmu(path=None, rebuild=False, verbose=True):
    """Path of a WheelRailContact FMU that matches the current sources, building it if needed.

    Parameters
    ----------
    path : path-like, optional
        A prebuilt FMU to use as is (no staleness check).
    rebuild : bool
        Force a rebuild of the checkout's FMU.
    """
    if path is not None:
        path = Path(path)
        if not path.is_file():
            raise FileNotFoundError(f"fmu: {str(path)!r} does not exist")
        return path
    target = fmu_build.ROOT / f"{fmu_build.MODEL_NAME}.fmu"
    if (rebuild or not target.is_file()
            or fmu_build.fmu_digest(target) != fmu_build.source_hash()):
        if verbose:
            print(f"building {target.name} from the sources (first run, or the sources changed "
                  "since the last build; 30-60 s) ...", flush=True)
        fmu_build.build(fmu_build.ROOT)
    return target


def simulate_scene(scene_path, fmu_path=None, messages=None):
    """Simulate a scene file through the FMU with fmpy.

    Parameters
    ----------
    scene_path : path-like
        Scene TOML file.
    fmu_path : path-like, optional
        FMU to use (default: :func:`locate_fmu`).
    messages : list, optional
        Receives ``(status, category, message)`` of every message the FMU logs.

    Returns
    -------
    scene : Scene
    result : ndarray
        Structured array: ``time``, the outputs.
    inputs : ndarray
        Structured array: ``time`` and the inputs, on the same grid.
    """
    import fmpy

    scene_path = Path(scene_path).resolve()
    scene = load_scene(scene_path)
    fmu = locate_fmu(fmu_path)
    inputs = scene.input_signals()
    log = messages if messages is not None else []

    def logger(_env, _instance, status, category, message):
        log.append((int(status), (category or b"").decode(errors="replace"),
                    (message or b"").decode(errors="replace")))

    sim = scene.simulation
    result = fmpy.simulate_fmu(
        str(fmu), start_time=sim["start_time"], stop_time=sim["stop_time"],
        output_interval=sim["step_size"], input=_with_geometry_inputs(inputs, scene_path),
        start_values={"scene_file": str(scene_path)}, debug_logging=True, logger=logger)
    return scene, result, inputs


def _with_geometry_inputs(inputs, scene_path):
    """``inputs`` with the FMU's geometry and friction inputs added as constant columns at the
    scene's own values (the FMU's start values: nothing changes), so that fmpy, which warns of
    every input variable its signal lacks, has them all."""
    import tomllib  # noqa: PLC0415

    from .fmu_parameters import RUNTIME_INPUTS, scene_to_parameters  # noqa: PLC0415

    with open(scene_path, "rb") as fh:
        start = scene_to_parameters(tomllib.load(fh))
    out = np.zeros(inputs.shape, dtype=inputs.dtype.descr + [(n, float) for n in RUNTIME_INPUTS])
    for name in inputs.dtype.names:
        out[name] = inputs[name]
    for name in RUNTIME_INPUTS:
        out[name] = float(start[name])
    return out


def write_results(path, result, inputs):
    """Write time, inputs and outputs to a CSV file (one header line)."""
    names = ["time"] + list(INPUTS) + [n for n in result.dtype.names if n != "time"]
    columns = [result["time"]]
    for name in INPUTS:
        columns.append(np.interp(result["time"], inputs["time"], inputs[name]))
    columns += [result[n] for n in names[1 + len(INPUTS):]]
    np.savetxt(path, np.column_stack(columns), delimiter=",", header=",".join(names),
               comments="", fmt="%.17g")
    return path


def output_units(fmu_path=None):
    """Output name -> unit, from the FMU's model description (:func:`locate_fmu`)."""
    import fmpy

    md = fmpy.read_model_description(str(locate_fmu(fmu_path)))
    return {v.name: v.unit or (v.declaredType.unit if v.declaredType is not None else None)
            for v in md.modelVariables if v.causality == "output"}


#: Outputs whose value -1 means "not estimated" at that step (the FMU variables'
#: descriptions; :data:`railcontact.effects.NOT_ESTIMATED`).
NOT_ESTIMATED_OUTPUTS = ("creep_table_error_estimate", "friction_table_error_estimate",
                         "friction_iteration_residual", "corrugation_series_error_estimate")
_NOT_ESTIMATED = -1.0

#: The derivatives d(Fx, Fy, Mz)/d(xi_x, xi_y, phi) (:data:`railcontact.effects.JACOBIAN_FIELDS`).
JACOBIAN_OUTPUTS = tuple(f"d{f}_d{v}" for f in ("Fx", "Fy", "Mz")
                         for v in ("xi_x", "xi_y", "phi"))


def not_computed(scene):
    """The outputs the scene's effects do not compute (the FMU holds them at 0 or -1):
    output name -> why (from the FMU variables' descriptions).

    Mz and the Jacobian come from Kalker's exact theory only (creep method ``"exact"``); the
    wear, corrugation, non-steady and rough-rail outputs from their effects.
    """
    effects = scene.effects
    creep = effects.get("creep", {})
    why = {}
    if creep.get("method") != "exact":
        reason = (f"creep method {creep.get('method')!r} gives no spin moment (Kalker's exact "
                  "theory, method 'exact', does)" if creep else "creep is off")
        why["Mz"] = reason
        why.update({n: f"creep method {creep.get('method')!r}: no Jacobian (method 'exact' "
                       "gives it)" if creep else "creep is off" for n in JACOBIAN_OUTPUTS})
    needs = {"wear_depth_per_passage": ("wear",), "corrugation_amplitude": ("corrugation",),
             "corrugation_growth_rate": ("corrugation", "wear"),
             "relaxation_length": ("nonsteady",), "relaxed_creepage_longitudinal": ("nonsteady",),
             "relaxed_creepage_lateral": ("nonsteady",), "relaxed_spin": ("nonsteady",),
             "gap_curvature": ("roughness",), "gap_skewness": ("roughness",),
             "gap_flatness": ("roughness",), "critical_creepage": ("roughness",)}
    for name, effect_names in needs.items():
        off = [e for e in effect_names if e not in effects]
        if off:
            why[name] = " and ".join(off) + (" is" if len(off) == 1 else " are") + " off"
    if "corrugation" not in effects and "roughness" not in effects:
        why["patch_shift"] = "smooth rail (corrugation and roughness are off)"
    return why


#: Where ``creep_within_validity`` drops, the plot names the cause that applies
#: (:func:`validity_causes`; the FMU variable's description lists them all).
VALIDITY_NOTES = {
    "spin": ("the spin pole lies inside the contact (spin coefficient > 1, Eq. (2.98)), where "
             "the {method} theory is outside its range; the forces shown are still bounded by "
             "mu N"),
    "saturation": ("the linear theory's force |(Fx, Fy)| exceeds mu N (the linear theory does "
                   "not saturate: valid only for |T| << mu N)"),
    "line": ("lateral creepage or spin is not zero, and the 2-D theory of a line contact "
             "ignores both"),
}


def validity_causes(scene, result, inputs):
    """Why ``creep_within_validity`` is false where it is: the keys of
    :data:`VALIDITY_NOTES` that apply to this scene and these samples (empty if it never
    drops). A line contact: ``"line"``; the linear theory: ``"saturation"`` where |(Fx, Fy)|
    > mu N, ``"spin"`` elsewhere; the other theories: ``"spin"``."""
    if "creep_within_validity" not in result.dtype.names:
        return []
    invalid = ~np.asarray(result["creep_within_validity"], dtype=bool)
    if not invalid.any():
        return []
    creep = scene.effects.get("creep", {})
    if scene.geometry.get("kind") == "line" or creep.get("method") == "carter":
        return ["line"]
    if creep.get("method") != "linear":
        return ["spin"]
    n_load = np.interp(result["time"], inputs["time"], inputs["normal_force"])
    over = np.hypot(result["Fx"], result["Fy"]) > scene.friction_coefficient * n_load * (
        1.0 + 1e-12)
    return [c for c, hit in (("saturation", (invalid & over).any()),
                             ("spin", (invalid & ~over).any())) if hit]


def validity_note(scene, result, inputs):
    """The note under the plot where ``creep_within_validity`` drops: the cause(s) that
    apply (:func:`validity_causes`), or None."""
    causes = validity_causes(scene, result, inputs)
    if not causes:
        return None
    method = scene.effects.get("creep", {}).get("method", "creep")
    return ("creep_within_validity = false (shaded): "
            + "; or ".join(VALIDITY_NOTES[c].format(method=method) for c in causes) + ".")


def creep_curves(scene, result, inputs):
    """The force-versus-creepage view of a creep scene: ``[(force, creepage, x, y), ...]``
    with x the creepage [-] and y = force / (mu N) [-] at every output sample (mu the scene's
    friction coefficient, N the normal force input), for each creepage input that varies
    (Fx against creepage_longitudinal, Fy against creepage_lateral). Empty without creep."""
    if not any(e in scene.effects for e in ("creep", "velocity_friction", "roughness")):
        return []
    t = np.asarray(result["time"], dtype=float)
    mu_n = scene.friction_coefficient * np.interp(t, inputs["time"], inputs["normal_force"])
    out = []
    for force, creepage in (("Fx", "creepage_longitudinal"), ("Fy", "creepage_lateral")):
        if creepage not in scene.inputs or force not in result.dtype.names:
            continue
        x = np.interp(t, inputs["time"], inputs[creepage])
        if not np.ptp(x) > 0:
            continue
        with np.errstate(divide="ignore", invalid="ignore"):
            y = np.where(mu_n > 0, np.asarray(result[force], dtype=float) / mu_n, np.nan)
        out.append((force, creepage, x, y))
    return out


def plot_layout(scene, result, inputs):
    """What the run plot shows: panels for what changes, a list for what does not.

    Returns
    -------
    dict
        ``inputs``: the driven inputs that vary (always at least one: ``normal_force``);
        ``outputs``: the outputs that vary, Fx and Fy always; ``constant_inputs`` and
        ``constant_outputs``: name -> value of those that do not vary (listed under the plot,
        no panel); ``not_computed``: output name -> why the scene does not compute it
        (:func:`not_computed`, and the "not estimated" outputs that are -1 throughout; no
        panel, listed as not computed); ``gaps``: output name -> boolean mask of the samples
        where a plotted output is "not estimated" (-1; drawn as gaps); ``invalid``: list of
        (t_start, t_end) where ``creep_within_validity`` is false (empty when it is true
        throughout or not an output); ``same_as``: output name -> the plotted output it
        equals at every sample (no panel of its own).
    """
    def varies(values):
        return bool(np.ptp(np.asarray(values, dtype=float)) > 0)

    driven = [n for n in INPUTS if n in scene.inputs and varies(inputs[n])]
    constant_inputs = {n: float(inputs[n][0]) for n in INPUTS
                       if n in scene.inputs and n not in driven}
    if not driven:
        driven = ["normal_force"]
        constant_inputs.pop("normal_force", None)
    names = [n for n in result.dtype.names if n != "time"]
    missing = {n: why for n, why in not_computed(scene).items() if n in names}
    gaps = {}
    for n in NOT_ESTIMATED_OUTPUTS:
        if n in names and n not in missing:
            mask = np.asarray(result[n], dtype=float) == _NOT_ESTIMATED
            if mask.all():
                missing[n] = "not estimated in this scene (-1 throughout)"
            elif mask.any():
                gaps[n] = mask
    names = [n for n in names if n not in missing]

    def varies_where_estimated(n):
        values = np.asarray(result[n], dtype=float)
        return varies(values[~gaps[n]] if n in gaps else values) or n in gaps

    outputs = [n for n in names if n != "creep_within_validity"
               and (n in ("Fx", "Fy") or varies_where_estimated(n))]
    constant_outputs = {n: result[n][0] for n in names
                        if n not in outputs and n != "creep_within_validity"}
    # an output equal to one already shown throughout (e.g. contact_half_width = a0 on a
    # smooth rail) gets no panel of its own
    same_as = {}
    for k, name in enumerate(outputs):
        for other in outputs[:k]:
            if other not in same_as and np.array_equal(result[name], result[other]):
                same_as[name] = other
                break
    outputs = [n for n in outputs if n not in same_as]
    invalid = []
    if "creep_within_validity" in names:
        valid = np.asarray(result["creep_within_validity"], dtype=bool)
        if valid.all():
            constant_outputs["creep_within_validity"] = True
        else:
            t = np.asarray(result["time"], dtype=float)
            edges = np.diff(np.concatenate(([0], (~valid).astype(np.int8), [0])))
            for i, j in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)):
                # a sample holds until the next one: shade [t_i, t_j) (to the end at the end)
                invalid.append((float(t[i]), float(t[min(j, len(t) - 1)])))
    return dict(inputs=driven, outputs=outputs, constant_inputs=constant_inputs,
                constant_outputs=constant_outputs, same_as=same_as, invalid=invalid,
                not_computed=missing, gaps=gaps)


def _format_constants(values, units):
    parts = []
    for name, value in values.items():
        unit = units.get(name)
        text = str(value) if isinstance(value, (bool, np.bool_)) else f"{float(value):.4g}"
        parts.append(f"{name} = {text}" + (f" {unit}" if unit and unit != "1" else ""))
    return parts


def _group_not_computed(missing):
    """``{why: [names]}`` in first-seen order, the nine Jacobian entries named as one."""
    groups = {}
    for name, why in missing.items():
        groups.setdefault(why, []).append(name)
    for why, names in groups.items():
        if all(j in names for j in JACOBIAN_OUTPUTS):
            groups[why] = ["d(Fx, Fy, Mz)/d(xi_x, xi_y, phi)"] + [
                n for n in names if n not in JACOBIAN_OUTPUTS]
    return groups


def figure_results(scene, result, inputs, units=None):
    """The run plot as a matplotlib figure (:func:`plot_results` saves it).

    Time panels: the driven inputs in grey, the outputs the scene computes in blue (a "not
    estimated" sample, -1, is a gap, and the panel says so); where ``creep_within_validity``
    is false the output panels are shaded and a note names the cause that applies
    (:func:`validity_note`). A creep scene gets a last panel, force / (mu N) against creepage
    (:func:`creep_curves`). Under the plot: the constant inputs and outputs with their values,
    and the outputs the scene does not compute ("not computed", with why; no panel).

    ``units``: output name -> unit for the axis labels (e.g. :func:`output_units`).
    """
    import textwrap

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    units = dict(units or {})
    units.update({n: INPUTS[n][0] for n in INPUTS})
    layout = plot_layout(scene, result, inputs)
    driven, outputs = layout["inputs"], layout["outputs"]
    curves = creep_curves(scene, result, inputs)
    constants = (_format_constants(layout["constant_inputs"], units)
                 + _format_constants(layout["constant_outputs"], units))
    footer = []
    if layout["same_as"]:
        constants += [f"{n} = {m} throughout" for n, m in layout["same_as"].items()]
    if constants:
        footer = textwrap.wrap("constant during the run, or equal to a plotted output (no "
                               "panel): " + ", ".join(constants), 110)
    if layout["not_computed"]:
        footer += [""] + textwrap.wrap(
            "not computed in this scene (no panel; the FMU holds them at 0 or -1): " + "; ".join(
                f"{', '.join(names)} ({why})"
                for why, names in _group_not_computed(layout["not_computed"]).items()), 110)
    note = validity_note(scene, result, inputs) if layout["invalid"] else None
    if note:
        footer += [""] + textwrap.wrap(note, 110)
    rows = len(driven) + len(outputs)
    extra = 0.9 + 0.16 * len(footer) + (2.6 if curves else 0.0)
    fig = plt.figure(figsize=(8, 1.5 * rows + 1 + extra))
    grid = fig.add_gridspec(rows + (2 if curves else 0), 1,
                            height_ratios=[1.0] * rows + ([0.35, 1.9] if curves else []))
    axes = []
    for k in range(rows):
        axes.append(fig.add_subplot(grid[k], sharex=axes[0] if axes else None))
    for ax in axes[:-1]:
        ax.tick_params(labelbottom=False)
    t_out = np.asarray(result["time"], dtype=float)
    for ax, name in zip(axes, driven):
        ax.plot(inputs["time"], inputs[name], color="tab:gray")
        ax.set_facecolor("#f4f4f4")
        ax.set_ylabel(f"{name}\n[{units[name]}]", fontsize=8)
    axes[0].set_title("inputs (set by the scene)", fontsize=9, loc="left")
    for ax, name in zip(axes[len(driven):], outputs):
        values = np.asarray(result[name], dtype=float)
        if name in layout["gaps"]:
            values = np.where(layout["gaps"][name], np.nan, values)
            ax.text(0.99, 0.95, "gaps: not estimated (-1) there", transform=ax.transAxes,
                    ha="right", va="top", fontsize=7, color="0.35")
        ax.plot(t_out, values, color="tab:blue")
        for t0, t1 in layout["invalid"]:
            ax.axvspan(t0, t1, color="tab:red", alpha=0.15, lw=0)
        unit = units.get(name)
        ax.set_ylabel(f"{name}\n[{unit}]" if unit else name, fontsize=8)
    axes[len(driven)].set_title("outputs (computed by the FMU)", fontsize=9, loc="left")
    axes[-1].set_xlabel("time [s]")
    axes[-1].tick_params(labelbottom=True)
    if curves:
        ax = fig.add_subplot(grid[rows + 1])
        for (force, creepage, x, y), color in zip(curves, ("tab:blue", "tab:orange")):
            ax.plot(x, y, ".", ms=2, color=color, label=f"{force} / (mu N) against {creepage}")
        ax.axhline(1.0, color="0.6", lw=0.8, ls="--")
        ax.axhline(-1.0, color="0.6", lw=0.8, ls="--")
        ax.set_xlabel("creepage [1]")
        ax.set_ylabel(f"force / (mu N)\n[1], mu = {scene.friction_coefficient:g}", fontsize=8)
        ax.set_title("creep curve: force against creepage (every output sample; the other "
                     "inputs vary too)", fontsize=9, loc="left")
        ax.legend(fontsize=7, loc="upper right", frameon=False)
        if layout["invalid"]:
            ax.text(0.01, 0.04, "points where creep_within_validity = false included",
                    transform=ax.transAxes, fontsize=7, color="0.35")
        axes.append(ax)
    handles = [Line2D([], [], color="tab:gray", label="input"),
               Line2D([], [], color="tab:blue", label="output")]
    if layout["invalid"]:
        handles.append(Patch(color="tab:red", alpha=0.15,
                             label="creep_within_validity = false (see note below)"))
    height = fig.get_figheight()
    fig.suptitle(f"scene {scene.name}: {scene.description}", fontsize=9, x=0.02, ha="left",
                 y=1.0 - 0.1 / height)
    fig.legend(handles=handles, loc="upper right", bbox_to_anchor=(0.98, 1.0 - 0.3 / height),
               fontsize=8, ncol=len(handles), frameon=False)
    if footer:      # 0.1 in above the bottom edge, whatever the figure's height
        fig.text(0.02, 0.1 / height, "\n".join(footer), fontsize=7, va="bottom", ha="left")
    # leave room for the title and legend on top and the lists below (a line of 7 pt text
    # takes about 0.12 in)
    top = 1.0 - 0.6 / height
    bottom = (0.25 + 0.125 * len(footer)) / height
    fig.tight_layout(rect=(0.0, bottom, 1.0, top))
    return fig


def plot_results(path, scene, result, inputs, units=None):
    """Plot the run into a PNG file (:func:`figure_results`) and return its path."""
    import matplotlib.pyplot as plt

    fig = figure_results(scene, result, inputs, units)
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def summary_lines(scene, result, width=100):
    """The run's closing summary, wrapped to ``width`` columns: rows, the last row's outputs
    that the scene computes, and the names of those it does not."""
    import textwrap

    last = result[-1]
    missing = not_computed(scene)
    # (no-break spaces keep each "name = value" on one line; put back after wrapping)
    shown = [f"{n}\u00a0=\u00a0{last[n]:.6g}" for n in result.dtype.names
             if n != "time" and n not in missing
             and not (n in NOT_ESTIMATED_OUTPUTS and last[n] == _NOT_ESTIMATED)]
    lines = [f"scene {scene.name}: {len(result)} rows, t = {result['time'][0]:g} to "
             f"{last['time']:g} s. Last row:"]
    lines += [line.replace("\u00a0", " ") for line in textwrap.wrap(
        ", ".join(shown), width, initial_indent="  ", subsequent_indent="  ")]
    skipped = [n for n in result.dtype.names if n in missing or (
        n in NOT_ESTIMATED_OUTPUTS and last[n] == _NOT_ESTIMATED)]
    if skipped:
        lines += textwrap.wrap(
            "not computed in this scene (0 or -1 in the CSV): " + ", ".join(
                n for names in _group_not_computed(
                    {n: missing.get(n, "") for n in skipped}).values() for n in names),
            width, initial_indent="  ", subsequent_indent="  ")
    return lines


def message_lines(messages, width=100):
    """The FMU's log messages for the terminal: warnings as wrapped notes (the run went on;
    they say where a model or table met its limits), errors as errors. ``(stream, line)``
    pairs, stream "out" or "err"."""
    import textwrap

    notes = [m for status, _c, m in messages if status == 1]
    errors = [(status, m) for status, _c, m in messages if status >= 2]
    out = []
    if notes:
        out.append(("out", "Notes from the FMU (the run went on; these say where a model or a "
                           "table met its limits):"))
        for m in notes:
            out += [("out", line) for line in textwrap.wrap(
                m, width, initial_indent="  - ", subsequent_indent="    ")]
    for status, m in errors:
        out += [("err", line) for line in textwrap.wrap(
            f"FMU {_STATUS.get(status, status)}: {m}", width, subsequent_indent="    ")]
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m railcontact.run",
                                     description="Run a scene through the WheelRailContact "
                                                 "FMU with fmpy; write CSV and PNG.")
    parser.add_argument("scene", help="scene TOML file, e.g. examples/scenes/"
                                      "creep_only_analytic.toml")
    parser.add_argument("--out", default="out", help="output directory (default: out)")
    parser.add_argument("--fmu", default=None, help="use this FMU instead of building one")
    args = parser.parse_args(argv)

    messages = []

    def show_messages():
        for stream, line in message_lines(messages):
            print(line, file=sys.stderr if stream == "err" else sys.stdout)

    try:
        scene, result, inputs = simulate_scene(args.scene, args.fmu, messages)
    except SceneError as exc:
        print(f"invalid scene: {exc}", file=sys.stderr)
        return 2
    except Exception as exc:   # fmpy raises on a failed FMI call; show what the FMU said
        show_messages()
        print(f"simulation failed: {exc}", file=sys.stderr)
        return 1
    show_messages()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    csv = write_results(out / f"{scene.name}.csv", result, inputs)
    png = plot_results(out / f"{scene.name}.png", scene, result, inputs,
                       units=output_units(args.fmu))
    print("\n".join(summary_lines(scene, result)))
    print(f"wrote {csv}\n  and {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

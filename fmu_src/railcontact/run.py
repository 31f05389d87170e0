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

Errors and warnings the FMU logs are printed; an invalid scene stops with a message naming
the key (exit status 2), a failed simulation with exit status 1.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from . import fmu_build
from .scene import INPUTS, SceneError, load_scene

__all__ = ["locate_fmu", "simulate_scene", "write_results", "output_units", "plot_layout",
           "plot_results", "VALIDITY_NOTE", "main"]

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
            print(f"building {target.name} (sources changed or FMU missing) ...", flush=True)
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
        output_interval=sim["step_size"], input=inputs,
        start_values={"scene_file": str(scene_path)}, debug_logging=True, logger=logger)
    return scene, result, inputs


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


#: Where ``creep_within_validity`` drops, the plot says why (the FMU variable's description).
VALIDITY_NOTE = ("creep_within_validity = false: the creep theory is outside its range here "
                 "(spin pole inside the contact, spin coefficient > 1, Eq. (2.98); linear "
                 "theory: |T| > mu N; line contact: lateral creepage or spin ignored). The "
                 "forces shown are still bounded by mu N.")


def plot_layout(scene, result, inputs):
    """What the run plot shows: panels for what changes, a list for what does not.

    Returns
    -------
    dict
        ``inputs``: the driven inputs that vary (always at least one: ``normal_force``);
        ``outputs``: the outputs that vary, Fx and Fy always; ``constant_inputs`` and
        ``constant_outputs``: name -> value of those that do not vary (listed under the plot,
        no panel); ``invalid``: list of (t_start, t_end) where ``creep_within_validity`` is
        false (empty when it is true throughout or not an output); ``same_as``: output name
        -> the plotted output it equals at every sample (no panel of its own).
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
    outputs = [n for n in names if n != "creep_within_validity"
               and (n in ("Fx", "Fy") or varies(result[n]))]
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
                constant_outputs=constant_outputs, same_as=same_as, invalid=invalid)


def _format_constants(values, units):
    parts = []
    for name, value in values.items():
        unit = units.get(name)
        text = str(value) if isinstance(value, (bool, np.bool_)) else f"{float(value):.4g}"
        parts.append(f"{name} = {text}" + (f" {unit}" if unit and unit != "1" else ""))
    return parts


def plot_results(path, scene, result, inputs, units=None):
    """Plot the driven inputs and the outputs against time into a PNG file.

    Inputs (set by the scene) are drawn in grey, outputs (computed by the FMU) in blue, under
    two headings, with a legend. Inputs and outputs that stay constant get no panel; they are
    listed with their values under the plot. Where ``creep_within_validity`` is false the output
    panels are shaded and the legend says what that means (:data:`VALIDITY_NOTE`).

    ``units``: output name -> unit for the axis labels (e.g. :func:`output_units`)."""
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
    constants = (_format_constants(layout["constant_inputs"], units)
                 + _format_constants(layout["constant_outputs"], units))
    footer = []
    if layout["same_as"]:
        constants += [f"{n} = {m} throughout" for n, m in layout["same_as"].items()]
    if constants:
        footer = textwrap.wrap("no panel (constant during the run, or equal to a plotted "
                               "output): " + ", ".join(constants),
                               110)
    if layout["invalid"]:
        footer += [""] + textwrap.wrap(VALIDITY_NOTE, 110)
    rows = len(driven) + len(outputs)
    extra = 0.9 + 0.16 * len(footer)
    fig, axes = plt.subplots(rows, 1, sharex=True, figsize=(8, 1.5 * rows + 1 + extra))
    axes = np.atleast_1d(axes)
    for ax, name in zip(axes, driven):
        ax.plot(inputs["time"], inputs[name], color="tab:gray")
        ax.set_facecolor("#f4f4f4")
        ax.set_ylabel(f"{name}\n[{units[name]}]", fontsize=8)
    axes[0].set_title("inputs (set by the scene)", fontsize=9, loc="left")
    for ax, name in zip(axes[len(driven):], outputs):
        ax.plot(result["time"], result[name], color="tab:blue")
        for t0, t1 in layout["invalid"]:
            ax.axvspan(t0, t1, color="tab:red", alpha=0.15, lw=0)
        unit = units.get(name)
        ax.set_ylabel(f"{name}\n[{unit}]" if unit else name, fontsize=8)
    axes[len(driven)].set_title("outputs (computed by the FMU)", fontsize=9, loc="left")
    axes[-1].set_xlabel("time [s]")
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
    if footer:
        fig.text(0.02, 0.01, "\n".join(footer), fontsize=7, va="bottom", ha="left")
    # leave room for the title and legend on top and the list of constants below
    top = 1.0 - 0.6 / height
    bottom = (0.12 + 0.13 * len(footer)) / height
    fig.tight_layout(rect=(0.0, bottom, 1.0, top))
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


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
    try:
        scene, result, inputs = simulate_scene(args.scene, args.fmu, messages)
    except SceneError as exc:
        print(f"invalid scene: {exc}", file=sys.stderr)
        return 2
    except Exception as exc:   # fmpy raises on a failed FMI call; show what the FMU said
        for status, _category, message in messages:
            if status >= 1:
                print(f"FMU {_STATUS.get(status, status)}: {message}", file=sys.stderr)
        print(f"simulation failed: {exc}", file=sys.stderr)
        return 1
    for status, _category, message in messages:
        if status >= 1:
            print(f"FMU {_STATUS.get(status, status)}: {message}", file=sys.stderr)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    csv = write_results(out / f"{scene.name}.csv", result, inputs)
    png = plot_results(out / f"{scene.name}.png", scene, result, inputs,
                       units=output_units(args.fmu))
    last = result[-1]
    summary = ", ".join(f"{n} = {last[n]:.6g}" for n in result.dtype.names)
    print(f"scene {scene.name}: {len(result)} rows; last row: {summary}")
    print(f"wrote {csv} and {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

r"""Run a scene through the WheelRailContact FMU with fmpy: ``python -m railcontact.run SCENE``.

Usage::

    python -m railcontact.run examples/scenes/creep_only_analytic.toml [--out DIR] [--fmu PATH]

The command

1. reads and validates the scene (:func:`railcontact.scene.load_scene`);
2. locates ``WheelRailContact.fmu`` (``--fmu``, else the one at the top of the source checkout)
   and builds it with ``build_fmu.py`` if it is missing or older than the sources;
3. simulates it with :func:`fmpy.simulate_fmu`, feeding the input signals the scene defines,
   with the scene passed as the FMU parameter ``scene_file``;
4. writes ``<out>/<scene name>.csv`` (time, inputs, outputs) and ``<out>/<scene name>.png``.

Errors and warnings the FMU logs are printed; an invalid scene stops with a message naming
the key (exit status 2), a failed simulation with exit status 1.
"""

from __future__ import annotations

import argparse
import importlib.util
import sys
from pathlib import Path

import numpy as np

from .scene import INPUTS, SceneError, load_scene

__all__ = ["locate_fmu", "simulate_scene", "write_results", "output_units", "plot_layout",
           "plot_results", "main"]

_SOURCE_ROOT = Path(__file__).resolve().parents[2]   # the checkout (editable install)
_STATUS = {0: "ok", 1: "warning", 2: "discard", 3: "error", 4: "fatal", 5: "pending"}


def _build_module():
    path = _SOURCE_ROOT / "build_fmu.py"
    if not path.is_file():
        raise FileNotFoundError(
            f"cannot build the FMU: {path} not found (railcontact.run builds the FMU from a "
            "source checkout; pass --fmu PATH to use a prebuilt WheelRailContact.fmu)")
    spec = importlib.util.spec_from_file_location("_railcontact_build_fmu", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


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
    builder = _build_module()
    target = _SOURCE_ROOT / f"{builder.MODEL_NAME}.fmu"
    if rebuild or not target.is_file() or builder.fmu_digest(target) != builder.source_hash():
        if verbose:
            print(f"building {target.name} (sources changed or FMU missing) ...", flush=True)
        builder.build(_SOURCE_ROOT)
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


#: Outputs drawn together in one panel: (title, names, scale, unit shown).
OUTPUT_GROUPS = (
    ("forces on the wheel", ("Fx", "Fy"), 1e-3, "kN"),
    ("spin moment", ("Mz",), 1.0, "N.m"),
    ("contact size", ("a0", "b0", "contact_half_width"), 1e3, "mm"),
    ("peak pressure", ("p0",), 1e-6, "MPa"),
    ("stick zone", ("stick_area_fraction", "stick_width_ratio", "r_a0"), 1.0, "1"),
    ("relaxed creepages", ("relaxed_creepage_longitudinal", "relaxed_creepage_lateral"), 1.0,
     "1"),
)
#: Inputs drawn together (creepages share a panel and a unit).
INPUT_GROUPS = (
    ("normal force", ("normal_force",), 1e-3, "kN"),
    ("creepages", ("creepage_longitudinal", "creepage_lateral"), 1.0, "1"),
    ("spin", ("spin",), 1.0, "1/m"),
    ("rolling speed", ("rolling_speed",), 1.0, "m/s"),
    ("rail position", ("rail_position",), 1.0, "m"),
)
#: Flags shown as shaded time spans on the forces panel, not as panels.
VALIDITY_NOTE = ("creep_within_validity = 0: the creep theory is used outside its range (spin "
                 "pole inside the contact, spin coefficient > 1, Nielsen Eq. (2.98)); the "
                 "forces there are the theory's formulas, not verified")


def plot_layout(scene, result, inputs, units=None):
    """What :func:`plot_results` draws: input panels, output panels, constants, flag spans.

    Returns a dict with ``inputs`` and ``outputs`` (lists of ``(title, [(name, scale)],
    unit)``: only quantities that change during the run), ``constants`` (``name = value unit``
    strings of the inputs and outputs that stay constant, the always-constant "not in use"
    outputs left out) and ``invalid_spans`` (``(t0, t1)`` where ``creep_within_validity`` is 0).
    """
    units = units or {}
    t = np.asarray(result["time"], dtype=float)

    def varies(values):
        values = np.asarray(values, dtype=float)
        return np.ptp(values) > 1e-12 * max(1e-300, float(np.abs(values).max()))

    def panels(groups, data, names, unit_of):
        out, used = [], set()
        for title, members, scale, unit in groups:
            shown = [(n, scale) for n in members if n in names and varies(data[n])]
            used.update(n for n in members if n in names)
            if shown:
                out.append((title, shown, unit))
        for n in names:
            if n not in used and varies(data[n]):
                out.append((n.replace("_", " "), [(n, 1.0)], unit_of(n)))
        return out

    in_names = [n for n in INPUTS if n in inputs.dtype.names]
    out_names = [n for n in result.dtype.names if n not in ("time", "creep_within_validity")]
    constants = [f"{n} = {float(inputs[n][0]):.4g} {INPUTS[n][0]}" for n in in_names
                 if not varies(inputs[n])]
    constants += [f"{n} = {float(result[n][0]):.4g} {units.get(n) or ''}".rstrip()
                  for n in out_names if not varies(result[n])
                  and float(result[n][0]) not in (0.0, -1.0)]
    spans = []
    if "creep_within_validity" in result.dtype.names:
        bad = np.asarray(result["creep_within_validity"], dtype=float) < 0.5
        edges = np.flatnonzero(np.diff(np.r_[0, bad.astype(int), 0]))
        spans = [(t[i], t[min(j, len(t) - 1)]) for i, j in zip(edges[::2], edges[1::2])]
    return {"inputs": panels(INPUT_GROUPS, inputs, in_names, lambda n: INPUTS[n][0]),
            "outputs": panels(OUTPUT_GROUPS, result, out_names, lambda n: units.get(n) or ""),
            "constants": constants, "invalid_spans": spans}


def plot_results(path, scene, result, inputs, units=None):
    """Plot the inputs (grey, left) and the outputs (colour, right) against time into a PNG.

    Quantities that stay constant are listed under the title instead of drawn; related outputs
    share a panel with a legend (:data:`OUTPUT_GROUPS`); where ``creep_within_validity`` drops
    to 0 the forces panel is shaded and the legend says why (:data:`VALIDITY_NOTE`).
    ``units``: output name -> unit for the axis labels (e.g. :func:`output_units`)."""
    import textwrap

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    layout = plot_layout(scene, result, inputs, units)
    n_rows = max(len(layout["inputs"]), len(layout["outputs"]), 1)
    fig, axes = plt.subplots(n_rows, 2, sharex=True, figsize=(12, 1.9 * n_rows + 2.0),
                             squeeze=False)
    columns = (("inputs (set by the scene)", layout["inputs"], inputs, True),
               ("outputs of the FMU", layout["outputs"], result, False))
    for col, (heading, panels, data, grey) in enumerate(columns):
        axes[0, col].set_title(heading, fontsize=10, fontweight="bold")
        for row in range(n_rows):
            ax = axes[row, col]
            if row >= len(panels):
                ax.set_visible(False)
                continue
            title, members, unit = panels[row]
            for k, (name, scale) in enumerate(members):
                colour = ("0.35", "0.65")[k % 2] if grey else f"C{k}"
                ax.plot(data["time"], np.asarray(data[name], dtype=float) * scale,
                        color=colour, label=name)
            ax.set_ylabel(f"{title}\n[{unit}]" if unit else title, fontsize=8)
            if len(members) > 1:
                ax.legend(fontsize=7, loc="best")
            if not grey and title == "forces on the wheel":
                for k, (t0, t1) in enumerate(layout["invalid_spans"]):
                    ax.axvspan(t0, t1, color="tab:red", alpha=0.15,
                               label="creep_within_validity = 0 (note below)" if k == 0
                               else None)
                if layout["invalid_spans"]:
                    ax.legend(fontsize=7, loc="best")
        visible = [axes[r, col] for r in range(min(len(panels), n_rows))]
        if visible:
            visible[-1].set_xlabel("time [s]")
            visible[-1].xaxis.set_tick_params(labelbottom=True)
    constants = "; ".join(layout["constants"]) or "none"
    fig.suptitle(f"scene {scene.name}: {scene.description}\n"
                 + textwrap.fill(f"constant during the run: {constants}", 150), fontsize=9)
    bottom = 0.0
    if layout["invalid_spans"]:
        fig.text(0.5, 0.01, "shaded: " + textwrap.fill(VALIDITY_NOTE, 150), ha="center",
                 va="bottom", fontsize=8, color="tab:red")
        bottom = 0.45 / fig.get_figheight()
    fig.tight_layout(rect=(0.0, bottom, 1.0, 1.0 - 0.55 / fig.get_figheight()))
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

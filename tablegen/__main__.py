"""Command line: ``python -m tablegen build [--only NAME] [--resolution R] [--scheduler ADDR]``.

A build writes ``./tables-build/<name>.nc`` (``--output-dir`` to choose); the shipped
``tables/`` (bundled into the FMU) are replaced only with ``--replace-shipped``. Use a table
built elsewhere by pointing ``RAILCONTACT_TABLES_DIR`` at its directory.

Examples
--------
Build every (non-hidden, buildable) table into ``./tables-build`` on a local dask cluster::

    python -m tablegen build

One table, coarse, in-process (no cluster)::

    python -m tablegen build --only creep_modified_strip --resolution coarse \
        --scheduler synchronous

On an existing dask.distributed cluster (every worker must be able to ``import tablegen`` and
``import railcontact``: start the workers from the same checkout, e.g. with
``PYTHONPATH=<checkout>/fmu_src:<checkout>``, or an editable install of it)::

    python -m tablegen build --only creep_exact --resolution fine --scheduler tcp://host:8786

Replace the shipped table (then rebuild the FMU)::

    python -m tablegen build --only creep_modified_strip --replace-shipped

List the tables::

    python -m tablegen list
"""

from __future__ import annotations

import argparse
import shlex
import sys

from .registry import REGISTRY
from .spec import RESOLUTIONS

_WORKERS_RULE = ("A --scheduler's workers must be able to import tablegen and railcontact "
                 "(start them from this checkout: PYTHONPATH=<checkout>/fmu_src:<checkout>, "
                 "or an editable install).")


def _summary(name, res):
    """The line printed after a build: where, what was computed in this run, accuracy."""
    acc = ", ".join(f"{v}: max {a['max_abs_error']:.2e} rms {a['rms_error']:.2e}"
                    for v, a in res["accuracy"].items())
    done = []
    if res.get("n_reused_nodes"):
        done.append(f"{res['n_reused_nodes']} node values reused from --reuse-nodes")
    if res["n_resumed"]:
        done.append(f"{res['n_resumed']} cases resumed from an interrupted run")
    took = (f"{res['seconds']:.1f} s" if res["seconds"] >= 1 else
            f"{res['seconds'] * 1e3:.0f} ms")
    done.append(f"{res['n_computed']} cases computed in {took}"
                if res["n_computed"] else "nothing left to compute")
    return (f"{name}: {res['path']} ({res['size_bytes'] / 1024:.1f} KiB; {res['n_points']} "
            f"grid points + {res['n_check']} check points: " + ", ".join(done) + f"); {acc}")


def main(argv=None):
    from .build import build_table  # noqa: PLC0415

    parser = argparse.ArgumentParser(prog="python -m tablegen",
                                     description="Build the smooth railcontact tables.",
                                     epilog=_WORKERS_RULE)
    sub = parser.add_subparsers(dest="command", required=True)
    b = sub.add_parser(
        "build", help="build tables (all by default)",
        description="Build tables into ./tables-build (or --output-dir); the shipped tables/ "
                    "are replaced only with --replace-shipped. Use a table built elsewhere "
                    "with RAILCONTACT_TABLES_DIR=<its directory>.",
        epilog=_WORKERS_RULE)
    b.add_argument("--only", action="append", metavar="NAME",
                   help="table to build (repeatable); default: all non-hidden tables (on 2 "
                        "cores creep_exact takes 6-21 h from scratch, the others together "
                        "2-3 min: docs/tables.md)")
    b.add_argument("--resolution", default="default", choices=RESOLUTIONS)
    b.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="dask.distributed scheduler address (tcp://host:8786; its workers "
                        "must import tablegen and railcontact), or 'synchronous'; default: a "
                        "local cluster")
    b.add_argument("--workers", type=int, default=None,
                   help="processes of the local cluster (default: all cores)")
    where = b.add_mutually_exclusive_group()
    where.add_argument("--output-dir", default=None,
                       help="directory of the table files (default: ./tables-build, or "
                            "$TABLEGEN_OUTPUT_DIR)")
    where.add_argument("--replace-shipped", action="store_true",
                       help="write into the checkout's shipped tables/ (which build_fmu.py "
                            "bundles), replacing the files there")
    b.add_argument("--workdir", default=None,
                   help="where finished chunks are kept (resume after a failure)")
    b.add_argument("--progress", dest="progress", action="store_true", default=None)
    b.add_argument("--no-progress", dest="progress", action="store_false")
    b.add_argument("--reuse-nodes", default=None, metavar="FILE",
                   help="take the node values of an earlier build of the same table (same "
                        "method, or where the spec's reusable_points accepts its method) from "
                        "FILE at every grid point that is one of its nodes; compute the others "
                        "(a refined axis, a changed solver setting), the analytic limits and "
                        "the check points")
    c = sub.add_parser("check", help="re-measure a table file's accuracy on fresh points and "
                                     "update its attributes", epilog=_WORKERS_RULE)
    c.add_argument("--only", action="append", metavar="NAME", required=True)
    c.add_argument("--points", type=int, default=None, help="number of check points")
    c.add_argument("--seed", type=int, default=1)
    c.add_argument("--scheduler", default=None, metavar="ADDRESS")
    c.add_argument("--workers", type=int, default=None)
    c.add_argument("--output-dir", default=None,
                   help="directory of the table files (default: ./tables-build; the shipped "
                        "ones: --output-dir tables)")
    c.add_argument("--progress", dest="progress", action="store_true", default=None)
    c.add_argument("--no-progress", dest="progress", action="store_false")
    sub.add_parser("list", help="list the table specifications")
    args = parser.parse_args(argv)

    if args.command == "list":
        for name, spec in sorted(REGISTRY.items()):
            why = spec.available()
            state = "hidden" if spec.hidden else ("ok" if why is None else f"unavailable: {why}")
            print(f"{name:28s} {state:12s} {spec.title}")
        return 0

    command = "python -m tablegen " + " ".join(shlex.quote(a) for a in
                                               (argv if argv is not None else sys.argv[1:]))
    if args.command == "check":
        from pathlib import Path  # noqa: PLC0415

        from .build import SchedulerUnreachable, check_table  # noqa: PLC0415

        for name in args.only:
            if name not in REGISTRY:
                parser.error(f"--only must be one of {sorted(REGISTRY)}; got {name!r}")
            path = (Path(args.output_dir) / f"{name}.nc") if args.output_dir else None
            try:
                res = check_table(name, path, args.points, args.seed, args.scheduler,
                                  args.workers, progress=args.progress, command=command)
            except SchedulerUnreachable as exc:
                print(f"python -m tablegen: error: {exc}", file=sys.stderr)
                return 2
            print(f"{name}: " + ", ".join(f"{v}: max {a['max_abs_error']:.2e} rms "
                                          f"{a['rms_error']:.2e}" for v, a in res.items()))
        return 0
    import warnings  # noqa: PLC0415

    from railcontact.tables import TableAccuracyWarning  # noqa: PLC0415

    from .build import (SHIPPED_TABLES_DIR, SchedulerUnreachable,  # noqa: PLC0415
                        default_output_dir)

    names = args.only or [n for n, s in sorted(REGISTRY.items()) if not s.hidden]
    output_dir = SHIPPED_TABLES_DIR if args.replace_shipped else args.output_dir
    status = 0
    for name in names:
        spec = REGISTRY.get(name)
        if spec is None:
            parser.error(f"--only must be one of {sorted(REGISTRY)}; got {name!r}")
        why = spec.available()
        if why:
            print(f"{name}: skipped, {why}", file=sys.stderr)
            status = 1
            continue
        try:
            with warnings.catch_warnings():   # (said below, once, in the build's summary)
                warnings.simplefilter("ignore", TableAccuracyWarning)
                res = build_table(name, args.resolution, output_dir=output_dir,
                                  scheduler=args.scheduler, workers=args.workers,
                                  workdir=args.workdir, progress=args.progress,
                                  command=command, reuse_nodes=args.reuse_nodes)
        except SchedulerUnreachable as exc:
            print(f"python -m tablegen: error: {exc}", file=sys.stderr)
            return 2
        print(_summary(name, res))
        if (res["accuracy_versus_shipped"] or "").startswith("worse"):
            print(f"{name}: WARNING: {res['accuracy_versus_shipped']}", file=sys.stderr)
    if not args.replace_shipped:
        print(f"The shipped tables/ are unchanged. To use the tables built here, set "
              f"RAILCONTACT_TABLES_DIR={output_dir or default_output_dir()} (or rebuild with "
              "--replace-shipped).")
    return status


if __name__ == "__main__":
    sys.exit(main())

"""Command line: ``python -m tablegen build [--only NAME] [--resolution R] [--scheduler ADDR]``.

Examples
--------
Build every (non-hidden, buildable) table into ``tables/`` on a local dask cluster::

    python -m tablegen build

One table, coarse, in-process (no cluster)::

    python -m tablegen build --only creep_modified_strip --resolution coarse \
        --scheduler synchronous

On an existing dask.distributed cluster (workers must import railcontact and tablegen)::

    python -m tablegen build --only creep_exact --resolution fine --scheduler tcp://host:8786

List the tables::

    python -m tablegen list
"""

from __future__ import annotations

import argparse
import shlex
import sys

from .registry import REGISTRY
from .spec import RESOLUTIONS


def main(argv=None):
    from .build import build_table  # noqa: PLC0415

    parser = argparse.ArgumentParser(prog="python -m tablegen",
                                     description="Build the smooth railcontact tables.")
    sub = parser.add_subparsers(dest="command", required=True)
    b = sub.add_parser("build", help="build tables (all by default)")
    b.add_argument("--only", action="append", metavar="NAME",
                   help="table to build (repeatable); default: all non-hidden tables")
    b.add_argument("--resolution", default="default", choices=RESOLUTIONS)
    b.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="dask.distributed scheduler address, or 'synchronous'; default: a "
                        "local cluster")
    b.add_argument("--workers", type=int, default=None,
                   help="processes of the local cluster (default: all cores)")
    b.add_argument("--output-dir", default=None, help="default: the checkout's tables/")
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
                                     "update its attributes")
    c.add_argument("--only", action="append", metavar="NAME", required=True)
    c.add_argument("--points", type=int, default=None, help="number of check points")
    c.add_argument("--seed", type=int, default=1)
    c.add_argument("--scheduler", default=None, metavar="ADDRESS")
    c.add_argument("--workers", type=int, default=None)
    c.add_argument("--output-dir", default=None, help="directory of the table files")
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

        from .build import check_table  # noqa: PLC0415

        for name in args.only:
            if name not in REGISTRY:
                parser.error(f"--only must be one of {sorted(REGISTRY)}; got {name!r}")
            path = (Path(args.output_dir) / f"{name}.nc") if args.output_dir else None
            res = check_table(name, path, args.points, args.seed, args.scheduler,
                              args.workers, progress=args.progress, command=command)
            print(f"{name}: " + ", ".join(f"{v}: max {a['max_abs_error']:.2e} rms "
                                          f"{a['rms_error']:.2e}" for v, a in res.items()))
        return 0
    names = args.only or [n for n, s in sorted(REGISTRY.items()) if not s.hidden]
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
        res = build_table(name, args.resolution, output_dir=args.output_dir,
                          scheduler=args.scheduler, workers=args.workers, workdir=args.workdir,
                          progress=args.progress, command=command,
                          reuse_nodes=args.reuse_nodes)
        acc = ", ".join(f"{v}: max {a['max_abs_error']:.2e} rms {a['rms_error']:.2e}"
                        for v, a in res["accuracy"].items())
        print(f"{name}: {res['path']} ({res['size_bytes'] / 1024:.1f} KiB, "
              f"{res['n_points']} points + {res['n_check']} checks in {res['seconds']:.1f} s); "
              f"{acc}")
    return status


if __name__ == "__main__":
    sys.exit(main())

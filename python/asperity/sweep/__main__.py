"""python -m asperity.sweep (or `asperity sweep`, the C++ command that runs this module):
run a sweep (see --help)."""
from __future__ import annotations

import argparse
import json
import re
import signal
import sys
import tomllib

EPILOG = """\
examples:
  {prog} examples/sweeps/steel420_bolt_load.toml --out out/sweep
  {prog} examples/joints/steel420_two_bolts.toml \\
      --vary 'load.bolts.nut_factor ~ uniform(0.158, 0.267)' \\
      --vary 'joint.half[*].material.H ~ normal(5.8 GPa, 5 %)' \\
      --samples 1000 --seed 1 --method sobol --out out/sweep --scheduler tcp://host:8786

Key paths: dotted, [i] 1-based, [*] every element (as the case-file errors name keys).
Variations: grids 'LOW .. HIGH, N steps[, log]', uniform(LOW, HIGH), normal(MEAN, SD or
N %), choice(A, B, ...). Exit codes: 0 done (failed samples are in failures.csv),
2 bad input (refused before any work), 3 every sample failed, 1 anything else (a file
that cannot be written, every Dask worker gone for --worker-timeout), 130 SIGINT, 143
SIGTERM (the partial output removed)."""


class _Parser(argparse.ArgumentParser):
    """One line for a usage error (as the C++ commands), not the whole usage block."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} ({self.prog} --help lists the options)\n")


# Dask's address forms: tcp://HOST:PORT (and tls://, ucx://, ws://, wss://), inproc://...
_SCHEDULER = re.compile(r"^(tcp|tls|ucx|ws|wss)://[^:/\s]+:\d+/?$|^inproc://\S+$")


def _on_sigterm(signum, frame):
    from . import engine

    engine.request_termination()


def _terminated():
    from .engine import Terminated

    return Terminated


def main(argv=None, prog: str = "python -m asperity.sweep") -> int:
    """Runs the command with the arguments `argv` (default: sys.argv[1:]); `prog` names it
    in the usage and help (`asperity sweep` when the C++ command runs it)."""
    try:
        previous = signal.signal(signal.SIGTERM, _on_sigterm)
    except ValueError:  # not the main thread: SIGTERM keeps its handler
        previous = None
    try:
        return _main(argv, prog)
    except KeyboardInterrupt:
        print("asperity sweep: interrupted (SIGINT); the output directory is left as it was",
              file=sys.stderr)
        return 130
    except _terminated():
        print("asperity sweep: terminated (SIGTERM); the output directory is left as it was",
              file=sys.stderr)
        return 143
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


def _main(argv, prog) -> int:
    ap = _Parser(
        prog=prog, epilog=EPILOG.format(prog=prog),
        formatter_class=argparse.RawDescriptionHelpFormatter,
        description="Sweeps and Monte Carlo of asperity cases on Dask: a sweep file, or a "
        "case file with --vary.")
    ap.add_argument("file", help="a sweep file (with `case = ...`) or a case file")
    ap.add_argument("--vary", action="append", default=[], metavar="'KEY ~ DIST'",
                    help="a varied key: 'KEY ~ uniform|normal|choice(...)' or 'KEY = GRID'")
    ap.add_argument("--set", action="append", default=[], metavar="'KEY = VALUE'",
                    help="a value for every sample (TOML value: 'load.preload = \"526 N\"')")
    ap.add_argument("--unset", action="append", default=[], metavar="KEY")
    ap.add_argument("--samples", type=int, help="draws per grid point")
    ap.add_argument("--seed", type=int)
    ap.add_argument("--method", choices=("random", "sobol", "lhs"))
    ap.add_argument("--out", required=True, help="output directory (replaced as a whole)")
    ap.add_argument("--scheduler", help="tcp://HOST:PORT of a running Dask scheduler "
                    "(default: DASK_SCHEDULER_ADDRESS, else a LocalCluster)")
    ap.add_argument("--workers", type=int, help="LocalCluster workers (default: one per core)")
    ap.add_argument("--threads-per-worker", type=int, default=1)
    ap.add_argument("--worker-timeout", type=float, default=60.0, metavar="SECONDS",
                    help="give up when no Dask worker is connected for this long (default 60)")
    ap.add_argument("--serial", action="store_true", help="no Dask: run in this process")
    ap.add_argument("--batch", type=int, help="samples per task (default: automatic)")
    ap.add_argument("--block", type=int, default=1024, help="samples per file part")
    ap.add_argument("--format", default="netcdf,parquet", help="netcdf, parquet or both")
    ap.add_argument("--no-plots", action="store_true")
    ap.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                    help="progress bar (default: when stderr is a terminal)")
    a = ap.parse_args(argv)

    from . import spec
    from .engine import ClusterError, OutputError, run
    from .sweepfile import load

    try:
        head = spec.read_toml(a.file)
        if "case" in head and isinstance(head.get("case"), str):
            if a.vary or a.set or a.unset:
                raise spec.SweepError(f"{a.file}: a sweep file; --vary/--set/--unset go with a "
                                      "case file (or into the sweep file)")
            s = load(a.file, samples=a.samples, seed=a.seed, method=a.method)
        else:
            vary = dict(spec.parse_vary_flag(v) for v in a.vary)
            set_ = {}
            for item in a.set:
                key, _, value = item.partition("=")
                try:
                    set_[key.strip()] = tomllib.loads(f"v = {value}")["v"]
                except tomllib.TOMLDecodeError:
                    raise spec.SweepError(f"--set {item!r}: write KEY = TOML value, e.g. "
                                          "'load.preload = \"526 N\"'") from None
            s = spec.build(a.file, vary, samples=a.samples, seed=a.seed or 0,
                           method=a.method or "random", set_=set_, unset=a.unset)
        if a.batch is not None and a.batch < 1:
            raise spec.SweepError(f"--batch {a.batch}: a positive integer")
        if a.workers is not None and a.workers < 1:
            raise spec.SweepError(f"--workers {a.workers}: a positive integer")
        if a.threads_per_worker < 1:
            raise spec.SweepError(f"--threads-per-worker {a.threads_per_worker}: a positive "
                                  "integer")
        if a.scheduler is not None and not _SCHEDULER.match(a.scheduler):
            raise spec.SweepError(f"--scheduler {a.scheduler!r}: give the address of a running "
                                  "Dask scheduler, tcp://HOST:PORT (e.g. tcp://127.0.0.1:8786)")
        formats = [f.strip() for f in a.format.split(",") if f.strip()]
        if formats == ["both"]:
            formats = ["netcdf", "parquet"]
        info = run(s, a.out, scheduler=a.scheduler, workers=a.workers,
                   threads_per_worker=a.threads_per_worker, serial=a.serial, batch=a.batch,
                   block=a.block, formats=formats,
                   plots=not a.no_plots, progress=a.progress, worker_timeout=a.worker_timeout)
    except spec.SweepError as e:
        print(f"asperity sweep: error: {e}", file=sys.stderr)
        return 2
    except (OutputError, ClusterError) as e:
        print(f"asperity sweep: error: {e}", file=sys.stderr)
        return 1
    except Exception as e:  # noqa: BLE001
        from .. import _core

        if isinstance(e, _core.InvalidInput):
            print(f"asperity sweep: error: {e}", file=sys.stderr)
            return 2
        print(f"asperity sweep: {type(e).__name__}: {e}", file=sys.stderr)
        return 1
    print(json.dumps({k: info[k] for k in ("samples", "failed", "engine", "elapsed_s",
                                           "samples_per_s")}))
    print(f"wrote {a.out}: sweep.json, summary.csv, sensitivity.csv, failures.csv, "
          + ", ".join(info["files"][:3]) + (" ..." if len(info["files"]) > 3 else ""))
    return 3 if info["failed"] == info["samples"] else 0


if __name__ == "__main__":
    sys.exit(main())

"""Running a sweep: the samples in batches on a Dask cluster (or serially), results
streamed to disk in blocks, in sample order, with bounded memory.

Reproducibility: every sample's inputs are derived in the client from the seed before it
is sent (:meth:`Sweep.sample_inputs`); a batch is a pure function of its inputs, so a
batch that Dask re-runs after a worker died gives the same numbers, and the result does
not depend on the number of workers or on which worker ran what.
"""
from __future__ import annotations

import contextlib
import csv
import dataclasses
import json
import os
import re
import shutil
import sys
import time
import traceback
from typing import Optional

import numpy as np

from .. import _core
from .runners import runner_for
from .spec import Sweep, SweepError, apply_assignments, to_toml

MARKER = ".asperity-output"  # as the C++ commands' output directories (output_dir.hpp)
MARKER_LIST_HEADER = "files:"  # kOutputMarkerListHeader: the files listed after it


# --------------------------------------------------------------------------- worker side

def _in_dask_worker_process(client_pid: Optional[int]) -> bool:
    """True in a Dask worker that runs in a process of its own (not the caller's)."""
    if client_pid is None or os.getpid() == client_pid:
        return False
    try:
        from distributed import get_worker

        get_worker()
        return True
    except (ImportError, ValueError):
        return False


def run_batch(kind: str, base_dir: str, case: dict, items: list,
              client_pid: Optional[int] = None) -> list:
    """Runs ``[(sample, assignments)]`` (each sample's values written into the base
    ``case``, :func:`spec.apply_assignments`); returns ``[(sample, outputs or None,
    error or "")]``. A sample that fails (asperity.Error: bad input drawn, numerical
    failure; or any other exception) is returned with its error, never dropped.
    ``client_pid``: the process that submitted the batch; a worker in another process
    runs each sample on one library thread."""
    runner = runner_for(kind)
    if _in_dask_worker_process(client_pid):
        # One library thread per sample: the samples are spread over the workers' cores
        # already, and a second team of threads per core would only compete with them.
        # (A worker inside the caller's own process leaves the caller's setting alone.)
        _core.set_thread_count(1)
    out = []
    for s, assignments in items:
        try:
            text = to_toml(apply_assignments(case, assignments))
            out.append((s, runner.run(text, base_dir), ""))
        except _core.Error as e:
            out.append((s, None, f"{type(e).__name__}: {e}"))
        except Exception as e:  # noqa: BLE001  (recorded with the sample, not dropped)
            out.append((s, None, f"{type(e).__name__}: {e}"))
    return out


# --------------------------------------------------------------------------- output

class Terminated(BaseException):
    """SIGTERM (python -m asperity.sweep): the run stops and removes its partial output."""


_termination = {"requested": False, "in_loop": False}


def request_termination() -> None:
    """The SIGTERM handler's action. Outside the sample loop it raises at once; inside,
    the loop raises after the current batch (a signal raised anywhere could land in a
    finalizer, where Python prints the exception and drops it)."""
    _termination["requested"] = True
    if not _termination["in_loop"]:
        raise Terminated()


def _check_termination() -> None:
    if _termination["requested"]:
        raise Terminated()


# Seconds between checks of the cluster while no batch finishes.
HEARTBEAT_S = 1.0


class ClusterError(Exception):
    """The Dask cluster cannot go on (every worker gone, the scheduler lost)."""


def address_of(client) -> str:
    try:
        return str(client.scheduler.address)
    except Exception:  # noqa: BLE001
        return "(unknown address)"


class OutputError(Exception):
    """A file of the output could not be written (disk full, permissions): the message
    names the file and the reason."""


@contextlib.contextmanager
def writing(path: str):
    """Turns an OSError while writing ``path`` into an :class:`OutputError` naming it
    (``OSError [Errno 28]`` alone names no file when the disk fills during a write)."""
    try:
        yield
    except OSError as e:
        name = e.filename or path
        raise OutputError(f"cannot write {name}: {e.strerror or e}") from None


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True  # another user's process
    return True


def remove_stale_partials(out: str) -> list:
    """Removes ``.NAME.partial-PID`` (and ``.NAME.partial-PID.old``) siblings of ``out``
    left by a run that was killed: those whose process is gone and that hold the
    asperity marker. Returns the removed paths."""
    parent, base = os.path.split(os.path.abspath(out))
    pattern = re.compile(r"^\." + re.escape(base) + r"\.partial-(\d+)(\.old)?$")
    removed = []
    try:
        entries = os.listdir(parent)
    except OSError:
        return removed
    for name in entries:
        m = pattern.match(name)
        if not m or _pid_alive(int(m.group(1))):
            continue
        path = os.path.join(parent, name)
        if os.path.isdir(path) and not os.path.islink(path) and os.path.exists(
                os.path.join(path, MARKER)):
            shutil.rmtree(path, ignore_errors=True)
            removed.append(path)
    return removed


def _foreign_entries(out: str) -> list:
    """Entries of ``out`` (relative, directories with a trailing '/') that the marker does
    not list: the user's files (as src/joint/output_dir.cpp)."""
    listed = set()
    try:
        with open(os.path.join(out, MARKER)) as f:
            lines = f.read().splitlines()
        if MARKER_LIST_HEADER not in lines and lines[:1] == [
                "written by asperity sweep; replaced as a whole by the next run"]:
            # A marker of a sweep before the list (issue 21): its directory was replaced
            # as a whole, so everything in it is taken as asperity's.
            return []
        if MARKER_LIST_HEADER in lines:
            listed = {x for x in lines[lines.index(MARKER_LIST_HEADER) + 1:] if x}
    except (OSError, UnicodeDecodeError):
        pass
    other = []
    for root, dirs, files in os.walk(out):
        rel_root = os.path.relpath(root, out)
        for d in list(dirs):
            rel = os.path.normpath(os.path.join(rel_root, d))
            if not any(x.startswith(rel + "/") for x in listed):
                other.append(rel + "/")
                dirs.remove(d)
        for f in files:
            rel = os.path.normpath(os.path.join(rel_root, f))
            if rel != MARKER and rel not in listed:
                other.append(rel)
    return sorted(other)


def prepare_out_dir(out: str) -> str:
    """Refuses an existing directory holding files that asperity did not write (named, as
    the C++ commands do); removes stale partial directories of killed runs; returns the
    temporary sibling to write into (renamed over ``out`` at the end)."""
    out = os.path.abspath(out)
    if os.path.islink(out):
        raise SweepError(f"--out {out}: a symbolic link; give a directory path (asperity "
                         "replaces the output directory as a whole)")
    if os.path.exists(out):
        if not os.path.isdir(out):
            raise SweepError(f"--out {out}: exists and is not a directory")
        other = _foreign_entries(out) if os.listdir(out) else []
        if other:
            names = ", ".join(other[:5]) + (f" and {len(other) - 5} more" if len(other) > 5
                                            else "")
            if not os.path.exists(os.path.join(out, MARKER)):
                raise SweepError(f"--out {out}: a directory that asperity did not write (files "
                                 f"but no {MARKER} marker: {names}); asperity replaces its "
                                 "output directory as a whole, so it refuses to touch it: "
                                 "choose another --out or remove the directory yourself")
            raise SweepError(f"--out {out}: holds files that asperity did not write (its "
                             f"{MARKER} marker does not list them): {names}; asperity replaces "
                             "its output directory as a whole, so it refuses: move them out or "
                             "choose another --out")
    parent = os.path.dirname(out)
    try:
        os.makedirs(parent, exist_ok=True)
        remove_stale_partials(out)
        tmp = os.path.join(parent, f".{os.path.basename(out)}.partial-{os.getpid()}")
        if os.path.exists(tmp):
            shutil.rmtree(tmp)
        os.makedirs(os.path.join(tmp, "samples"))
        with open(os.path.join(tmp, MARKER), "w") as f:
            f.write("written by asperity sweep; replaced as a whole by the next run\n")
    except OSError as e:
        raise SweepError(f"--out {out}: cannot be written: {e.strerror}") from None
    return tmp


def write_marker(tmp: str) -> None:
    """The marker with the list of files this run wrote (as the C++ commands')."""
    files = []
    for root, _, names in os.walk(tmp):
        for n in names:
            rel = os.path.relpath(os.path.join(root, n), tmp)
            if rel != MARKER:
                files.append(rel.replace(os.sep, "/"))
    path = os.path.join(tmp, MARKER)
    with writing(path), open(path, "w") as f:
        f.write("written by asperity sweep; replaced as a whole by the next run\n"
                + MARKER_LIST_HEADER + "\n" + "".join(x + "\n" for x in sorted(files)))


def finish_out_dir(tmp: str, out: str) -> None:
    out = os.path.abspath(out)
    if os.path.exists(out):
        old = tmp + ".old"
        os.rename(out, old)
        os.rename(tmp, out)
        shutil.rmtree(old)
    else:
        os.rename(tmp, out)


@dataclasses.dataclass
class Schema:
    """Output names, their dims beyond ``sample`` and shapes (from the base case's run)."""

    names: list
    dims: dict
    shapes: dict
    sizes: dict  # dim name -> size
    attrs: dict = dataclasses.field(default_factory=dict)  # name -> CF units, long_name
    coords: dict = dataclasses.field(default_factory=dict)  # dim -> (values, attrs)


def schema_from(runner, outputs: dict, text: str = "") -> Schema:
    names = list(outputs)
    dims = {k: runner.dims(k) for k in names}
    shapes = {k: np.shape(outputs[k]) for k in names}
    sizes = {}
    for k in names:
        for d, n in zip(dims[k], shapes[k]):
            if sizes.setdefault(d, n) != n:
                raise AssertionError(f"dimension {d} of {k}: {n} against {sizes[d]}")
    attrs = {k: (runner.attrs(k) if hasattr(runner, "attrs") else {"units": "1",
                                                                    "long_name": k})
             for k in names}
    coords = {}
    for d, (values, a) in (runner.coords(outputs, text) if hasattr(runner, "coords")
                           else {}).items():
        if d in sizes and np.shape(values) == (sizes[d],):
            coords[d] = (np.asarray(values, dtype=float), a)
    for d, n in sizes.items():  # no value of its own: the 1-based number
        coords.setdefault(d, (np.arange(1, n + 1), {"units": "1", "long_name":
                                                    f"{d.replace('_', ' ')} number (1-based)"}))
    return Schema(names, dims, shapes, sizes, attrs, coords)


def varied_attrs(v) -> dict:
    """CF attributes of a varied input's coordinate (its values are SI)."""
    units = "1"
    if v.kind is not None and v.kind.kind == "quantity":
        units = si_units(v.kind.dimension)
    return {"units": units, "long_name": f"varied input {v.key} ({v.text})"}


_NAMED_UNITS = {(0, 0, 0): "1", (1, 0, 0): "m", (2, 0, 0): "m2", (1, 1, -2): "N",
                (-1, 1, -2): "Pa", (2, 1, -2): "J", (0, 1, -2): "N m-1", (0, 0, -1): "Hz",
                (0, 1, 0): "kg", (0, 0, 1): "s", (-2, 0, 0): "m-2", (1, 0, -1): "m s-1",
                (0, 1, -1): "kg s-1"}


def si_units(dim) -> str:
    """UDUNITS text of an asperity.Dimension in SI (N, Pa, J where they apply)."""
    key = (dim.m, dim.kg, dim.s)
    if key in _NAMED_UNITS:
        return _NAMED_UNITS[key]
    return " ".join(f"{u}{'' if e == 1 else e}" for u, e in (("kg", dim.kg), ("m", dim.m),
                                                              ("s", dim.s)) if e)


def global_attrs(sweep: Sweep, engine: str = "") -> dict:
    """The global attributes of every NetCDF part (CF-1.10 and the sweep's provenance)."""
    import datetime

    from .. import __version__

    return {
        "Conventions": "CF-1.10",
        "title": f"asperity sweep of {os.path.basename(sweep.case_path)}",
        "source": f"asperity {__version__}",
        "asperity_version": __version__,
        "case_file": os.path.abspath(sweep.case_path),
        "case_kind": sweep.kind,
        "method": sweep.method,
        "seed": int(sweep.seed),
        "samples": int(sweep.size),
        "varied": "; ".join(f"{v.key} = {v.text}" for v in sweep.variations),
        "date_created": datetime.datetime.now(datetime.timezone.utc).strftime(
            "%Y-%m-%dT%H:%M:%SZ"),
        "history": "python -m asperity.sweep" + (f" ({engine})" if engine else ""),
    }


class BlockWriter:
    """Collects samples in order and writes every ``block`` of them as
    ``samples/part-NNNNN.nc`` (NetCDF, scipy engine) and a row group of
    ``samples.parquet``; failures go to ``failures.csv`` as they come."""

    def __init__(self, tmp: str, sweep: Sweep, schema: Schema, block: int, formats,
                 attrs: dict | None = None):
        self.tmp, self.sweep, self.schema, self.block = tmp, sweep, schema, block
        self.attrs = attrs or {}
        self.formats = set(formats)
        self.parts: list[str] = []
        self.rows: list = []  # (sample, inputs, outputs, error), in sample order
        self.failed = 0
        self.written = 0
        self._parquet = None
        self._fail_path = os.path.join(tmp, "failures.csv")
        with writing(self._fail_path):
            self._fail_file = open(self._fail_path, "w", newline="")
            self._fail = csv.writer(self._fail_file)
            self._fail.writerow(["sample"] + [v.key for v in sweep.variations] + ["error"])

    def add(self, sample: int, inputs: list, outputs, error: str):
        if outputs is not None:
            try:
                outputs = self._conform(outputs)
            except ValueError as e:
                outputs, error = None, f"ShapeError: {e}"
        if outputs is None:
            self.failed += 1
            with writing(self._fail_path):
                self._fail.writerow([sample] + [val.toml for _, val in inputs] + [error])
        self.rows.append((sample, inputs, outputs, error))
        if len(self.rows) >= self.block:
            self.flush()

    def _conform(self, outputs: dict) -> dict:
        out = {}
        for k in self.schema.names:
            a = np.asarray(outputs.get(k, np.full(self.schema.shapes[k], np.nan)), dtype=float)
            if a.shape != self.schema.shapes[k]:
                raise ValueError(f"{k} has shape {a.shape}, the base case's {self.schema.shapes[k]}"
                                 " (a varied key changed the number of load cases or amplitudes)")
            out[k] = a
        return out

    def flush(self):
        if not self.rows:
            return
        import xarray as xr

        rows, self.rows = self.rows, []
        n = len(rows)
        samples = np.array([r[0] for r in rows], dtype=np.int64)
        data = {}
        for k in self.schema.names:
            a = np.full((n,) + self.schema.shapes[k], np.nan)
            for i, r in enumerate(rows):
                if r[2] is not None:
                    a[i] = r[2][k]
            data[k] = (("sample",) + self.schema.dims[k], a, self.schema.attrs.get(k, {}))
        data["ok"] = (("sample",), np.array([r[2] is not None for r in rows], dtype=np.int8),
                      {"units": "1", "long_name": "sample succeeded (1) or failed (0)"})
        data["error"] = (("sample",), np.array([r[3] for r in rows], dtype=object).astype(str),
                         {"long_name": "error of a failed sample (empty when it succeeded)"})
        coords = {"sample": (("sample",), samples, {"units": "1", "long_name":
                                                     "sample number (0-based, in draw order)"})}
        for d, (values, a) in self.schema.coords.items():
            coords[d] = ((d,), values, a)
        for j, v in enumerate(self.sweep.variations):
            vals = [r[1][j][1].coord for r in rows]
            coords[v.key] = (("sample",), np.array(vals, dtype=str if isinstance(vals[0], str)
                                                   else float), varied_attrs(v))
        ds = xr.Dataset(data, coords=coords, attrs=self.attrs)
        if "netcdf" in self.formats:
            path = os.path.join(self.tmp, "samples", f"part-{len(self.parts):05d}.nc")
            with writing(path):
                ds.to_netcdf(path, engine="scipy")
            self.parts.append(path)
        if "parquet" in self.formats:
            with writing(os.path.join(self.tmp, "samples.parquet")):
                self._write_parquet(ds)
        self.written += n
        with writing(self._fail_path):
            self._fail_file.flush()

    def _write_parquet(self, ds):
        import pyarrow as pa
        import pyarrow.parquet as pq

        cols = {"sample": ds["sample"].values}
        for v in self.sweep.variations:
            cols[v.key] = ds[v.key].values
        cols["ok"] = ds["ok"].values
        cols["error"] = ds["error"].values.astype(str)
        for k in self.schema.names:
            a = ds[k].values
            dims = self.schema.dims[k]
            if not dims:
                cols[k] = a
            for idx in np.ndindex(*a.shape[1:]) if dims else []:
                name = k + "[" + ",".join(f"{d}={i + 1}" for d, i in zip(dims, idx)) + "]"
                cols[name] = a[(slice(None),) + idx]
        table = pa.table(cols)
        if self._parquet is None:
            self._parquet = pq.ParquetWriter(os.path.join(self.tmp, "samples.parquet"),
                                              table.schema)
        self._parquet.write_table(table)

    def close(self):
        self.flush()
        if self._parquet is not None:
            with writing(os.path.join(self.tmp, "samples.parquet")):
                self._parquet.close()
        with writing(self._fail_path):
            self._fail_file.close()


# --------------------------------------------------------------------------- progress

class Progress:
    """A one-line progress bar on stderr when it is a terminal (else silent)."""

    def __init__(self, total: int, enabled: bool | None = None, stream=None):
        self.stream = stream or sys.stderr
        self.enabled = self.stream.isatty() if enabled is None else enabled
        self.total, self.done, self.failed = total, 0, 0
        self.t0 = time.monotonic()
        self._last = 0.0

    def update(self, done: int, failed: int):
        self.done, self.failed = done, failed
        now = time.monotonic()
        if self.enabled and (now - self._last > 0.2 or done == self.total):
            self._last = now
            w = 30
            f = int(w * done / self.total) if self.total else w
            rate = done / max(now - self.t0, 1e-9)
            self.stream.write(f"\r[{'#' * f}{'.' * (w - f)}] {done}/{self.total} samples, "
                              f"{failed} failed, {rate:.1f}/s ")
            self.stream.flush()

    def close(self):
        if self.enabled:
            self.stream.write("\n")
            self.stream.flush()


# --------------------------------------------------------------------------- client

def connect(scheduler: str | None = None, workers: int | None = None,
            threads_per_worker: int = 1):
    """A ``distributed.Client``: to ``scheduler`` (tcp://HOST:PORT) or
    DASK_SCHEDULER_ADDRESS when given, else a LocalCluster with ``workers`` processes
    (default: one per core) of ``threads_per_worker`` threads."""
    import logging

    from distributed import Client, LocalCluster

    address = scheduler or os.environ.get("DASK_SCHEDULER_ADDRESS") or None
    if address:
        try:
            return Client(address, timeout="20s")
        except (OSError, TimeoutError) as e:
            raise SweepError(f"--scheduler {address}: cannot connect: {e}") from None
    n = workers or os.cpu_count() or 1
    cluster = LocalCluster(n_workers=n, threads_per_worker=threads_per_worker, processes=True,
                           dashboard_address=None, silence_logs=logging.ERROR)
    return Client(cluster)


def preflight(sweep: Sweep):
    """Everything checked before any work: the case with each variation at its extremes
    (the case parser), then the base case run once in the client (its outputs fix the
    output schema). Returns (runner, schema)."""
    runner = runner_for(sweep.kind)
    sweep.check(lambda c: runner.check(to_toml(c), sweep.base_dir))
    text = to_toml(sweep.case)
    try:
        base = runner.run(text, sweep.base_dir)
    except _core.Error as e:
        raise SweepError(f"{sweep.case_path}: the case itself (no variation) fails: {e}") from None
    return runner, schema_from(runner, base, text)


def default_batch(sweep: Sweep, nthreads: int) -> int:
    """Samples per task: about 8 tasks per thread, at most 32 samples (a joint sample
    takes ~15 ms), at least 1."""
    return int(max(1, min(32, sweep.size // max(8 * nthreads, 1))))


def run(sweep: Sweep, out: str, *, scheduler: str | None = None, workers: int | None = None,
        threads_per_worker: int = 1, serial: bool = False, batch: int | None = None,
        block: int = 1024, formats=("netcdf", "parquet"), plots: bool = True,
        progress: bool | None = None, client=None, on_progress=None,
        worker_timeout: float = 60.0) -> dict:
    """Runs the sweep into directory ``out`` (replaced as a whole: written to a temporary
    sibling, renamed at the end, removed on error) and returns a dict (the content of
    ``out/sweep.json``). ``serial`` runs in this process without Dask (the reference).
    ``on_progress(done, total)`` is called after each batch (tests use it).
    ``worker_timeout``: seconds without any Dask worker before :class:`ClusterError`.
    A file that cannot be written (disk full) raises :class:`OutputError` naming it."""
    formats = tuple(formats)
    for f in formats:
        if f not in ("netcdf", "parquet"):
            raise SweepError(f"--format {f}: allowed: netcdf, parquet")
    if not formats:
        raise SweepError("--format: at least one of netcdf, parquet")
    if not (isinstance(block, int) and block >= 1):
        raise SweepError(f"block = {block!r}: a positive integer")
    if not (worker_timeout > 0 and np.isfinite(worker_timeout)):
        raise SweepError(f"--worker-timeout {worker_timeout!r}: a positive number of seconds")
    runner, schema = preflight(sweep)
    tmp = prepare_out_dir(out)
    own_client = False
    try:
        t0 = time.monotonic()
        if serial:
            nthreads, engine = 1, "serial"
        else:
            if client is None:
                client = connect(scheduler, workers, threads_per_worker)
                own_client = True
            nthreads = max(sum(client.nthreads().values()), 1)
            engine = f"dask ({client.scheduler.address}, {len(client.nthreads())} workers)"
        b = batch or default_batch(sweep, nthreads)
        writer = BlockWriter(tmp, sweep, schema, block, formats, global_attrs(sweep, engine))
        bar = Progress(sweep.size, progress)
        n_batches = -(-sweep.size // b)
        cache: dict = {}

        def make(j):
            lo, hi = j * b, min((j + 1) * b, sweep.size)
            inputs = list(sweep.sample_inputs(lo, hi, cache))
            items = [(s, sweep.assignments(vals)) for s, vals in inputs]
            return [vals for _, vals in inputs], items

        pending: dict = {}  # batch -> inputs, for the batches sent and not yet written
        done: dict = {}  # batch -> results, finished but not yet written (out of order)
        next_write = 0
        count = 0

        def write_ready():
            nonlocal next_write, count
            _check_termination()
            while next_write in done:
                res = done.pop(next_write)
                inputs = pending.pop(next_write)
                for (s, o, e), vals in zip(res, inputs):
                    writer.add(s, vals, o, e)
                count += len(res)
                next_write += 1
            bar.update(count, writer.failed)
            if on_progress:
                on_progress(count, sweep.size)

        _termination["in_loop"] = True
        if serial:
            for j in range(n_batches):
                inputs, items = make(j)
                pending[j] = inputs
                done[j] = run_batch(sweep.kind, sweep.base_dir, sweep.case, items)
                write_ready()
        else:
            from distributed import KilledWorker, wait

            # At most `ahead` batches beyond the oldest unwritten one are in flight or
            # waiting: memory stays bounded whatever the number of samples.
            ahead = max(4 * nthreads, 8)
            sent = 0
            futures: dict = {}  # key -> (future, batch)

            def submit_more():
                nonlocal sent
                while sent < n_batches and sent < next_write + ahead:
                    inputs, items = make(sent)
                    pending[sent] = inputs
                    f = client.submit(run_batch, sweep.kind, sweep.base_dir, sweep.case, items,
                                      os.getpid(), pure=False)
                    futures[f.key] = (f, sent)
                    sent += 1

            submit_more()
            no_workers_since = None

            def heartbeat():
                # Tasks wait for a worker silently when every worker is gone (also a
                # finished task whose result died with its worker: it is recomputed); say so
                # after worker_timeout seconds instead of waiting forever.
                nonlocal no_workers_since
                try:
                    workers_now = len(client.nthreads())
                except Exception as e:  # noqa: BLE001  (the scheduler itself is gone)
                    raise ClusterError(f"lost the Dask scheduler {address_of(client)}: "
                                       f"{type(e).__name__}: {e}; {count} of "
                                       f"{sweep.size} samples done") from None
                if workers_now:
                    no_workers_since = None
                elif no_workers_since is None:
                    no_workers_since = time.monotonic()
                elif time.monotonic() - no_workers_since >= worker_timeout:
                    raise ClusterError(
                        f"no Dask worker connected to the scheduler "
                        f"{address_of(client)} for {worker_timeout:g} s (every worker "
                        f"gone); {count} of {sweep.size} samples done: start workers "
                        "(dask worker ADDRESS) and run again, or raise --worker-timeout")

            def result_of(f):
                while True:
                    try:
                        return f.result(timeout=HEARTBEAT_S)
                    except TimeoutError:
                        _check_termination()
                        heartbeat()

            while futures:
                try:
                    finished = wait([f for f, _ in futures.values()], timeout=HEARTBEAT_S,
                                    return_when="FIRST_COMPLETED").done
                except TimeoutError:
                    finished = set()
                _check_termination()
                if not finished:
                    heartbeat()
                    continue
                for f in sorted(finished, key=lambda f: futures[f.key][1]):
                    _, j = futures.pop(f.key)
                    try:
                        done[j] = result_of(f)
                    except KilledWorker as e:
                        # The batch took down every worker that ran it (Dask's allowed
                        # failures): its samples are recorded as failed, the rest goes on.
                        done[j] = [(s, None, f"KilledWorker: {e}")
                                   for s in range(j * b, min((j + 1) * b, sweep.size))]
                    f.release()
                write_ready()
                submit_more()
        _termination["in_loop"] = False
        _check_termination()
        writer.close()
        bar.close()
        elapsed = time.monotonic() - t0
        from .stats import summarize

        info = {
            "case": os.path.abspath(sweep.case_path),
            "kind": sweep.kind,
            "method": sweep.method,
            "seed": sweep.seed,
            "samples_per_grid_point": sweep.samples,
            "grid_points": sweep.grid_points,
            "samples": sweep.size,
            "failed": writer.failed,
            "varied": {v.key: v.text for v in sweep.variations},
            "engine": engine,
            "batch": b,
            "elapsed_s": elapsed,
            "samples_per_s": sweep.size / elapsed if elapsed > 0 else None,
            "outputs": {k: list(schema.dims[k]) for k in schema.names},
            "files": sorted(os.path.relpath(p, tmp) for p in writer.parts)
            + (["samples.parquet"] if "parquet" in formats else []),
        }
        summarize(tmp, sweep, schema, writer.parts, plots=plots and "netcdf" in formats,
                  info=info)
        path = os.path.join(tmp, "sweep.json")
        with writing(path), open(path, "w") as f:
            json.dump(info, f, indent=2)
        write_marker(tmp)
        with writing(out):
            finish_out_dir(tmp, out)
        return info
    except BaseException:
        _termination["in_loop"] = False
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    finally:
        _termination.update(in_loop=False, requested=False)
        if own_client:
            cluster = client.cluster
            client.close()
            if cluster is not None:
                cluster.close()


def open_results(out: str):
    """The samples of a finished sweep as one xarray Dataset (lazy, over its NetCDF parts):
    dimension ``sample``, the varied keys as coordinates, ``ok`` and ``error``."""
    import glob

    import xarray as xr

    parts = sorted(glob.glob(os.path.join(out, "samples", "part-*.nc")))
    if not parts:
        raise SweepError(f"{out}: no samples/part-*.nc (not a sweep output, or written "
                         "without --format netcdf)")
    return xr.open_mfdataset(parts, combine="nested", concat_dim="sample", engine="scipy",
                             data_vars="all", coords="different", compat="equals")


def format_error(e: BaseException) -> str:
    return "".join(traceback.format_exception_only(type(e), e)).strip()

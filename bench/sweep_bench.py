#!/usr/bin/env python3
"""Speed of asperity.sweep (a benchmark, not a test): N `predict` samples of the chapter 5
joint (examples/sweeps/steel420_bolt_load.toml: nut factor and torques drawn, 4 load
cases, 7 joint amplitudes and the 6.75 um PZT amplitude each) on a real `dask scheduler`
with worker processes on loopback, one fresh cluster per configuration:

  1x1  one worker, one thread    (the same-run reference)
  2x1  two workers, one thread each   (issue 12's target: >= 1.7 x 1x1)
  1x2  one worker, two threads   (scales only if the C++ call releases the GIL)

Prints samples/s per configuration, its ratio to 1x1, the CPU time the workers got
(their share of the cores: on a shared machine it, not the code, may limit the ratio) and
the client's resident memory (RSS of this process after the first batch and its peak,
polled after every batch; scheduler and workers are other processes). Usage: bench/sweep_bench.py [--samples 10000] [--configs 1x1,2x1,1x2]
(PYTHONPATH must reach the asperity package, as for the tests).
"""
import argparse
import os
import pathlib
import socket
import subprocess
import sys
import tempfile
import time

import psutil

from asperity import sweep

ROOT = pathlib.Path(__file__).resolve().parents[1]


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_cluster(workers, threads):
    from distributed import Client

    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    log = open(os.devnull, "w")
    procs = [subprocess.Popen([sys.executable, "-m", "dask", "scheduler", "--host", "127.0.0.1",
                               "--port", str(port), "--no-dashboard"], stdout=log, stderr=log)]
    for _ in range(workers):
        procs.append(subprocess.Popen(
            [sys.executable, "-m", "dask", "worker", address, "--nthreads", str(threads),
             "--no-nanny", "--host", "127.0.0.1", "--no-dashboard"], stdout=log, stderr=log))
    deadline = time.monotonic() + 60
    while True:
        try:
            with Client(address, timeout="5s") as c:
                c.wait_for_workers(workers, timeout=60)
            return address, procs
        except OSError:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.5)


def stop(procs):
    for p in reversed(procs):
        p.terminate()
    for p in procs:
        try:
            p.wait(timeout=15)
        except subprocess.TimeoutExpired:
            p.kill()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--samples", type=int, default=10000)
    ap.add_argument("--configs", default="1x1,2x1,1x2")
    a = ap.parse_args()
    me = psutil.Process()
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} at start "
          "(shared: other processes compete for the cores)")
    print(f"client RSS after imports: {me.memory_info().rss / 2**20:.0f} MiB")
    results = {}
    for cfg in a.configs.split(","):
        w, t = (int(x) for x in cfg.split("x"))
        address, procs = start_cluster(w, t)
        peak = [me.memory_info().rss]
        first = []

        def poll(done, total):
            rss = me.memory_info().rss
            peak[0] = max(peak[0], rss)
            if not first:
                first.append(rss)

        try:
            s = sweep.load(str(ROOT / "examples" / "sweeps" / "steel420_bolt_load.toml"),
                           samples=a.samples, method="random")
            with tempfile.TemporaryDirectory() as tmp:
                load0 = os.getloadavg()[0]
                t0 = time.monotonic()
                info = sweep.run(s, os.path.join(tmp, "out"), scheduler=address, plots=False,
                                 on_progress=poll, progress=sys.stderr.isatty())
                wall = time.monotonic() - t0
                # CPU the workers got (user + system, over the run and the statistics):
                # on a shared machine, their share of the cores explains a poor ratio.
                cpu = sum(sum(psutil.Process(p.pid).cpu_times()[:2]) for p in procs[1:])
        finally:
            stop(procs)
        rate = info["samples"] / info["elapsed_s"]
        results[cfg] = rate
        print(f"{cfg}: {info['samples']} samples ({info['failed']} failed) in "
              f"{info['elapsed_s']:.1f} s = {rate:.1f} samples/s (batch {info['batch']}; "
              f"with statistics {wall:.1f} s); worker CPU {cpu:.0f} s = "
              f"{cpu / info['elapsed_s']:.2f} cores on average, "
              f"{info['samples'] / cpu:.1f} samples per worker CPU second; client RSS "
              f"{first[0] / 2**20:.0f} MiB after the first batch, peak "
              f"{peak[0] / 2**20:.0f} MiB; load average {load0:.1f} -> "
              f"{os.getloadavg()[0]:.1f}")
    if "1x1" in results:
        for cfg, r in results.items():
            print(f"ratio {cfg} / 1x1: {r / results['1x1']:.2f}")
    print(f"client peak RSS over the whole run (ru_maxrss): "
          f"{__import__('resource').getrusage(__import__('resource').RUSAGE_SELF).ru_maxrss / 1024:.0f} MiB")


if __name__ == "__main__":
    main()

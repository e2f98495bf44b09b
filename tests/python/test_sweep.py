"""asperity.sweep (issue 12): a real Dask scheduler and two workers on loopback with one
worker killed mid-run, the default LocalCluster, reproducibility, failures kept, bad input
refused before any work. Every Dask process is started here with a bounded wait and
always stopped."""
import os
import pathlib
import signal
import socket
import subprocess
import sys
import time

import numpy as np
import pytest

pytest.importorskip("distributed")
pytest.importorskip("xarray")
pytest.importorskip("scipy")

import asperity  # noqa: E402
from asperity import sweep  # noqa: E402
from asperity.sweep import spec  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
CASE = str(ROOT / "examples" / "joints" / "steel420_two_bolts.toml")
VARY = {"load.bolts.nut_factor": "uniform(0.158, 0.267)",
        "joint.half[*].material.H": "normal(5.8 GPa, 5 %)"}
ENV = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=os.pathsep.join(
    p for p in [os.path.dirname(os.path.dirname(sweep.__file__)),
                os.environ.get("PYTHONPATH", "")] if p))


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _same(a, b):
    """Every variable and coordinate of two result Datasets equal (bitwise; NaN = NaN):
    the same C++ code on the same inputs."""
    assert set(a.variables) == set(b.variables)
    for k in a.variables:
        x, y = a[k].values, b[k].values
        if x.dtype.kind == "f":
            assert np.array_equal(x, y, equal_nan=True), k
        else:
            assert (x == y).all(), k


def _serial(tmp_path, name, samples, seed, **kw):
    s = spec.build(CASE, VARY, samples=samples, seed=seed)
    sweep.run(s, str(tmp_path / name), serial=True, plots=False, **kw)
    return sweep.open_results(str(tmp_path / name)).load()


@pytest.fixture
def dask_cluster():
    """A `dask scheduler` and two `dask worker` processes (no nanny: a killed worker
    stays dead) on 127.0.0.1; yields (address, [worker processes])."""
    from distributed import Client

    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    procs = []
    log = open(os.devnull, "w")
    try:
        procs.append(subprocess.Popen(
            [sys.executable, "-m", "dask", "scheduler", "--host", "127.0.0.1", "--port",
             str(port), "--no-dashboard"], stdout=log, stderr=log, env=ENV))
        workers = []
        for _ in range(2):
            w = subprocess.Popen(
                [sys.executable, "-m", "dask", "worker", address, "--nthreads", "1",
                 "--no-nanny", "--host", "127.0.0.1", "--no-dashboard"],
                stdout=log, stderr=log, env=ENV)
            procs.append(w)
            workers.append(w)
        deadline = time.monotonic() + 60
        while True:
            try:
                with Client(address, timeout="5s") as c:
                    c.wait_for_workers(2, timeout=max(deadline - time.monotonic(), 1))
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.5)
        yield address, workers
    finally:
        for p in reversed(procs):
            if p.poll() is None:
                p.terminate()
        for p in procs:
            try:
                p.wait(timeout=15)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait(timeout=15)
        log.close()


def test_scheduler_two_workers_one_killed_equals_serial(tmp_path, dask_cluster):
    address, workers = dask_cluster
    n, seed = 64, 7
    out = tmp_path / "dask"
    cmd = [sys.executable, "-m", "asperity.sweep", CASE, "--samples", str(n), "--seed",
           str(seed), "--scheduler", address, "--batch", "2", "--block", "8", "--no-plots",
           "--out", str(out)]
    for k, v in VARY.items():
        cmd += ["--vary", f"{k} ~ {v}"]
    run = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                           env=ENV)
    try:
        # Kill one worker once the first block of samples is on disk (mid-run).
        deadline = time.monotonic() + 90
        killed_mid_run = False
        while time.monotonic() < deadline and run.poll() is None:
            parts = list(tmp_path.glob(".dask.partial-*/samples/part-*.nc"))
            if parts:
                workers[0].send_signal(signal.SIGKILL)
                workers[0].wait(timeout=15)
                killed_mid_run = run.poll() is None
                break
            time.sleep(0.05)
        stdout, stderr = run.communicate(timeout=120)
    finally:
        if run.poll() is None:
            run.kill()
    assert run.returncode == 0, stderr
    assert killed_mid_run, "the sweep ended before a worker could be killed"
    assert workers[0].returncode == -signal.SIGKILL
    ds = sweep.open_results(str(out)).load()
    assert list(ds["sample"].values) == list(range(n))  # every sample, in order
    assert ds["ok"].values.all()
    # The surviving worker ran its samples on one library thread each (the samples are
    # the parallel dimension; engine.run_batch sets it).
    from distributed import Client

    with Client(address, timeout="10s") as client:
        counts = client.run(lambda: __import__("asperity").thread_count())
    assert set(counts.values()) == {1}, counts
    before = asperity.thread_count()
    _same(ds, _serial(tmp_path, "serial", n, seed))
    assert asperity.thread_count() == before  # a serial run leaves the caller's setting


def test_default_local_cluster_equals_serial(tmp_path):
    n, seed = 16, 3
    s = spec.build(CASE, VARY, samples=n, seed=seed, method="sobol")
    info = sweep.run(s, str(tmp_path / "local"), plots=True)
    assert info["engine"].startswith("dask") and info["failed"] == 0
    ds = sweep.open_results(str(tmp_path / "local")).load()
    s2 = spec.build(CASE, VARY, samples=n, seed=seed, method="sobol")
    sweep.run(s2, str(tmp_path / "serial"), serial=True, plots=False)
    _same(ds, sweep.open_results(str(tmp_path / "serial")).load())
    for f in ("summary.csv", "sensitivity.csv", "failures.csv", "sweep.json",
              "samples.parquet", "bands_vs_preload.png", "bands_vs_amplitude.png",
              "histograms.png", "sensitivity.png"):
        assert (tmp_path / "local" / f).stat().st_size > 0, f


def test_draws_do_not_depend_on_batching(tmp_path):
    a = _serial(tmp_path, "b1", 8, 5, batch=1, block=3)
    b = _serial(tmp_path, "b5", 8, 5, batch=5, block=1024)
    _same(a, b)
    c = _serial(tmp_path, "seed6", 8, 6)
    assert not np.array_equal(a["load.bolts.nut_factor"], c["load.bolts.nut_factor"])


def _design(method, n, vary=None, seed=11):
    s = spec.build(CASE, vary or VARY, samples=n, seed=seed, method=method)
    rows = [vals for _, vals in s.sample_inputs(0, n)]
    return s, np.array([[val.coord for _, val in r] for r in rows])


@pytest.mark.parametrize("method", ["sobol", "lhs"])
def test_stratified_designs_hold_one_point_per_stratum(method):
    # Invariants: a scrambled Sobol net of 2^m points and a Latin hypercube of n points
    # put exactly one point in each of n equal strata of each input's probability.
    n = 64
    s, x = _design(method, n)
    lo, hi = 0.158, 0.267
    strata = np.floor((x[:, 0] - lo) / (hi - lo) * n).astype(int)
    assert sorted(strata) == list(range(n))
    from scipy.stats import norm

    u = norm.cdf((x[:, 1] - 5.8e9) / 0.29e9)
    assert sorted(np.floor(u * n).astype(int)) == list(range(n))


def test_random_draws_have_the_asked_moments():
    # 4096 draws: the sample mean of a normal(5.8 GPa, 5 %) lies within 4 standard
    # errors (0.29 GPa / 64) of 5.8 GPa, its sd within 10 % of 0.29 GPa (the sd's
    # standard error is ~1.1 %); uniform draws stay inside [LOW, HIGH].
    s, x = _design("random", 4096)
    assert ((x[:, 0] >= 0.158) & (x[:, 0] <= 0.267)).all()
    assert abs(x[:, 1].mean() - 5.8e9) < 4 * 0.29e9 / 64
    assert abs(x[:, 1].std() / 0.29e9 - 1) < 0.1


def test_grid_times_draws_uses_the_same_draws_at_every_grid_point():
    s = spec.build(CASE, {"load.bolts.diameter": "2.8 mm .. 3 mm, 3 steps",
                          "load.bolts.nut_factor": "uniform(0.158, 0.267)"}, samples=4, seed=2)
    rows = list(s.sample_inputs(0, s.size))
    assert s.size == 12 and len(rows) == 12
    d = np.array([[v.coord for _, v in r] for _, r in rows])
    assert np.allclose(d[:, 0], np.repeat([2.8e-3, 2.9e-3, 3.0e-3], 4), rtol=1e-12)
    assert (d[0:4, 1] == d[4:8, 1]).all() and (d[0:4, 1] == d[8:12, 1]).all()


def test_failed_sample_is_recorded_with_inputs_and_error(tmp_path):
    # A preload beyond the model's range passes the case parser (a positive torque) and
    # fails in predict (docs/joints.md): that sample is recorded, the others complete.
    s = spec.build(CASE, {"load.bolts.total_torques[1]": ["1.2 lbf*in", "3e6 lbf*in",
                                                          "1.3 lbf*in"]})
    info = sweep.run(s, str(tmp_path / "f"), serial=True, plots=False)
    assert info["samples"] == 3 and info["failed"] == 1
    ds = sweep.open_results(str(tmp_path / "f")).load()
    assert list(ds["ok"].values) == [1, 0, 1]
    assert "beyond the model's range" in str(ds["error"].values[1])
    assert np.isnan(ds["mu"].values[1]).all() and np.isfinite(ds["mu"].values[[0, 2]]).all()
    lines = (tmp_path / "f" / "failures.csv").read_text().splitlines()
    assert len(lines) == 2 and lines[1].startswith("1,3e6 lbf*in,")
    assert "beyond the model's range" in lines[1]


def test_choice_tables_and_words(tmp_path):
    # A choice of [choices] tables sets several keys together; a choice of words.
    s = spec.build(CASE, {"surface": "choice(before, rougher)", "joint.model": "choice(bke, ke)"},
                   samples=6, seed=1, choices={"surface": {
                       "before": {},
                       "rougher": {"joint.half[*].roughness.sigma": "2.5 um"}}})
    sweep.run(s, str(tmp_path / "c"), serial=True, plots=False)
    ds = sweep.open_results(str(tmp_path / "c")).load()
    rough = ds["surface"].values == "rougher"
    assert set(ds["joint.model"].values) <= {"bke", "ke"}
    # Combined sigma (Eq. 5.1: root sum of squares) of two 2.5 um halves.
    assert np.allclose(ds["sigma"].values[rough], np.hypot(2.5e-6, 2.5e-6), rtol=1e-9)
    assert np.allclose(ds["sigma"].values[~rough], np.hypot(1.763e-6, 2.015e-6), rtol=1e-9)


def test_dynamics_cases_sweep(tmp_path):
    case = str(ROOT / "examples" / "dynamics" / "impulse_dankowicz.toml")
    s = spec.build(case, {"dynamics.epsilon": [0.02, 0.032]})
    assert s.kind == "dynamics"
    sweep.run(s, str(tmp_path / "d"), serial=True, plots=False)
    ds = sweep.open_results(str(tmp_path / "d")).load()
    assert ds["ok"].values.all() and ds["modal_frequency"].shape == (2,)
    # epsilon 0.032 is the shipped case: the same modal frequency as running it directly.
    from asperity import dynamics

    assert ds["modal_frequency"].values[1] == dynamics.run_case(case)["summary"]["modal_frequency"]


@pytest.mark.parametrize("vary, words", [
    ({"load.bolts.nut_facter": "uniform(0.158, 0.267)"}, ["load.bolts.nut_facter", "unknown key"]),
    ({"joint.half[3].material.H": "normal(5.8 GPa, 5 %)"}, ["joint.half[3]", "2 elements"]),
    ({"load.bolts.nut_factor": "uniform(0.267, 0.158)"}, ["load.bolts.nut_factor", "LOW < HIGH"]),
    ({"load.bolts.nut_factor": "uniform(-0.1, 0.2)"}, ["load.bolts.nut_factor", "must lie in (0, 1]"]),
    ({"joint.half[1].material.nu": "uniform(0.3, 0.6)"}, ["material.nu", "[0, 0.5)"]),
    ({"joint.half[*].material.H": "normal(5.8 GPa, -5 %)"}, ["material.H", "SD > 0"]),
    ({"joint.half[*].material.H": "normal(5.8 GPa, 40 %)"}, ["material.H", "MEAN +-"]),
    ({"joint.half[*].material.H": "normal(5.8 um, 5 %)"}, ["material.H", "length", "pressure"]),
    ({"load.bolts.nut_factor": "uniform(0.1 N, 0.2 N)"}, ["nut_factor", "dimensionless"]),
    ({"joint.area": "uniform(100, 200)"}, ["joint.area", "give the unit"]),
    ({"joint.model": "choice(bke, xyz)"}, ["joint.model", "xyz"]),
    ({"joint.model": "uniform(1, 2)"}, ["joint.model", "use a grid or choice"]),
    ({"load.bolts.count": "normal(2, 10 %)"}, ["load.bolts.count", "integer"]),
])
def test_bad_input_refused_before_any_work(tmp_path, vary, words):
    out = tmp_path / "out"
    cmd = [sys.executable, "-m", "asperity.sweep", CASE, "--samples", "10", "--out", str(out),
           # Nothing listens there: a refusal must come before any connection.
           "--scheduler", f"tcp://127.0.0.1:{_free_port()}"]
    for k, v in vary.items():
        cmd += ["--vary", f"{k} ~ {v}"]
    p = subprocess.run(cmd, capture_output=True, text=True, env=ENV, timeout=60)
    assert p.returncode == 2, p.stderr
    msg = p.stderr.strip()
    assert msg.startswith("asperity sweep: error: ") and len(msg.splitlines()) == 1
    for w in words:
        assert w in msg, msg
    assert not out.exists() and not list(tmp_path.glob(".out.partial-*"))


def test_foreign_output_directory_is_refused(tmp_path):
    out = tmp_path / "mine"
    out.mkdir()
    (out / "notes.txt").write_text("keep")
    s = spec.build(CASE, VARY, samples=2, seed=1)
    with pytest.raises(sweep.SweepError, match=r"did not write .*: notes.txt\)"):
        sweep.run(s, str(out), serial=True)
    assert (out / "notes.txt").read_text() == "keep"


def test_vibration_cases_run_and_equal_the_direct_run(tmp_path):
    """A vibration case (asperity vibration) varied in its Jenkins slip force: each sample's
    outputs are the direct run's curves put on the fixed amplitude grid (linear
    interpolation in log10 a, exact at the grid's ends), and the peak damping ratio is
    the largest of the mode's points."""
    from asperity import vibration

    src = ROOT / "examples" / "vibration" / "jenkins_sdof.toml"
    s = spec.build(str(src), {"element[1].F_s": [0.15, 0.25]})
    sweep.run(s, str(tmp_path / "v"), serial=True)
    ds = sweep.open_results(str(tmp_path / "v")).load()
    assert ds.sizes["sample"] == 2 and int(ds["ok"].sum()) == 2
    text = src.read_text()
    for i, Fs in enumerate([0.15, 0.25]):
        r = vibration.run_case_text(text.replace("F_s = 0.2", f"F_s = {Fs}"), str(src.parent))
        nm = r["nonlinear_mode"]
        la = np.asarray(nm["log10_amplitude"])
        grid = ds["mode_log10_amplitude"].values[i]
        assert grid[0] == pytest.approx(la[0]) and grid[-1] == pytest.approx(la[-1])
        want = np.interp(grid, la, np.asarray(nm["damping_ratio"]))
        np.testing.assert_allclose(ds["mode_damping_ratio"].values[i], want, rtol=1e-12)
        assert float(ds["mode_peak_damping_ratio"].values[i]) == pytest.approx(
            float(np.max(nm["damping_ratio"])), rel=1e-12)
        peaks = [float(np.max(np.asarray(c["output_amplitude"])[:, 0]))
                 for c in r["frequency_response"]]
        np.testing.assert_allclose(ds["response_peak_amplitude"].values[i], peaks, rtol=1e-12)
    # A larger slip force slips later: the damping peak moves to larger amplitude.
    assert ds["mode_peak_damping_amplitude"].values[1] > ds["mode_peak_damping_amplitude"].values[0]
    # Value coordinates: the forcing amplitudes of the case's curves (force_cos 3.3 N; 0.1 N
    # times the force scales 0.5, 1, 2) and its modal amplitude range (10^-2 .. 10^5).
    np.testing.assert_allclose(ds["curve"].values, [3.3, 0.05, 0.1, 0.2], rtol=1e-12)
    assert ds["curve"].attrs["units"] == "N" and ds["mode_frequency_hz"].attrs["units"] == "Hz"
    np.testing.assert_allclose(ds["modal_amplitude"].values[[0, -1]], [1e-2, 1e5], rtol=1e-12)
    # Constant outputs are named as such, not described: the stuck linear frequency does
    # not depend on F_s, nor does the peak damping ratio (the Jenkins element is
    # positively homogeneous in (x, F_s): amplitudes scale with F_s, ratios do not).
    import json

    info = json.loads((tmp_path / "v" / "sweep.json").read_text())
    assert {"linear_frequency_hz", "mode_peak_damping_ratio"} <= set(info["constant_outputs"])
    assert "mode_peak_damping_amplitude" not in info["constant_outputs"]
    import csv

    rows = {r["output"]: r for r in csv.DictReader(open(tmp_path / "v" / "summary.csv"))}
    lin = rows["linear_frequency_hz"]
    assert lin["varies"] == "no" and lin["sd"] == "" and lin["min"] == lin["max"]
    assert rows["mode_peak_damping_amplitude"]["varies"] == "yes"
    # Frequency and damping bands against amplitude.
    assert (tmp_path / "v" / "bands_vs_modal_amplitude.png").stat().st_size > 0


def test_vary_flag_takes_a_grid_array_and_progress_draws_a_bar():
    import io

    assert spec.parse_vary_flag('load.bolts.diameter = ["2.8 mm", "3 mm"]') == (
        "load.bolts.diameter", ["2.8 mm", "3 mm"])
    assert spec.parse_vary_flag("joint.area ~ normal(170 mm^2, 2 %)") == (
        "joint.area", "normal(170 mm^2, 2 %)")
    from asperity.sweep.engine import Progress

    buf = io.StringIO()
    bar = Progress(10, enabled=True, stream=buf)
    bar.update(10, 1)
    bar.close()
    assert "10/10 samples, 1 failed" in buf.getvalue() and "#" * 30 in buf.getvalue()
    quiet = io.StringIO()
    Progress(10, stream=quiet).update(10, 0)  # not a terminal: nothing
    assert quiet.getvalue() == ""


# Issue 21's sweep faults: each refused before any work with one line (exit 2), or, for
# --format both, accepted as --help offers it.
def _sweep_cli(tmp_path, *args, timeout=60):
    cmd = [sys.executable, "-m", "asperity.sweep", *args]
    return subprocess.run(cmd, capture_output=True, text=True, env=ENV, timeout=timeout,
                          cwd=tmp_path)


@pytest.mark.parametrize("args, words", [
    (["--scheduler", "xyz"], ["--scheduler 'xyz'", "tcp://HOST:PORT"]),
    (["--threads-per-worker", "0"], ["--threads-per-worker 0", "positive integer"]),
    (["--samples", "1000000000000"], ["1,000,000,000,000 samples", "limit of 10,000,000"]),
    (["--vary", "joint.area = 100 mm^2 .. 200 mm^2, 1000000000 steps"],
     ["1000000000 steps", "limit of 10,000,000"]),
])
def test_sweep_flags_refused_before_any_work(tmp_path, args, words):
    p = _sweep_cli(tmp_path, CASE, "--vary", "load.bolts.nut_factor ~ uniform(0.158, 0.267)",
                   "--out", "out", *args, timeout=30)
    msg = p.stderr.strip()
    assert p.returncode == 2, msg
    assert msg.startswith("asperity sweep: error: ") and len(msg.splitlines()) == 1, msg
    for w in words:
        assert w in msg, msg
    assert not (tmp_path / "out").exists()


def test_sweep_case_file_not_utf8_is_named(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_bytes(b"[joint]\nname = \"\xff\xfe\"\n")
    p = _sweep_cli(tmp_path, str(bad), "--vary", "joint.area ~ uniform(1 mm^2, 2 mm^2)",
                   "--out", "out")
    msg = p.stderr.strip()
    assert p.returncode == 2 and len(msg.splitlines()) == 1, msg
    assert f"{bad}:2: byte 0xff" in msg and "not UTF-8" in msg, msg


def test_sweep_usage_error_is_one_line(tmp_path):
    p = _sweep_cli(tmp_path, CASE, "--out", "out", "--bogus")
    msg = p.stderr.strip()
    assert p.returncode == 2 and len(msg.splitlines()) == 1, msg
    assert "unrecognized arguments: --bogus" in msg and "--help" in msg, msg


def test_sweep_format_both_writes_netcdf_and_parquet(tmp_path):
    pytest.importorskip("pyarrow")
    p = _sweep_cli(tmp_path, CASE, "--vary", "load.bolts.nut_factor ~ uniform(0.158, 0.267)",
                   "--samples", "2", "--serial", "--no-plots", "--format", "both", "--out", "out")
    assert p.returncode == 0, p.stderr
    names = {f.name for f in (tmp_path / "out").iterdir()}
    assert "samples.parquet" in names and "samples" in names, names


def test_sweep_sigint_prints_no_traceback(tmp_path):
    # A serial run interrupted (SIGINT, as Ctrl-C) says so in one line, exit 130.
    cmd = [sys.executable, "-m", "asperity.sweep", CASE, "--vary",
           "load.bolts.nut_factor ~ uniform(0.158, 0.267)", "--samples", "5000", "--serial",
           "--no-plots", "--out", "out"]
    # SIGINT at its default disposition in the child, as in a terminal: a runner that starts
    # the tests in the background (`cmd &` in a non-interactive shell) leaves it ignored, and
    # Python then keeps it ignored.
    run = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                           env=ENV, cwd=tmp_path,
                           preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    time.sleep(4.0)  # past the imports, into the samples
    run.send_signal(signal.SIGINT)
    _, err = run.communicate(timeout=60)
    assert run.returncode == 130, err
    assert "Traceback" not in err and "interrupted (SIGINT)" in err, err
    assert not (tmp_path / "out").exists() and not list(tmp_path.glob(".out.partial-*"))


# Issue 21, item 8: the sweep's output and input rules (as the C++ commands').
def _one_cheap_sample():
    """One sample of the case cut to one load case and one amplitude (fast)."""
    return spec.build(CASE, {"load.bolts.nut_factor": [0.2]},
                      set_={"load.bolts.total_torques": ["2.7 lbf*in"],
                            "excitation.amplitudes": ["1 um"]})


def _cli_in_process(capsys, *args):
    from asperity.sweep.__main__ import main

    code = main(list(args))
    return code, capsys.readouterr().err.strip()


def test_full_disk_names_the_file_in_one_line(tmp_path, capsys, monkeypatch):
    # A part file that lands on /dev/full: every write to it fails with ENOSPC, as on a
    # full disk. Linux has /dev/full (the platform the project builds on): asserted, not skipped.
    assert os.path.exists("/dev/full")
    from asperity.sweep import engine

    prepare = engine.prepare_out_dir

    def onto_full_disk(out):
        tmp = prepare(out)
        os.symlink("/dev/full", os.path.join(tmp, "samples", "part-00000.nc"))
        return tmp

    monkeypatch.setattr(engine, "prepare_out_dir", onto_full_disk)
    code, err = _cli_in_process(capsys, CASE, "--vary", "load.bolts.nut_factor ~ uniform(0.158, "
                                "0.267)", "--samples", "2", "--serial", "--no-plots", "--out",
                                str(tmp_path / "out"))
    assert code == 1, err
    assert len(err.splitlines()) == 1, err
    assert err.startswith("asperity sweep: error: cannot write "), err
    assert "part-00000.nc" in err and "No space left on device" in err, err
    assert not (tmp_path / "out").exists() and not list(tmp_path.glob(".out.partial-*"))


def test_every_worker_gone_is_named_not_waited_on(tmp_path, dask_cluster):
    address, workers = dask_cluster
    from asperity.sweep.engine import ClusterError

    def kill_every_worker(done, total):  # after the first batch: mid-run
        for w in workers:
            if w.poll() is None:
                w.send_signal(signal.SIGKILL)
                w.wait(timeout=15)

    s = spec.build(CASE, {"load.bolts.nut_factor": "uniform(0.158, 0.267)"}, samples=64)
    t0 = time.monotonic()
    with pytest.raises(ClusterError) as e:
        sweep.run(s, str(tmp_path / "gone"), scheduler=address, batch=2, block=8, plots=False,
                  worker_timeout=1.0, on_progress=kill_every_worker)
    # Not forever: the 1 s timeout after the 1 s heartbeat (60 s is a generous bound on
    # a loaded machine).
    assert time.monotonic() - t0 < 60
    msg = str(e.value)
    assert "no Dask worker connected" in msg and address in msg and "for 1 s" in msg, msg
    assert not (tmp_path / "gone").exists() and not list(tmp_path.glob(".gone.partial-*"))


def test_sigterm_removes_the_partial_output(tmp_path, capsys, monkeypatch):
    # SIGTERM to this process once the first block is on disk (mid-run), through the
    # command's handler.
    from asperity.sweep import engine

    flush = engine.BlockWriter.flush

    def flush_then_sigterm(self):
        flush(self)
        if self.parts:
            os.kill(os.getpid(), signal.SIGTERM)

    monkeypatch.setattr(engine.BlockWriter, "flush", flush_then_sigterm)
    code, err = _cli_in_process(capsys, CASE, "--vary", "load.bolts.nut_factor ~ uniform(0.158, "
                                "0.267)", "--samples", "40", "--serial", "--no-plots", "--block",
                                "4", "--batch", "4", "--out", str(tmp_path / "out"))
    assert code == 143, err
    assert "Traceback" not in err and "terminated (SIGTERM)" in err, err
    assert not (tmp_path / "out").exists() and not list(tmp_path.glob(".out.partial-*"))


def test_stale_partial_of_a_dead_run_is_removed(tmp_path):
    from asperity.sweep.engine import MARKER

    dead = subprocess.Popen(["true"])
    dead.wait(timeout=30)  # its PID is now free (reuse within this test is unlikely)
    stale = tmp_path / f".out.partial-{dead.pid}"
    (stale / "samples").mkdir(parents=True)
    (stale / MARKER).write_text("written by asperity sweep\n")
    alive = tmp_path / f".out.partial-{os.getpid()}x"  # not a partial name: kept
    alive.mkdir()
    s = _one_cheap_sample()
    sweep.run(s, str(tmp_path / "out"), serial=True, plots=False)
    assert not stale.exists() and alive.exists()
    assert (tmp_path / "out" / "sweep.json").exists()


def test_foreign_files_in_out_are_named(tmp_path):
    s = _one_cheap_sample()
    out = tmp_path / "out"
    sweep.run(s, str(out), serial=True, plots=False)
    sweep.run(s, str(out), serial=True, plots=False)  # its own output: replaced
    (out / "samples" / "notes.txt").write_text("keep")
    with pytest.raises(sweep.SweepError, match=r"marker does not list them\): samples/notes.txt"):
        sweep.run(s, str(out), serial=True, plots=False)
    assert (out / "samples" / "notes.txt").read_text() == "keep"


def test_case_file_over_4_mib_is_refused(tmp_path):
    # The C++ commands' cap on a case file (core::kMaxCaseFileBytes, 4 MiB).
    big = tmp_path / "big.toml"
    big.write_text(pathlib.Path(CASE).read_text() + "#" * (4 << 20) + "\n")
    p = _sweep_cli(tmp_path, str(big), "--vary", "load.bolts.nut_factor ~ uniform(0.158, 0.267)",
                   "--out", "out")
    msg = p.stderr.strip()
    assert p.returncode == 2 and len(msg.splitlines()) == 1, msg
    assert str(big) in msg and "limit of 4 MiB" in msg, msg


# Issue 21, item 5: results by xarray/CF conventions.
def test_results_carry_cf_attributes_and_value_coordinates(tmp_path):
    s = spec.build(CASE, {"load.bolts.nut_factor": [0.25],
                          "joint.half[*].material.H": ["5.8 GPa"]})
    sweep.run(s, str(tmp_path / "cf"), serial=True, plots=False)
    ds = sweep.open_results(str(tmp_path / "cf")).load()
    for k, v in ds.variables.items():
        assert v.attrs.get("long_name"), k
        if k != "error":  # text: no units (CF 3.1)
            assert v.attrs.get("units"), k
    assert ds["stiffness"].attrs["units"] == "N m-1" and ds["energy"].attrs["units"] == "J"
    assert ds["joint.half[*].material.H"].attrs["units"] == "Pa"
    assert ds["load.bolts.nut_factor"].attrs["units"] == "1"
    a = ds.attrs
    assert a["Conventions"].startswith("CF-") and a["asperity_version"] == asperity.__version__
    assert a["case_file"] == CASE and a["method"] == "random" and a["seed"] == 0
    import datetime

    datetime.datetime.strptime(a["date_created"], "%Y-%m-%dT%H:%M:%SZ")
    # Value coordinates: the preloads of Table 5.5 (234/331/526/721 N, printed to 3 digits:
    # 0.5 N of 234 N is 0.22 %, so 0.3 %), and the case file's joint amplitudes (the
    # same text in SI: 1e-12).
    np.testing.assert_allclose(ds["load"].values, [234, 331, 526, 721], rtol=3e-3)
    assert ds["load"].attrs["units"] == "N"
    np.testing.assert_allclose(ds["amplitude"].values,
                               np.array([0.05, 0.1, 0.25, 0.5, 1, 2, 4]) * 1e-6, rtol=1e-12)
    assert ds["amplitude"].attrs["units"] == "m"


def test_output_of_an_earlier_sweep_without_a_file_list_is_replaced(tmp_path):
    # The marker of sweeps before issue 21 lists no files; their output stays replaceable,
    # while a hand-made (empty) marker does not make a directory asperity's.
    from asperity.sweep.engine import MARKER

    old = tmp_path / "old"
    (old / "samples").mkdir(parents=True)
    (old / "samples" / "part-00000.nc").write_text("x")
    (old / MARKER).write_text("written by asperity sweep; replaced as a whole by the next run\n")
    s = _one_cheap_sample()
    sweep.run(s, str(old), serial=True, plots=False)
    assert "files:" in (old / MARKER).read_text()
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / MARKER).write_text("")
    (mine / "notes.txt").write_text("keep")
    with pytest.raises(sweep.SweepError, match="notes.txt"):
        sweep.run(s, str(mine), serial=True, plots=False)


def test_case_writer_round_trips_every_string():
    # The sweep writes each sample's case as TOML (spec.to_toml): strings and keys with
    # quotes, backslashes, newlines and other control characters must read back as they were
    # (tomllib, TOML v1.0.0); before, a newline or a backslash in a key gave invalid TOML.
    import tomllib

    from asperity.sweep import spec

    odd = 'a"b\\c\nd\te\x01f\x7fg\rh\x08i\x0cj é'
    case = {"joint": {"name": odd, odd: 1.5, "list": [odd, "x"]},
            "element": [{"name": odd, "k": 2}], "key\\with": {"v": odd}}
    assert tomllib.loads(spec.to_toml(case)) == case

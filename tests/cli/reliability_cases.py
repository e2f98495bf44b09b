#!/usr/bin/env python3
"""Issue 13's reliability cases as regression tests: outputs replace only regular files,
temporaries are removed after SIGINT/SIGTERM and by the next run, a command's outputs
are committed together or not at all (a full disk names the user's path and the
system's reason), files the user put into an output directory are never deleted, and
readers refuse streams, directories and oversized or non-UTF-8 case files.

Usage: reliability_cases.py ASPERITY_EXE SOURCE_DIR CASE. Standard library only.
Exit 0 = pass, 1 = fail.
"""
import math
import os
import resource
import signal
import subprocess
import sys
import time

from case_runner import check, main  # tests/cli/case_runner.py

SPHERE = ["sphere", "--E1=207GPa", "--nu1=0.3", "--E2=207GPa", "--nu2=0.3", "--H=6.83GPa",
          "--R1=2.5mm", "--P=35N", "--mu-cfc=0.284", "--delta-max=1.5um"]
FLAT = ["flat", "--beta=0.04", "--psi=0.5", "--nu=0.3", "--P-star=1e-3", "--model=bke"]



def run(exe, argv, cwd, limit_bytes=None, timeout=120):
    def limit():
        # A file-size limit makes write() fail with EFBIG: a full disk without root.
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit_bytes, limit_bytes))
    return subprocess.run([exe] + argv, capture_output=True, text=True, cwd=cwd,
                          timeout=timeout, preexec_fn=limit if limit_bytes else None)


def leftovers(directory):
    """Hidden temporaries of asperity's naming in `directory`."""
    return [f for f in os.listdir(directory) if ".tmp-" in f or ".old-" in f]


def write_history(path, rows):
    with open(path, "w") as f:
        f.write("delta_star\n")
        for i in range(rows):
            f.write("%.6f\n" % (0.5 * math.sin(i * 0.001)))


def dead_pid():
    p = subprocess.Popen(["true"])
    p.wait()
    return p.pid


def expect_exit2(r, *fragments):
    check(r.returncode == 2, f"expected exit 2, got {r.returncode}: {r.stderr}")
    for frag in fragments:
        check(frag in r.stderr, f"message lacks {frag!r}: {r.stderr}")
    check(".tmp-" not in r.stderr, f"message names a temporary: {r.stderr}")


# ------------------------------------------------------------------ outputs


def case_out_dev_stdout(exe, src, tmp):
    was_link = os.path.islink("/dev/stdout")
    r = run(exe, SPHERE + ["--loop", "/dev/stdout"], tmp)
    check(r.returncode == 0, f"exit {r.returncode}: {r.stderr}")
    check(r.stdout.startswith("model,branch,delta[m],Q[N]\n"), f"stdout: {r.stdout[:200]!r}")
    check(os.path.islink("/dev/stdout") == was_link, "/dev/stdout was replaced")
    # Through a pipe the same (the written-through device is the pipe).
    r = run(exe, SPHERE + ["--loop", "/dev/fd/1"], tmp)
    check(r.returncode == 0 and r.stdout.startswith("model,branch"), r.stderr)


def case_out_dev_full(exe, src, tmp):
    r = run(exe, SPHERE + ["--loop", "/dev/full"], tmp)
    expect_exit2(r, 'cannot write "/dev/full": No space left on device')
    # The regular file of the same command is not committed when the device fails.
    r = run(exe, SPHERE + ["--loop", "a.csv", "--energy-curve", "/dev/full"], tmp)
    expect_exit2(r, "/dev/full", "No space left on device")
    check(not os.path.exists(os.path.join(tmp, "a.csv")), "a.csv written although the set failed")
    check(not leftovers(tmp), f"leftovers {leftovers(tmp)}")


def case_out_directory_refused(exe, src, tmp):
    os.mkdir(os.path.join(tmp, "d.csv"))
    r = run(exe, SPHERE + ["--loop", "d.csv"], tmp)
    expect_exit2(r, '"d.csv" is a directory')


def case_out_symlink_keeps_link(exe, src, tmp):
    real = os.path.join(tmp, "real.csv")
    with open(real, "w") as f:
        f.write("old\n")
    os.symlink("real.csv", os.path.join(tmp, "link.csv"))
    r = run(exe, SPHERE + ["--loop", "link.csv"], tmp)
    check(r.returncode == 0, r.stderr)
    check(os.path.islink(os.path.join(tmp, "link.csv")), "the link was replaced")
    with open(real) as f:
        check(f.readline() == "model,branch,delta[m],Q[N]\n", "the linked file was not written")


def case_half_written_set(exe, src, tmp):
    # flat writes --loop (small) then --out (large): the limit fails the second.
    write_history(os.path.join(tmp, "h.csv"), 20000)
    with open(os.path.join(tmp, "l.csv"), "w") as f:
        f.write("earlier\n")
    r = run(exe, FLAT + ["--delta-star-max=0.5", "--points=50", "--loop=l.csv", "--history=h.csv",
                         "--out=f.csv"], tmp, limit_bytes=64 * 1024)
    expect_exit2(r, 'cannot write "f.csv": File too large')
    check(not os.path.exists(os.path.join(tmp, "f.csv")), "f.csv written")
    with open(os.path.join(tmp, "l.csv")) as f:
        check(f.read() == "earlier\n", "l.csv was replaced although the set failed")
    check(not leftovers(tmp), f"leftovers {leftovers(tmp)}")
    # Without the limit both are written.
    r = run(exe, FLAT + ["--delta-star-max=0.5", "--points=50", "--loop=l.csv", "--history=h.csv",
                         "--out=f.csv"], tmp)
    check(r.returncode == 0, r.stderr)
    check(os.path.getsize(os.path.join(tmp, "f.csv")) > 64 * 1024, "f.csv incomplete")


def case_disk_full_tmpfs(exe, src, tmp):
    """ENOSPC on a real full file system: a 64 KiB tmpfs when this user may mount one,
    else the same through a file-size limit (EFBIG), so the check always runs."""
    mnt = os.path.join(tmp, "small")
    os.mkdir(mnt)
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", mnt],
                             capture_output=True).returncode == 0
    try:
        argv = SPHERE + ["--loop", "a.csv", "--energy-curve", "e.csv", "--points", "2000"]
        r = run(exe, argv, mnt, limit_bytes=None if mounted else 64 * 1024)
        expect_exit2(r, 'cannot write "a.csv": ',
                     "No space left on device" if mounted else "File too large")
        check(os.listdir(mnt) == [], f"left behind: {os.listdir(mnt)}")
    finally:
        if mounted:
            subprocess.run(["umount", mnt])


def case_dynamics_disk_full_names_user_path(exe, src, tmp):
    case = os.path.join(src, "examples/dynamics/harmonic_coulomb.toml")
    r = run(exe, ["dynamics", case, "--out", "dyn", "--no-plots"], tmp, limit_bytes=16 * 1024)
    expect_exit2(r, 'cannot write "dyn/timeseries.csv": File too large')
    check(not os.path.exists(os.path.join(tmp, "dyn")), "dyn exists")
    check(not leftovers(tmp), f"leftovers {leftovers(tmp)}")


def signal_cleanup(exe, tmp, sig):
    write_history(os.path.join(tmp, "h.csv"), 3_000_000)
    p = subprocess.Popen([exe] + FLAT + ["--delta-star-max=0.5", "--loop=l.csv", "--history=h.csv",
                                         "--out=f.csv"], cwd=tmp,
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 60
    seen = []
    while not seen and p.poll() is None and time.monotonic() < deadline:
        seen = leftovers(tmp)
        time.sleep(0.002)
    check(seen, "no temporary was seen before the run ended (the test did not interrupt it)")
    p.send_signal(sig)
    rc = p.wait(timeout=60)
    check(rc == -sig, f"exit {rc}, expected death by signal {sig}")
    check(not leftovers(tmp), f"temporaries left after signal {sig}: {leftovers(tmp)}")
    check(not os.path.exists(os.path.join(tmp, "f.csv")), "f.csv written")
    check(not os.path.exists(os.path.join(tmp, "l.csv")), "l.csv written")


def case_sigterm_cleanup(exe, src, tmp):
    signal_cleanup(exe, tmp, signal.SIGTERM)


def case_sigint_cleanup(exe, src, tmp):
    signal_cleanup(exe, tmp, signal.SIGINT)


def case_dynamics_sigterm_cleanup(exe, src, tmp):
    """SIGTERM while `dynamics --out` streams its time series into the staged directory
    (the 604 MB .timeseries.csv.tmp-* of the issue): nothing of ours stays behind."""
    with open(os.path.join(src, "examples/dynamics/harmonic_coulomb.toml")) as f:
        text = f.read().replace("duration = 60", "duration = 50000")
    with open(os.path.join(tmp, "long.toml"), "w") as f:
        f.write(text)
    p = subprocess.Popen([exe, "dynamics", "long.toml", "--out", "dyn", "--no-plots"], cwd=tmp,
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 60
    seen = []
    while not seen and p.poll() is None and time.monotonic() < deadline:
        seen = leftovers(tmp)
        time.sleep(0.005)
    check(seen, "no staged output was seen before the run ended (the test did not interrupt it)")
    time.sleep(0.3)  # let it stream into the staged directory
    p.send_signal(signal.SIGTERM)
    rc = p.wait(timeout=60)
    check(rc == -signal.SIGTERM, f"exit {rc}, expected death by SIGTERM")
    check(not leftovers(tmp), f"temporaries left after SIGTERM: {leftovers(tmp)}")
    check(not os.path.exists(os.path.join(tmp, "dyn")), "dyn written")


def predict_sweep(src, tmp, n):
    """examples/joints/steel_smooth.toml with n preloads (200, 202, ... N) and its 12
    amplitudes: about 5 ms of computation and 100 KB of loops.csv per preload."""
    with open(os.path.join(src, "examples/joints/steel_smooth.toml")) as f:
        text = f.read()
    bolts = text[text.index("bolts = {"):]
    bolts = bolts[:bolts.index("\n")]
    preloads = ", ".join(f'"{200 + 2 * i} N"' for i in range(n))
    with open(os.path.join(tmp, "sweep.toml"), "w") as f:
        f.write(text.replace(bolts, f"preloads = [{preloads}]"))
    return "sweep.toml"


def tree(directory):
    """{relative path: bytes} of every file below `directory`."""
    files = {}
    for root, _, names in os.walk(directory):
        for name in names:
            path = os.path.join(root, name)
            with open(path, "rb") as f:
                files[os.path.relpath(path, directory)] = f.read()
    return files


def earlier_predict_output(exe, src, tmp, plots):
    """A complete `predict --out out` of the shipped 3-preload case: what a kill of a
    later run must leave alone (or replace whole)."""
    case = os.path.join(src, "examples/joints/steel_smooth.toml")
    r = run(exe, ["predict", case, "--out", "out"] + ([] if plots else ["--no-plots"]), tmp)
    check(r.returncode == 0, r.stderr)
    old = tree(os.path.join(tmp, "out"))
    check("summary.json" in old and ".asperity-output" in old, f"earlier output: {sorted(old)}")
    return old


def replaced_whole(out_dir, n):
    """True when `out_dir` is a complete output of the n-preload sweep: its marker lists
    exactly the files present and summary.json holds every preload."""
    files = tree(out_dir)
    marker = files.get(".asperity-output", b"").decode().splitlines()
    if "files:" not in marker:
        return False
    listed = marker[marker.index("files:") + 1:]
    if sorted(listed) != sorted(f for f in files if f != ".asperity-output"):
        return False
    try:
        return len(json.loads(files["summary.json"])["loads"]) == n
    except (KeyError, ValueError):
        return False


def case_predict_sigterm_computing(exe, src, tmp):
    """SIGTERM while `predict --out out` computes its load cases: exit by the signal,
    nothing of ours left, the earlier complete output in `out` untouched."""
    old = earlier_predict_output(exe, src, tmp, plots=False)
    n = 400
    case = predict_sweep(src, tmp, n)
    env = dict(os.environ, ASPERITY_PROGRESS_INTERVAL="0")  # a line after every preload
    p = subprocess.Popen([exe, "predict", case, "--out", "out", "--no-plots"], cwd=tmp, env=env,
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    # Wait until a tenth of the preloads are done: the computation runs.
    def count(line):  # "asperity predict: i/n preloads (p %)" -> i
        return int(line.split()[2].split("/")[0]) if line.startswith("asperity predict:") else 0
    done = 0
    while done < n // 10:
        line = p.stderr.readline()
        check(line, "the run ended before its progress reached a tenth")
        done = max(done, count(line))
    p.send_signal(signal.SIGTERM)
    rest = p.stderr.read()
    rc = p.wait(timeout=60)
    p.stderr.close()
    # Evidence that the signal came mid-computation: the last progress line is below n.
    last = max([done] + [count(line) for line in rest.splitlines()])
    check(last < n, f"the computation finished ({last}/{n}) before the signal")
    check(rc == -signal.SIGTERM, f"exit {rc}, expected death by SIGTERM")
    check(not leftovers(tmp), f"temporaries left after SIGTERM: {leftovers(tmp)}")
    check(tree(os.path.join(tmp, "out")) == old, "the earlier output was changed")


def predict_sigterm_writing(exe, src, tmp, plots):
    """SIGTERM while `predict --out out` writes its staged directory `.out.tmp-*` (with
    plots: while gnuplot draws, its own temporary under TMPDIR): exit by the signal, no
    staged directory, temporary or plot directory left, and `out` either the earlier
    complete output or (a signal after the commit) the new one whole; never a mixture."""
    old = earlier_predict_output(exe, src, tmp, plots)
    n = 100
    case = predict_sweep(src, tmp, n)
    plot_tmp = os.path.join(tmp, "plot-tmp")
    os.mkdir(plot_tmp)
    env = dict(os.environ, TMPDIR=plot_tmp)
    argv = [exe, "predict", case, "--out", "out"] + ([] if plots else ["--no-plots"])
    for _ in range(3):
        p = subprocess.Popen(argv, cwd=tmp, env=env, start_new_session=True,
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        # The staged directory exists only once the computation is over. Without plots,
        # kill while it holds a file being written (`.loops.csv.tmp-*`, 10 MB); with
        # plots, while gnuplot draws (its directory under TMPDIR exists).
        staged, killed = [], False
        deadline = time.monotonic() + 60
        while not killed and p.poll() is None and time.monotonic() < deadline:
            staged = []
            for d in [f for f in os.listdir(tmp) if f.startswith(".out.tmp-")]:
                try:
                    staged = os.listdir(os.path.join(tmp, d))
                except FileNotFoundError:
                    staged = []
            drawing = staged and os.listdir(plot_tmp)
            if drawing if plots else any(".tmp-" in f for f in staged):
                p.send_signal(signal.SIGTERM)
                killed = True
            else:
                time.sleep(0.001)
        rc = p.wait(timeout=60)
        # gnuplot, started by the killed process in its new session, must be gone with it
        # (the cleanup handler kills and reaps it); a survivor is killed here and fails.
        try:
            os.killpg(p.pid, signal.SIGKILL)
            survivor = True
        except ProcessLookupError:
            survivor = False
        stderr = p.stderr.read().decode()
        p.stderr.close()
        now = tree(os.path.join(tmp, "out"))
        if not killed:  # the run ended between two looks: nothing was tested
            check(rc == 0 and replaced_whole(os.path.join(tmp, "out"), n),
                  f"exit {rc} without a signal: {stderr}")
            old = now
            continue
        check(rc == -signal.SIGTERM, f"exit {rc}, expected death by SIGTERM: {stderr}")
        check(not survivor, "a process of the killed predict (gnuplot) outlived it")
        check(not leftovers(tmp), f"temporaries left after SIGTERM: {leftovers(tmp)}")
        check(not os.listdir(plot_tmp), f"gnuplot's temporaries left: {os.listdir(plot_tmp)}")
        if now == old:
            return  # the signal came before the commit: the earlier output intact
        check(replaced_whole(os.path.join(tmp, "out"), n),
              f"out is neither the earlier output nor the new one whole: {sorted(now)} "
              f"(staged directory at the signal: {staged})")
        old = now  # the signal came after the commit: nothing was tested mid-write
    check(False, "in 3 runs the signal never came while the staged directory was written")


def case_predict_sigterm_writing(exe, src, tmp):
    predict_sigterm_writing(exe, src, tmp, plots=False)


def case_predict_sigterm_plotting(exe, src, tmp):
    predict_sigterm_writing(exe, src, tmp, plots=True)


def case_predict_sigterm_kills_gnuplot(exe, src, tmp):
    """SIGTERM while gnuplot draws: the cleanup handler ends the gnuplot it started
    (SIGKILL, reaped) before removing the temporaries, so nothing outlives the command.
    A stand-in `gnuplot` first on PATH writes its pid and sleeps, so the signal always
    comes while it runs (and the test needs no real gnuplot)."""
    fake_bin = os.path.join(tmp, "fake-bin")
    os.mkdir(fake_bin)
    pid_file = os.path.join(tmp, "gnuplot.pid")
    with open(os.path.join(fake_bin, "gnuplot"), "w") as f:
        f.write(f'#!/bin/sh\necho $$ > "{pid_file}.part" && mv "{pid_file}.part" "{pid_file}"\n'
                "exec sleep 60\n")
    os.chmod(os.path.join(fake_bin, "gnuplot"), 0o755)
    plot_tmp = os.path.join(tmp, "plot-tmp")
    os.mkdir(plot_tmp)
    env = dict(os.environ, PATH=fake_bin + os.pathsep + os.environ.get("PATH", ""),
               TMPDIR=plot_tmp)
    case = os.path.join(src, "examples/joints/steel_smooth.toml")
    p = subprocess.Popen([exe, "predict", case, "--out", "out"], cwd=tmp, env=env,
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 60
    while not os.path.exists(pid_file) and p.poll() is None and time.monotonic() < deadline:
        time.sleep(0.005)
    check(os.path.exists(pid_file), f"the stand-in gnuplot never ran (exit {p.poll()})")
    with open(pid_file) as f:
        gnuplot = int(f.read())
    p.send_signal(signal.SIGTERM)
    rc = p.wait(timeout=60)
    stderr = p.stderr.read().decode()
    p.stderr.close()
    try:
        os.kill(gnuplot, 0)
        alive = True
        os.kill(gnuplot, signal.SIGKILL)
    except ProcessLookupError:
        alive = False
    check(rc == -signal.SIGTERM, f"exit {rc}, expected death by SIGTERM: {stderr}")
    check(not alive, f"gnuplot (pid {gnuplot}) outlived the killed predict")
    check(not leftovers(tmp), f"temporaries left after SIGTERM: {leftovers(tmp)}")
    check(not os.listdir(plot_tmp), f"gnuplot's temporaries left: {os.listdir(plot_tmp)}")
    check(not os.path.exists(os.path.join(tmp, "out")), "a half-written output was committed")


def case_stale_temporaries_removed(exe, src, tmp):
    write_history(os.path.join(tmp, "h.csv"), 100)
    dead = dead_pid()
    stale = [f".f.csv.tmp-{dead}-deadbeef", ".f.csv.tmp-0123abcd"]  # ours, an earlier version's
    live = f".f.csv.tmp-{os.getpid()}-0badf00d"  # a running process's: kept
    for name in stale + [live]:
        with open(os.path.join(tmp, name), "w") as f:
            f.write("partial")
    os.mkdir(os.path.join(tmp, ".dyn.tmp-89abcdef"))  # an earlier version's staged directory
    open(os.path.join(tmp, ".dyn.tmp-89abcdef", ".asperity-output"), "w").close()
    os.mkdir(os.path.join(tmp, f".dyn.tmp-{dead}-01234567"))
    r = run(exe, FLAT + ["--history=h.csv", "--out=f.csv"], tmp)
    check(r.returncode == 0, r.stderr)
    case = os.path.join(src, "examples/dynamics/harmonic_coulomb.toml")
    r = run(exe, ["dynamics", case, "--out", "dyn", "--no-plots"], tmp)
    check(r.returncode == 0, r.stderr)
    check(sorted(leftovers(tmp)) == [live], f"left: {leftovers(tmp)}")


def case_user_files_kept(exe, src, tmp):
    case = os.path.join(src, "examples/dynamics/harmonic_coulomb.toml")
    argv = ["dynamics", case, "--out", "dyn", "--no-plots"]
    r = run(exe, argv, tmp)
    check(r.returncode == 0, r.stderr)
    with open(os.path.join(tmp, "dyn", ".asperity-output")) as f:
        marker = f.read().splitlines()
    listed = marker[marker.index("files:") + 1:]
    check(listed == ["summary.json", "timeseries.csv"], f"marker lists {listed}")
    r = run(exe, argv, tmp)  # only its own files: replaced
    check(r.returncode == 0, r.stderr)
    with open(os.path.join(tmp, "dyn", "notes.txt"), "w") as f:
        f.write("mine")
    r = run(exe, argv, tmp)
    expect_exit2(r, "notes.txt", "did not write")
    check(os.path.exists(os.path.join(tmp, "dyn", "notes.txt")), "the user's file was deleted")
    # A hand-made empty marker does not make a directory asperity's.
    os.mkdir(os.path.join(tmp, "mine"))
    open(os.path.join(tmp, "mine", ".asperity-output"), "w").close()
    with open(os.path.join(tmp, "mine", "data.csv"), "w") as f:
        f.write("x\n")
    r = run(exe, ["dynamics", case, "--out", "mine", "--no-plots"], tmp)
    expect_exit2(r, "data.csv")
    check(os.path.exists(os.path.join(tmp, "mine", "data.csv")), "the user's file was deleted")


# ------------------------------------------------------------------ reads


def case_streams_refused(exe, src, tmp):
    for argv, frag in [
        (["predict", "/dev/zero"], "/dev/zero: the case file is not a regular file (it is a "
                                   "character device)"),
        (["dynamics", "/dev/urandom"], "/dev/urandom: the case file is not a regular file"),
        (["vibration", "/dev/zero"], "/dev/zero: the case file is not a regular file"),
        (FLAT + ["--history=/dev/zero", "--out=f.csv"], "not a regular file"),
        (["analyze", "/dev/zero", "--P=526N"], "not a regular file"),
        (["roughness", "--surface", "/dev/zero,/dev/zero"], "not a regular file"),
        (["predict", tmp], "is not a regular file (it is a directory)"),
    ]:
        start = time.monotonic()
        r = run(exe, argv, tmp, timeout=30)
        expect_exit2(r, frag)
        check("9223372036854775807" not in r.stderr, r.stderr)
        # Refused before reading: no 4 GB read (generous bound; a read would take minutes).
        check(time.monotonic() - start < 20, f"{argv} took {time.monotonic() - start:.1f} s")
    fifo = os.path.join(tmp, "pipe.toml")
    os.mkfifo(fifo)
    r = run(exe, ["predict", fifo], tmp, timeout=30)  # no writer: must not block
    expect_exit2(r, "not a regular file (it is a pipe)")


def case_case_file_cap(exe, src, tmp):
    big = os.path.join(tmp, "big.toml")
    with open(big, "wb") as f:
        f.truncate(5 * 1024 * 1024)
    r = run(exe, ["predict", big], tmp)
    expect_exit2(r, "is 5 MiB, more than the 4 MiB this reader accepts")


def case_case_file_invalid_utf8(exe, src, tmp):
    path = os.path.join(tmp, "bad.toml")
    with open(path, "wb") as f:
        f.write(b"# a case\n[joint]\nname = \"ab\xffcd\"\n")
    for cmd in ("predict", "dynamics", "vibration"):
        r = run(exe, [cmd, path], tmp)
        expect_exit2(r, f"{path}:3:11: the case file is not valid UTF-8 text (byte 0xFF")


# ------------------------------------------------------------------ implausible input


def json_of(exe, argv, tmp):
    import json
    r = run(exe, argv + ["--json"], tmp)
    check(r.returncode == 0, f"exit {r.returncode}: {r.stderr}")
    return json.loads(r.stdout), r.stderr


def case_flat_psi_limits(exe, src, tmp):
    # psi = 0.01 gave mu = 49.9 silently; 1e-300 exited 3 with "no sign change".
    for psi in ("0.01", "1e-300", "0.049"):
        r = run(exe, ["flat", "--beta=0.04", f"--psi={psi}", "--nu=0.3", "--P-star=1e-3"], tmp)
        expect_exit2(r, f"--psi {psi} is not allowed", "at least 0.05")
    # Between the limit and the thesis's smallest psi (0.5, Fig. 4.4): a warning, and the
    # mu of 7.9 flagged (above 3, the largest of the thesis's computations).
    j, err = json_of(exe, ["flat", "--beta=0.04", "--psi=0.1", "--nu=0.3", "--P-star=1e-3"], tmp)
    check(any("plasticity index psi = 0.1 is below 0.5" in w for w in j["warnings"]), j["warnings"])
    check(any("friction coefficient mu = 7.886 is above 3" in w for w in j["warnings"]),
          j["warnings"])
    check("warning: plasticity index" in err, err)
    # Fig. 4.4's own inputs: no warning (a list that cannot be always empty: see above).
    j, err = json_of(exe, ["flat", "--beta=0.04", "--psi=0.5", "--nu=0.3", "--P-star=1e-3"], tmp)
    check(j["warnings"] == [] and "warning" not in err, f"{j['warnings']} {err}")


def case_flat_beta_limit(exe, src, tmp):
    r = run(exe, ["flat", "--beta=1e6", "--psi=0.5", "--nu=0.3", "--P-star=1e-3"], tmp)
    expect_exit2(r, "--beta 1e+06 is not allowed", "1/pi")
    j, _ = json_of(exe, ["flat", "--beta=0.1", "--psi=0.5", "--nu=0.3", "--P-star=1e-3"], tmp)
    check(any("beta = sigma R eta = 0.1 is above 0.06" in w for w in j["warnings"]),
          j["warnings"])


def case_shear_modulus_range(exe, src, tmp):
    base = SPHERE[:1] + ["--E1=200GPa", "--nu1=0.3", "--E2=207GPa", "--nu2=0.3", "--H=6.83GPa",
                         "--R1=2.5mm", "--P=35N", "--mu-cfc=0.284"]
    r = run(exe, base + ["--G1=500GPa"], tmp)  # G > E/2: nu < 0
    expect_exit2(r, "--G1 = 5e+11 Pa is not allowed with --E1 = 2e+11 Pa", "E/3 <= G <= E/2")
    r = run(exe, base + ["--G1=60GPa"], tmp)  # G < E/3: nu > 0.5
    expect_exit2(r, "--G1 = 6e+10 Pa", "G >= E/3 is nu <= 0.5")
    r = run(exe, base + ["--G1=100GPa"], tmp)  # G = E/2 (nu = 0): allowed
    check(r.returncode == 0, r.stderr)


def case_sphere_tiny_hardness(exe, src, tmp):
    argv = ["sphere", "--E1=207GPa", "--nu1=0.3", "--E2=207GPa", "--nu2=0.3", "--H2=1e-30Pa",
            "--R1=2.5mm", "--P=35N", "--mu-cfc=0.284"]
    j, err = json_of(exe, argv, tmp)
    check(any("hardness H = 1e-30 Pa" in w and "outside 1e-3 to 0.2 E*" in w
              for w in j["warnings"]), j["warnings"])
    check("warning: hardness" in err, err)


def case_dynamics_loop_cycles_warned(exe, src, tmp):
    import json
    with open(os.path.join(src, "examples/dynamics/harmonic_coulomb.toml")) as f:
        text = f.read()
    check("loop_cycles = 5" in text, "the example changed")
    path = os.path.join(tmp, "long.toml")
    with open(path, "w") as f:
        f.write(text.replace("loop_cycles = 5", "loop_cycles = 1000"))
    r = run(exe, ["dynamics", path, "--out", "o", "--no-plots"], tmp)
    check(r.returncode == 0, r.stderr)
    with open(os.path.join(tmp, "o", "summary.json")) as f:
        summary = json.load(f)
    check("steady_loop" not in summary, "steady_loop present")
    check(any("steady_loop is left out: loop_cycles = 1000" in w for w in summary["warnings"]),
          summary["warnings"])
    check("warning: steady_loop is left out" in r.stderr, r.stderr)


# ------------------------------------------------------------------ messages


def case_messages_name_the_input(exe, src, tmp):
    # analyze of an X3P: no binary echoed.
    r = run(exe, ["analyze", os.path.join(src, "tests/data/mountainsmap-650x650.x3p"),
                  "--P=526N"], tmp)
    expect_exit2(r, "is a zip archive (an X3P height map?)")
    check(all(c >= " " or c == "\n" for c in r.stderr), f"control characters: {r.stderr!r}")
    case = os.path.join(src, "examples/joints/steel420_two_bolts.toml")
    for flag, value in (("--noise-Q", "-1N"), ("--k-pzt", "0N/um")):
        r = run(exe, ["synthesize", case, "--preload=526N", "--imposed=6.75um", "--out=s.csv",
                      f"{flag}={value}"], tmp)
        expect_exit2(r, f"{flag} = ")
    with open(case) as f:
        text = f.read()
    check("count = 2" in text, "the example changed")
    bad = os.path.join(tmp, "bolts_two.toml")  # the example has no relative paths
    with open(bad, "w") as f:
        f.write(text.replace("count = 2", 'count = "two"'))
    r = run(exe, ["predict", bad], tmp)
    expect_exit2(r, 'load.bolts.count = "two": must be a whole number')
    # Heights of +-1e300 are not "flat" (their squares overflowed).
    with open(os.path.join(tmp, "big.csv"), "w") as f:
        f.write("x[um],z[um]\n")
        for i in range(8000):
            f.write(f"{i * 0.5},{1e300 if i % 2 else -1e300}\n")
    r = run(exe, ["roughness", "--surface", "big.csv,big.csv"], tmp)
    expect_exit2(r, "heights up to 1e+294 m", "check the unit")
    check("flat" not in r.stderr, r.stderr)
    scan = os.path.join(src, "examples/roughness/pzt_max.csv")
    r = run(exe, ["roughness", "--surface", f"{scan}@diagonal,{scan}@min"], tmp)
    expect_exit2(r, 'unknown tag "@diagonal" (allowed: @max, @min')


if __name__ == "__main__":
    sys.exit(main(globals()))

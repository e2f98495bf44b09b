#!/usr/bin/env python3
"""Progress of `asperity predict` (issue 13): on a terminal a bar redrawn after every
preload; otherwise (a log, a pipe) a line "asperity predict: i/n preloads (p %)" at most
every ASPERITY_PROGRESS_INTERVAL seconds (default 10; 0 = after every preload), the last
one n/n, nothing for a sweep shorter than the interval; a bad ASPERITY_PROGRESS_INTERVAL
is refused (exit 2) before any work.

Usage: predict_progress_cases.py ASPERITY_EXE SOURCE_DIR CASE. Standard library only.
Exit 0 = pass, 1 = fail.
"""
import errno
import json
import os
import pty
import re
import subprocess
import sys
import time

from case_runner import check, main  # tests/cli/case_runner.py

VARIABLE = "ASPERITY_PROGRESS_INTERVAL"
LINE = re.compile(r"asperity predict: (\d+)/(\d+) preloads \((\d+) %\)")
BAR_WIDTH = 30  # predict_command.cpp



def sweep_case(src, tmp, n):
    """examples/joints/steel_smooth.toml with n preloads (200, 205, ... N) and no
    excitation: the load cases alone (a few ms each)."""
    with open(os.path.join(src, "examples/joints/steel_smooth.toml")) as f:
        text = f.read()
    bolts = text[text.index("bolts = {"):]
    bolts = bolts[:bolts.index("\n")]
    preloads = ", ".join(f'"{200 + 5 * i} N"' for i in range(n))
    text = text.replace(bolts, f"preloads = [{preloads}]")
    text = text[:text.index("[excitation]")]
    path = os.path.join(tmp, f"sweep{n}.toml")
    with open(path, "w") as f:
        f.write(text)
    return path


def environment(interval):
    env = dict(os.environ)
    env.pop(VARIABLE, None)
    if interval is not None:
        env[VARIABLE] = interval
    return env


def run_piped(exe, argv, interval, tmp):
    """stderr to a pipe (not a terminal)."""
    return subprocess.run([exe] + argv, capture_output=True, text=True, cwd=tmp, timeout=120,
                          env=environment(interval))


def progress_lines(stderr, n):
    """The (i, percent) of every progress line; every line of stderr must be one."""
    out = []
    for line in stderr.splitlines():
        m = LINE.fullmatch(line)
        check(m, f"stderr line is not a progress line: {line!r}")
        i, total, percent = int(m.group(1)), int(m.group(2)), int(m.group(3))
        check(total == n, f"{line!r}: total {total}, the case has {n} preloads")
        # Whole per cent rounded down, so 100 % means every preload is done.
        check(percent == 100 * i // n, f"{line!r}: expected {100 * i // n} %")
        out.append(i)
    return out


def case_lines_every_preload(exe, src, tmp):
    n = 40
    case = sweep_case(src, tmp, n)
    r = run_piped(exe, ["predict", case, "--json"], "0", tmp)
    check(r.returncode == 0, r.stderr)
    check(len(json.loads(r.stdout)["loads"]) == n, "the JSON does not hold every preload")
    counts = progress_lines(r.stderr, n)
    # Interval 0: one line after each preload, counting 1..n in order (the counter is
    # taken under a lock, whatever the order in which the threads finish).
    check(counts == list(range(1, n + 1)), f"counts {counts}")


def case_lines_throttled(exe, src, tmp):
    # A fractional interval: lines at most every millisecond, the counts increasing and
    # the last one n/n once any line was printed. Each load case takes milliseconds
    # (backbone tabulation), so 40 of them outlast 1 ms and print at least one line.
    n = 40
    case = sweep_case(src, tmp, n)
    r = run_piped(exe, ["predict", case, "--json"], "0.001", tmp)
    check(r.returncode == 0, r.stderr)
    counts = progress_lines(r.stderr, n)
    check(counts, "no progress line at all")
    check(all(a < b for a, b in zip(counts, counts[1:])), f"counts not increasing: {counts}")
    check(counts[-1] == n, f"the last line is {counts[-1]}/{n}, not {n}/{n}")


def case_short_run_silent(exe, src, tmp):
    # Default interval (variable unset): a sweep shorter than 10 s prints no line.
    n = 8
    case = sweep_case(src, tmp, n)
    start = time.monotonic()
    r = run_piped(exe, ["predict", case, "--json"], None, tmp)
    elapsed = time.monotonic() - start
    check(r.returncode == 0, r.stderr)
    check(len(json.loads(r.stdout)["loads"]) == n, "the JSON does not hold every preload")
    # Not a timing assertion: the premise of the check below. Eight load cases take
    # about 0.05 s; a run of 10 s or more would be allowed its lines.
    check(elapsed < 10.0, f"the run took {elapsed:.1f} s, not a short sweep: cannot check")
    check(r.stderr == "", f"a short sweep printed: {r.stderr!r}")
    # A large interval behaves as the default for the same run.
    r = run_piped(exe, ["predict", case, "--json"], "3600", tmp)
    check(r.returncode == 0 and r.stderr == "", f"interval 3600 printed: {r.stderr!r}")


def case_terminal_bar(exe, src, tmp):
    # stderr a terminal (a pseudo-terminal): the bar "\r[###   ] i/n preloads", redrawn
    # after every preload, a newline after n/n; never the plain lines, whatever the
    # interval.
    n = 12
    case = sweep_case(src, tmp, n)
    master, slave = pty.openpty()
    with open(os.path.join(tmp, "stdout.json"), "w") as stdout_file:
        p = subprocess.Popen([exe, "predict", case, "--json"], cwd=tmp, env=environment("0"),
                             stdin=subprocess.DEVNULL, stdout=stdout_file, stderr=slave)
    os.close(slave)
    shown = b""
    while True:
        try:
            chunk = os.read(master, 4096)
        except OSError as e:  # EIO: every writer of the terminal has closed it
            if e.errno != errno.EIO:
                raise
            break
        if not chunk:
            break
        shown += chunk
    os.close(master)
    rc = p.wait(timeout=60)
    with open(os.path.join(tmp, "stdout.json")) as f:
        stdout = f.read()
    check(rc == 0, f"exit {rc}: {shown!r}")
    check(len(json.loads(stdout)["loads"]) == n, "the JSON does not hold every preload")
    text = shown.decode()
    check("asperity predict:" not in text, f"plain progress lines on a terminal: {text!r}")
    # The terminal turns the final "\n" into "\r\n" (ONLCR).
    check(text.endswith("\r\n"), f"the bar does not end its line: {text!r}")
    frames = text[:-2].split("\r")
    check(frames[0] == "", f"output before the first bar: {frames[0]!r}")
    bar = re.compile(r"\[([# ]{%d})\] (\d+)/(\d+) preloads" % BAR_WIDTH)
    counts = []
    for frame in frames[1:]:
        m = bar.fullmatch(frame)
        check(m, f"not a bar: {frame!r}")
        i, total = int(m.group(2)), int(m.group(3))
        check(total == n, f"{frame!r}: total {total}, expected {n}")
        filled = m.group(1)
        check(filled == "#" * (BAR_WIDTH * i // n) + " " * (BAR_WIDTH - BAR_WIDTH * i // n),
              f"{frame!r}: the bar does not show {i}/{n}")
        counts.append(i)
    check(counts == list(range(1, n + 1)), f"counts {counts}")


def case_bad_interval(exe, src, tmp):
    case = sweep_case(src, tmp, 3)
    out = os.path.join(tmp, "out")
    for value in ["abc", "-1", "nan", "inf", "", "10s", " 5", "1e999", "0x10"]:
        r = run_piped(exe, ["predict", case, "--out", out, "--no-plots"], value, tmp)
        check(r.returncode == 2, f"{VARIABLE}={value!r}: exit {r.returncode}: {r.stderr}")
        check(r.stdout == "", f"{VARIABLE}={value!r}: stdout {r.stdout!r}")
        line = r.stderr.strip()
        check(len(r.stderr.splitlines()) == 1, f"not one line: {r.stderr!r}")
        for needle in [f'asperity: error: {VARIABLE}="{value}" is not allowed',
                       "a number >= 0", "the default"]:
            check(needle in line, f"{VARIABLE}={value!r}: message lacks {needle!r}: {line}")
        check(not os.path.exists(out), f"{VARIABLE}={value!r}: the output was written")
    # A control character is shown escaped, not sent to the terminal.
    r = run_piped(exe, ["predict", case, "--json"], "1\x1b[2J", tmp)
    check(r.returncode == 2 and '="1\\x1B[2J"' in r.stderr and "\x1b" not in r.stderr,
          f"escape sequence echoed: {r.stderr!r}")


def case_bad_threads(exe, src, tmp):
    # ASPERITY_THREADS (core::worker_count) is checked by every command before any work:
    # refused with exit 2, never ignored or capped.
    case = sweep_case(src, tmp, 3)
    out = os.path.join(tmp, "out")
    for value in ["abc", "0", "-2", "", "257", "1.5", "4 "]:
        env = {**os.environ, "ASPERITY_THREADS": value}
        r = subprocess.run([exe, "predict", case, "--out", out, "--no-plots"], capture_output=True,
                           text=True, cwd=tmp, timeout=120, env=env)
        check(r.returncode == 2, f"ASPERITY_THREADS={value!r}: exit {r.returncode}: {r.stderr}")
        check(f'asperity: error: environment variable ASPERITY_THREADS="{value}" is not allowed: '
              "an integer from 1 to 256" in r.stderr, f"ASPERITY_THREADS={value!r}: {r.stderr}")
        check(not os.path.exists(out), f"ASPERITY_THREADS={value!r}: the output was written")
    for value in ["1", "2", "256"]:
        env = {**os.environ, "ASPERITY_THREADS": value}
        r = subprocess.run([exe, "predict", case, "--json"], capture_output=True, text=True,
                           cwd=tmp, timeout=120, env=env)
        check(r.returncode == 0, f"ASPERITY_THREADS={value!r}: exit {r.returncode}: {r.stderr}")


if __name__ == "__main__":
    sys.exit(main(globals()))

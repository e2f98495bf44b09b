"""The Python example and the figure script run (matplotlib, Agg backend)."""
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_sphere_example_prints_table_3_2(tmp_path):
    png = tmp_path / "loops.png"
    out = subprocess.run([sys.executable, str(ROOT / "examples" / "sphere_example.py"), str(png)],
                         check=True, capture_output=True, text=True).stdout
    assert "P_c = 152.8 N" in out
    assert "bke    1.444 (1.444)" in out
    assert "bke    1.639 (1.639)" in out
    assert png.stat().st_size > 10_000


def test_figures_script(tmp_path):
    subprocess.run([sys.executable, str(ROOT / "scripts" / "figures_ch3.py"), str(tmp_path)],
                   check=True, capture_output=True, text=True)
    for fig in ("3_2", "3_4", "3_6", "3_7", "3_8"):
        assert (tmp_path / f"fig_{fig}.png").stat().st_size > 10_000


def test_figures_ch4_script(tmp_path):
    # Fig. 4.4-4.7 and Table 4.1 (docs/rough_flat.md) regenerate.
    out = subprocess.run([sys.executable, str(ROOT / "scripts" / "figures_ch4.py"), str(tmp_path)],
                         check=True, capture_output=True, text=True).stdout
    assert "Table 4.1" in out
    for fig in ("4_4", "4_5", "4_6", "4_7"):
        assert (tmp_path / f"fig_{fig}.png").stat().st_size > 10_000


def _fake_tree(tmp_path, cmake_body):
    """A copy of scripts/run-example.sh with stand-ins for setup.sh, cmake and the CLI."""
    import shutil
    (tmp_path / "scripts").mkdir()
    shutil.copy(ROOT / "scripts" / "run-example.sh", tmp_path / "scripts")
    (tmp_path / "scripts" / "setup.sh").write_text("echo setting up\n")
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    cmake = bin_dir / "cmake"
    cmake.write_text("#!/bin/sh\n" + cmake_body)
    cmake.chmod(0o755)
    cli = tmp_path / "build" / "release" / "src" / "cli"
    cli.mkdir(parents=True)
    (cli / "asperity").write_text("#!/bin/sh\necho predicted\n")
    (cli / "asperity").chmod(0o755)
    logs = tmp_path / "logs"
    logs.mkdir()
    env = {"PATH": f"{bin_dir}:/usr/bin:/bin", "TMPDIR": str(logs)}
    return subprocess.run(["bash", str(tmp_path / "scripts" / "run-example.sh")],
                          capture_output=True, text=True, env=env), logs


def test_run_example_is_quiet_when_the_build_works(tmp_path):
    p, logs = _fake_tree(tmp_path, "echo configured; echo '[66/66] Linking'\n")
    assert p.returncode == 0, p.stderr
    assert p.stdout == "predicted\n" and p.stderr == ""
    assert list(logs.iterdir()) == []  # the log is removed on success


def test_run_example_shows_the_compiler_error_when_the_build_fails(tmp_path):
    # The build's own message reaches the terminal, not just ninja's "subcommand failed".
    p, logs = _fake_tree(tmp_path, 'if [ "$1" = "--build" ]; then\n'
                         '  echo "src/joint/case.cpp:12:3: error: expected ; before }"\n'
                         '  echo "ninja: build stopped: subcommand failed."; exit 1\nfi\n'
                         "echo configured\n")
    assert p.returncode == 1
    assert "build (cmake --build --preset default) failed (exit 1)" in p.stderr
    assert "src/joint/case.cpp:12:3: error: expected ; before }" in p.stderr
    assert "predicted" not in p.stdout  # stopped before running the example
    kept = list(logs.iterdir())
    assert len(kept) == 1 and str(kept[0]) in p.stderr  # the full log is kept and named
    assert "setting up" in kept[0].read_text()


def test_brb_backbone_plot_script(tmp_path):
    # examples/brb/plot_backbones.py on a stand-in for a run's nonlinear_mode.csv (the real
    # runs take minutes): the columns it reads, the figure written.
    run = tmp_path / "run"
    run.mkdir()
    rows = ["log10_amplitude,frequency_hz,damping_ratio,tip_z_acceleration_m_s2"]
    rows += [f"{-7 + k},{184 - k},{1e-6 * 10 ** k},{0.03 * 10 ** k}" for k in range(4)]
    (run / "nonlinear_mode.csv").write_text("\n".join(rows) + "\n")
    png = tmp_path / "backbones.png"
    subprocess.run([sys.executable, str(ROOT / "examples" / "brb" / "plot_backbones.py"),
                    str(run), str(run), str(png)], check=True, capture_output=True, text=True)
    assert png.stat().st_size > 10_000

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

"""The example script runs headless on a tiny world and writes its figure."""

import os
import subprocess
import sys
from pathlib import Path

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "explore_and_localise.py"


def test_the_example_runs_and_plots(tmp_path):
    figure = tmp_path / "figure.png"
    result = subprocess.run(
        [sys.executable, EXAMPLE, "--width", "120", "--height", "24", "--queries", "4",
         "--route", "line:x0=1.5,y0=2,x1=4,y1=2.5,speed_m_s=0.5,fps=4", "--out", figure],
        capture_output=True, text=True, env={**os.environ, "MPLBACKEND": "Agg"}, check=False)
    assert result.returncode == 0, result.stderr
    assert figure.stat().st_size > 1000
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert result.stdout.count("query at") == 4

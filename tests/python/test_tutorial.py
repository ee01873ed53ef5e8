"""docs/tutorial.md's Python part: examples/real_frames.py on the real arena frames."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

SOURCE = Path(__file__).resolve().parents[2]
EXAMPLE = SOURCE / "examples" / "real_frames.py"
ROUTE = Path(os.environ.get("OMNINAV_SHARED_DATA", SOURCE.parent / "shared" / "data")) / \
    "real" / "ftl-arena" / "route"


def test_the_tutorial_example_maps_localises_and_plots_the_arena(tmp_path):
    if not ROUTE.is_dir():
        pytest.skip(f"shared data {ROUTE} is absent")
    figure = tmp_path / "arena.png"
    result = subprocess.run([sys.executable, EXAMPLE, ROUTE, "--out", figure],
                            capture_output=True, text=True,
                            env={**os.environ, "MPLBACKEND": "Agg"}, check=False)
    assert result.returncode == 0, result.stderr
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "130 panoramas of 180 x 50 pixels" in result.stdout
    found = re.search(r"localised (\d+) queries: (\d+) at a place explored just before or after",
                      result.stdout)
    assert found, result.stdout
    queries, right = map(int, found.groups())
    assert queries == 65
    # The order of the frames is the only truth here: a query lies between the places explored
    # just before and after it. Measured: 65 of 65; at least 95 % must hold.
    assert right >= 62, result.stdout

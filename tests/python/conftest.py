"""Shared fixtures of the Python module's tests: the omninav program of the same build (to
compare against), and a tiny rendered route written as a BoB database by `omninav render`."""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

# The panoramas of every test: small, so that the whole suite stays well under a minute.
WIDTH_PX = 120
HEIGHT_PX = 24
# A small room whose routes below stay clear of its furniture.
WORLD = "room:seed=6,boxes=6"
ROUTE = "circle:cx=3,cy=2.5,radius_m=0.8,turns=0.5,speed_m_s=0.25,fps=8"


def omninav_program():
    program = os.environ.get("OMNINAV_EXE")
    if not program or not Path(program).exists():
        pytest.skip("OMNINAV_EXE does not name the omninav program (run the tests through ctest)")
    return program


def run_omninav(*args, **kwargs):
    """Runs `omninav args...` and returns its standard output; fails the test with its message
    when it exits non-zero."""
    result = subprocess.run(
        [omninav_program(), "--quiet", *map(str, args)],
        capture_output=True,
        text=True,
        check=False,
        **kwargs,
    )
    assert result.returncode == 0, f"omninav {' '.join(map(str, args))}: {result.stderr}"
    return result.stdout


def render(out, trajectory, world=WORLD):
    run_omninav(
        "render",
        "--world", world,
        "--trajectory", trajectory,
        "--width", WIDTH_PX,
        "--height", HEIGHT_PX,
        "--rays-per-pixel", 1,
        "--out", out,
    )
    return out


@pytest.fixture(scope="session")
def route_db(tmp_path_factory):
    """Half a circle in a small room: some 80 panoramas with their true poses."""
    folder = tmp_path_factory.mktemp("route") / "db"
    return render(folder, ROUTE)


@pytest.fixture(scope="session")
def query_db(tmp_path_factory):
    """Queries 8 cm inside the route, at poses of their own."""
    folder = tmp_path_factory.mktemp("queries") / "db"
    return render(folder, "circle:cx=3,cy=2.5,radius_m=0.72,turns=0.5,speed_m_s=0.25,fps=1")


@pytest.fixture(scope="session")
def route_map(tmp_path_factory, route_db):
    """The route explored into a map by `omninav explore`."""
    path = tmp_path_factory.mktemp("map") / "route.vmem"
    run_omninav("explore", "--input", route_db, "--out", path)
    return path

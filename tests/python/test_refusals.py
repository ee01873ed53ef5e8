"""What the command line refuses, Python refuses too, with omninav's errors instead of a crash:
poses no map can hold, poses the renderer cannot trace, an array whose copy cannot be made."""

import math
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import omninav
from conftest import HEIGHT_PX, WIDTH_PX, WORLD

ABSURD_POSES = [
    omninav.CameraPose(1e300, 0.0, 1.0),
    omninav.CameraPose(float("nan"), 2.0, 1.0),
    omninav.CameraPose(2.0, float("inf"), 1.0),
    omninav.CameraPose(1e30, 2.0, 1.0),
    omninav.CameraPose(2.0, 2.0, 1.0, heading_rad=float("nan")),
]


@pytest.mark.parametrize("pose", ABSURD_POSES)
def test_a_frame_refuses_a_truth_no_map_can_hold(pose):
    image = np.zeros((HEIGHT_PX, WIDTH_PX, 3), np.uint8)
    with pytest.raises(omninav.InputError, match="is not a|not a finite"):
        omninav.Frame(image, truth=pose, source="frame 7")
    frame = omninav.Frame(image, source="frame 7")
    with pytest.raises(omninav.InputError, match="frame 7"):
        frame.truth = pose
    assert frame.truth is None


def test_a_huge_truth_never_reaches_a_saved_map(tmp_path):
    world = omninav.World(WORLD, width_px=WIDTH_PX, height_px=HEIGHT_PX, rays_per_pixel=1)
    renderer = omninav.Renderer(world)
    pose = omninav.CameraPose(3.0, 2.5, 1.0)
    good = [omninav.Frame(renderer.render(pose), index=i, truth=pose) for i in range(3)]
    memory = omninav.Map()
    memory.explore(good)
    memory.save(tmp_path / "m.vmem")
    with pytest.raises(omninav.InputError):
        memory.explore([omninav.Frame(renderer.render(pose), truth=omninav.CameraPose(1e300, 0, 1))])
    assert omninav.Map.open(tmp_path / "m.vmem").place_count == memory.place_count


@pytest.mark.parametrize("pose", ABSURD_POSES)
def test_the_renderer_refuses_a_pose_it_cannot_trace(pose):
    world = omninav.World(WORLD, width_px=WIDTH_PX, height_px=HEIGHT_PX, rays_per_pixel=1)
    renderer = omninav.Renderer(world)
    with pytest.raises(omninav.InputError, match="the camera pose"):
        renderer.render(pose)
    assert renderer.render(omninav.CameraPose(3.0, 2.5, 1.0)).shape == (HEIGHT_PX, WIDTH_PX, 3)


def test_an_array_whose_copy_cannot_be_made_raises_memory_error():
    # In a child with its address space limited: a broadcast view of 30 GB (strides of 0, so
    # not packed) needs a packed copy, which cannot be allocated.
    code = textwrap.dedent("""
        import resource
        import numpy as np
        import omninav
        resource.setrlimit(resource.RLIMIT_AS, (8 << 30, 8 << 30))
        view = np.broadcast_to(np.zeros((1, 1, 3), np.uint8), (100000, 100000, 3))
        try:
            omninav.Frame(view)
        except MemoryError:
            print("MemoryError")
    """)
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            check=False)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "MemoryError"

"""Sequences read from Python carry the poses their source records: a CSV's, and a BoB
database's as the renderer made them."""

import math

import numpy as np
from PIL import Image

import omninav
from conftest import HEIGHT_PX, ROUTE, WIDTH_PX, WORLD


def test_a_csv_sequence_gives_its_rows_poses_in_radians(tmp_path):
    rows = [("a.png", 1.0, 2.0, 90.0), ("b.png", 1.5, -0.25, -45.0), ("c.png", 0.0, 0.0, 180.0)]
    for i, (name, *_) in enumerate(rows):
        Image.fromarray(np.full((4, 8, 3), 40 * i, np.uint8), "RGB").save(tmp_path / name)
    lines = ["file,x_m,y_m,heading_deg,time_s"]
    lines += [f"{name},{x},{y},{h},{0.5 * i}" for i, (name, x, y, h) in enumerate(rows)]
    (tmp_path / "poses.csv").write_text("\n".join(lines) + "\n")
    frames = list(omninav.open_sequence(tmp_path / "poses.csv"))
    assert len(frames) == 3
    for i, (frame, (name, x, y, heading_deg)) in enumerate(zip(frames, rows)):
        assert frame.source.endswith(name)
        assert (frame.truth.x_m, frame.truth.y_m) == (x, y)
        assert math.isclose(frame.truth.heading_rad, math.radians(heading_deg), abs_tol=1e-12)
        assert frame.time_s == 0.5 * i
        assert (frame.image == 40 * i).all()


def test_a_rendered_database_gives_the_renderers_poses(route_db):
    world = omninav.World(WORLD, width_px=WIDTH_PX, height_px=HEIGHT_PX, rays_per_pixel=1)
    trajectory = world.trajectory(ROUTE)
    sequence = omninav.open_sequence(route_db)
    assert "BoB" in sequence.describe() and not sequence.needs_unwrapping
    frames = list(sequence)
    assert len(frames) == len(trajectory)
    for frame, (time_s, pose) in zip(frames, trajectory):
        # BoB databases store millimetres and degrees: the poses come back to within rounding.
        assert abs(frame.truth.x_m - pose.x_m) < 1e-6 and abs(frame.truth.y_m - pose.y_m) < 1e-6
        assert abs(math.remainder(frame.truth.heading_rad - pose.heading_rad, 2 * math.pi)) < 1e-9
        assert frame.image.shape == (HEIGHT_PX, WIDTH_PX, 3)


def test_the_renderer_from_python_draws_the_databases_pixels(route_db):
    world = omninav.World(WORLD, width_px=WIDTH_PX, height_px=HEIGHT_PX, rays_per_pixel=1)
    renderer = omninav.Renderer(world)
    frame = next(omninav.open_sequence(route_db))
    np.testing.assert_array_equal(renderer.render(frame.truth, frame.time_s or 0.0, frame.index),
                                  frame.image)


def test_a_csv_sequence_gives_the_robots_odometry_beside_the_truth(tmp_path):
    Image.fromarray(np.zeros((4, 8, 3), np.uint8), "RGB").save(tmp_path / "a.png")
    (tmp_path / "poses.csv").write_text(
        "file,x_m,y_m,heading_deg,odometry_x_m,odometry_y_m,odometry_heading_deg\n"
        "a.png,1.0,2.0,90.0,1.1,2.2,80.0\n")
    frame = next(omninav.open_sequence(tmp_path / "poses.csv"))
    assert (frame.truth.x_m, frame.truth.y_m) == (1.0, 2.0)
    assert (frame.odometry.x_m, frame.odometry.y_m) == (1.1, 2.2)
    assert math.isclose(frame.odometry.heading_rad, math.radians(80.0), abs_tol=1e-12)


def test_a_tour_covers_the_floor_in_lanes(tmp_path):
    world = omninav.World("room:boxes=0", width_px=WIDTH_PX, height_px=HEIGHT_PX,
                          rays_per_pixel=1)
    tour = world.trajectory("tour:lane_m=0.5,clearance_m=0.25,fps=2")
    xs = [pose.x_m for _, pose in tour]
    ys = [pose.y_m for _, pose in tour]
    # The default room is 6 x 5 m: the lanes reach within the clearance of every wall.
    assert min(xs) < 0.35 and max(xs) > 5.65 and min(ys) < 0.35 and max(ys) > 4.65

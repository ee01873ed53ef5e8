"""Maps organised into a lattice, routes over it, and the navigator driving a robot written in
Python to a goal image, all checked against the renderer's true poses."""

import math

import pytest

import omninav
from conftest import HEIGHT_PX, WIDTH_PX, WORLD, render

GRID = "grid:x0=2,y0=1.8,nx=5,ny=4,spacing_m=0.3"


class RenderedRobot:
    """A robot of the caller's: it shows what the renderer sees from its pose and moves as
    told (the world is open where it drives)."""

    def __init__(self, renderer, pose):
        self.renderer = renderer
        self.pose = pose

    def view(self, step):
        return self.renderer.render(self.pose, frame_index=step)

    def move(self, turn_rad, distance_m):
        heading = self.pose.heading_rad + turn_rad
        self.pose = omninav.CameraPose(self.pose.x_m + distance_m * math.cos(heading),
                                       self.pose.y_m + distance_m * math.sin(heading),
                                       self.pose.z_m, heading_rad=heading)
        return distance_m

    def truth(self):
        return self.pose


@pytest.fixture(scope="module")
def organised_grid(tmp_path_factory):
    database = render(tmp_path_factory.mktemp("grid") / "db", GRID)
    memory = omninav.Map()
    memory.explore(database)  # a grid database: every image a place, headings its own
    memory.organise(step_m=0.3)  # a grid: the spacing is what it says
    return memory


def distance_m(a, b):
    return math.hypot(a.x_m - b.x_m, a.y_m - b.y_m)


def test_the_lattice_keeps_the_grids_shape(organised_grid):
    places = organised_grid.places()
    assert len(places) >= 16  # 20 grid points, less any inside furniture
    assert all(p.lattice_position is not None for p in places)
    # Lattice distances between places, over true distances: one scale for the whole grid
    # (the lattice has its own frame, so only distances compare).
    ratios = []
    for i, a in enumerate(places):
        for b in places[i + 1:]:
            true = distance_m(a.truth, b.truth)
            lattice = math.dist(a.lattice_position, b.lattice_position)
            ratios.append(lattice / true)
    ratios.sort()
    median = ratios[len(ratios) // 2]
    assert 0.5 < median < 2
    within = sum(abs(r / median - 1) < 0.35 for r in ratios)
    assert within > 0.8 * len(ratios)


def test_a_route_joins_neighbouring_places(organised_grid):
    places = organised_grid.places()
    goal = len(places) - 1
    plan = organised_grid.plan_route(goal)
    route = plan.route_from(0)
    assert route[0] == 0 and route[-1] == goal
    for a, b in zip(route, route[1:]):
        assert distance_m(places[a].truth, places[b].truth) < 0.3 * 1.6


def test_routes_follow_the_links_section_of_the_config(organised_grid):
    places = organised_grid.places()
    goal = len(places) - 1
    config = omninav.NavigationConfig.load()
    assert config.links.revisit_run == 5 and config.belief.confident_share == 0.5
    assert config.links.neighbour_spacings == 1.0  # lattice.yaml's, settable as every key
    # No grid pair passes a check this strict: the grid still hangs together by its nearest
    # pairs (confirmed_links joins the pieces), so the route still goes from neighbour to
    # neighbour.
    config.links.grid_direction_deg = 0.0
    route = organised_grid.plan_route(goal, config=config).route_from(0)
    assert route[0] == 0 and route[-1] == goal
    for a, b in zip(route, route[1:]):
        assert distance_m(places[a].truth, places[b].truth) < 0.3 * 1.6


def test_the_navigator_drives_a_python_robot_to_the_goal_image(organised_grid):
    world = omninav.World(WORLD, width_px=WIDTH_PX, height_px=HEIGHT_PX, rays_per_pixel=1)
    renderer = omninav.Renderer(world)
    places = organised_grid.places()
    goal = len(places) - 1  # the grid's far corner from place 0
    goal_pose = places[goal].truth
    start = places[0].truth
    robot = RenderedRobot(renderer, omninav.CameraPose(start.x_m, start.y_m, start.z_m,
                                                       heading_rad=start.heading_rad + 2.0))
    run = organised_grid.navigate_to_image(robot, renderer.render(goal_pose), max_steps=60)
    assert run.goal.place == goal
    assert run.reached
    assert distance_m(robot.pose, goal_pose) < 0.3, "stopped more than a grid spacing away"
    assert 0 < len(run.steps) <= 60 and run.path_length_m > 0.5
    assert run.steps[0].match is not None


def test_the_navigation_config_governs_the_run(organised_grid):
    world = omninav.World(WORLD, width_px=WIDTH_PX, height_px=HEIGHT_PX, rays_per_pixel=1)
    renderer = omninav.Renderer(world)
    places = organised_grid.places()
    start, goal_pose = places[0].truth, places[-1].truth
    config = omninav.NavigationConfig.load()
    config.navigator.max_steps = 3  # 1.5 m to go in steps of navigator.step_m: too few
    robot = RenderedRobot(renderer, start)
    run = organised_grid.navigate_to_image(robot, renderer.render(goal_pose), config=config)
    assert not run.reached and len(run.steps) <= 3
    assert run.path_length_m <= 3 * config.navigator.step_m + 1e-9


class NaNRobot(RenderedRobot):
    """A robot whose odometry breaks: move() says it drove NaN metres."""

    def move(self, turn_rad, distance_m):
        super().move(turn_rad, distance_m)
        return float("nan")


def test_a_robot_that_reports_nan_metres_driven_is_refused(organised_grid):
    world = omninav.World(WORLD, width_px=WIDTH_PX, height_px=HEIGHT_PX, rays_per_pixel=1)
    renderer = omninav.Renderer(world)
    places = organised_grid.places()
    start = places[0].truth
    robot = NaNRobot(renderer, omninav.CameraPose(start.x_m, start.y_m, start.z_m,
                                                  heading_rad=start.heading_rad + 2.0))
    with pytest.raises(omninav.InputError, match=r"robot\.move\(\) returned nan"):
        organised_grid.navigate_to_image(robot, renderer.render(places[-1].truth), max_steps=60)


def test_a_value_out_of_range_set_from_python_is_refused_as_in_navigation_yaml(organised_grid):
    goal = len(organised_grid.places()) - 1
    config = omninav.NavigationConfig.load()
    config.links.revisit_ratio = 0.0  # navigation.yaml allows 0.1..100
    with pytest.raises(omninav.UsageError, match="links.revisit_ratio"):
        organised_grid.plan_route(goal, config=config)


def test_a_live_session_recognises_places_and_agrees_with_the_compass(organised_grid, tmp_path):
    map_file = tmp_path / "grid.vmem"
    organised_grid.save(map_file)
    world = omninav.World(WORLD, width_px=WIDTH_PX, height_px=HEIGHT_PX, rays_per_pixel=1)
    renderer = omninav.Renderer(world)
    places = organised_grid.places()
    first = places[0].truth
    session = omninav.LiveSession(map_file)
    assert session.no_belief_reason is None
    compass = omninav.Compass()
    # Forwards along the grid's first row, 5 cm a frame, odometry from the renderer's poses.
    for index in range(25):
        pose = omninav.CameraPose(first.x_m + 0.05 * index, first.y_m, first.z_m,
                                  heading_rad=first.heading_rad)
        image = renderer.render(pose)
        output = session.push(image, 0.1 * index, pose.on_floor())
        expected = compass.push(image, truth_heading_rad=first.heading_rad)
        assert output.frame == index
        assert output.compass.heading_rad == expected.heading_rad  # the offline compass's
        # From the fourth frame on (the belief starts uniform), confident and next to the robot.
        if index >= 3:
            assert not output.place.lost, output.place
            assert distance_m(places[output.place.place].truth, pose) < 1.5 * 0.3, output.place
    # A frame stamped before the last is skipped and counted.
    assert session.push(image, 0.0) is None
    assert session.last_skip[0] == "stamp not increasing"
    assert session.skipped["stamp not increasing"] == 1


@pytest.mark.parametrize("with_odometry", [True, False])
def test_a_live_sessions_commands_drive_a_rendered_robot_to_the_goal(organised_grid, tmp_path,
                                                                      with_odometry):
    # The closed loop of a robot of the caller's: push the frame it sees, carry out what is left
    # of the command, push the next frame. With odometry (the renderer's poses) the session
    # follows each command by it; without, each frame is the navigator's next view.
    map_file = tmp_path / "grid.vmem"
    organised_grid.save(map_file)
    world = omninav.World(WORLD, width_px=WIDTH_PX, height_px=HEIGHT_PX, rays_per_pixel=1)
    renderer = omninav.Renderer(world)
    places = organised_grid.places()
    goal_pose, start = places[-1].truth, places[0].truth
    robot = RenderedRobot(renderer, omninav.CameraPose(start.x_m, start.y_m, start.z_m,
                                                       heading_rad=start.heading_rad + 2.0))
    session = omninav.LiveSession(map_file)
    assert session.navigate_to(renderer.render(goal_pose)).place == len(places) - 1
    assert session.navigating
    states = []
    for index in range(400):
        odometry = robot.pose.on_floor() if with_odometry else None
        command = session.push(robot.view(index), 0.1 * index, odometry).command
        states.append(command.state)
        if command.state != "driving":
            break
        robot.move(command.turn_rad, command.distance_m)
    assert states[-1] == "reached", states[-1]
    assert distance_m(robot.pose, goal_pose) < 0.3, "stopped more than a grid spacing away"
    assert command.turn_rad == 0 and command.distance_m == 0  # stand still
    session.stop_navigating()
    assert session.push(robot.view(400), 100.0).command is None

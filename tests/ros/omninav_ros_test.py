"""The ROS node for real (docs/ros.md): a bag of the rendered route (tests/io/bags, written by
Debian's python3-rosbag), a map explored from it by `omninav explore --all-frames` and organised,
then a rosmaster on a free port, omninav_ros on the map with odometry by its launch file
(roslaunch), and `rosbag play` of the bag, fast. Checks what the node publishes against the offline command and the construction:

  - /omninav/heading: one message per frame, stamped as the frame, its yaw and variance those
    of `omninav compass --pose-topic /odom` (the same compass on the same frames, started at the
    same heading) to the CSV's precision;
  - a second node without a map on the same bag's frames as PNG (sensor_msgs/CompressedImage,
    `compressed`), played together with the first bag: its headings are those of `omninav
    compass` on that bag (started at 0 without odometry);
  - /omninav/place: every frame recognises the place made from its own image (every frame of the
    route is a place of the map: the truth by construction), with a confidence in (0, 1];
  - bad input after the play (an image in an unknown encoding, one of another size) is skipped
    and counted, and the node goes on: no output for them, the services still answer, and the
    node's last line counts them;
  - the services: exploring during the play adds places, save_map writes them to the map file;
  - navigating: a bag of a robot in the route's world driven from the route's first pose to
    its last frame by the Python module's LiveSession, each command's velocity (docs/ros.md:
    the turn at max_angular_speed, then the drive at max_linear_speed) carried out for a frame
    period, 10 frames/s; it reaches the goal by the renderer's poses. A third node on that bag,
    told to navigate to the same goal image (~goal_image, ~navigate before the play), publishes
    one cmd_vel Twist and one ~navigation per frame equal to the library's, zero from the goal
    on, and a zero Twist on ~stop_navigating; a node without odometry refuses ~navigate.

  /usr/bin/python3 omninav_ros_test.py OMNINAV PACKAGE_PATH LAUNCH_FILE BAG_WRITERS_DIR MODULE_DIR

PACKAGE_PATH holds the package omninav (the build's share/), MODULE_DIR the Python module of the
same build. Exits 77 (CTest's skip) with a message when rosmaster, roslaunch, rosbag, rospy or
the module are missing."""

import csv
import math
import os
import shutil
import signal
import socket
import sqlite3
import subprocess
import sys
import tempfile
import time

SKIP = 77
FRAMES = 9  # the route's (tests/io/bags/route)
MAX_LINEAR_M_S, MAX_ANGULAR_RAD_S = 0.3, 0.7  # the navigator node's top speeds, not the defaults
NAVIGATION_PERIOD_S = 0.1  # the navigation bag's frame period
NAVIGATION_FRAMES = 400  # at most


def free_port():
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def wait_for(what, condition, seconds):
    deadline = time.monotonic() + seconds
    while not condition():
        if time.monotonic() > deadline:
            raise TimeoutError("timed out after %g s waiting for %s" % (seconds, what))
        time.sleep(0.05)


def stop(process):
    """Ctrl-C, as a user stops a node (the node logs its counts then); its whole process group
    killed when that does not end it in 5 s, or leaves anything behind (roslaunch's node)."""
    if process.poll() is None:
        process.send_signal(signal.SIGINT)
        try:
            process.wait(timeout=5)
        except subprocess.TimeoutExpired:
            pass
    try:
        os.killpg(process.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    process.wait()


def run(command, **kwargs):
    """Runs `command` in a process group of its own, all of which is killed after 30 s: `rosbag
    play` is a Python wrapper whose player (/usr/lib/rosbag/play) outlives a kill of it alone."""
    process = subprocess.Popen(command, start_new_session=True, **kwargs)
    try:
        status = process.wait(timeout=30)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        process.wait()
        raise
    if status != 0:
        raise subprocess.CalledProcessError(status, command)


def expect_headings(messages, offline):
    """The node's ~heading messages against `omninav compass`'s CSV rows, frame for frame."""
    assert len(messages) == len(offline), (len(messages), len(offline))
    for index, (message, row) in enumerate(zip(messages, offline)):
        assert abs(message.header.stamp.to_sec() - float(row["time_s"])) < 1e-4, index
        orientation = message.pose.pose.orientation
        yaw = 2.0 * math.atan2(orientation.z, orientation.w)
        expected = math.radians(float(row["heading_deg"]))
        error = math.atan2(math.sin(yaw - expected), math.cos(yaw - expected))
        assert abs(error) < 1e-9, (index, math.degrees(yaw), row["heading_deg"])
        sigma = math.radians(float(row["heading_sigma_deg"]))
        # heading_sigma_deg is printed with 4 decimals.
        assert abs(math.sqrt(message.pose.covariance[35]) - sigma) < math.radians(1e-4), index


def velocity(command):
    """docs/ros.md: what is left of the command's turn at max_angular_speed, else its drive at
    max_linear_speed; zero unless driving. (linear m/s, angular rad/s)"""
    if command.state == "driving" and command.turn_rad != 0:
        return 0.0, math.copysign(MAX_ANGULAR_RAD_S, command.turn_rad)
    if command.state == "driving" and command.distance_m > 0:
        return MAX_LINEAR_M_S, 0.0
    return 0.0, 0.0


def drive_closed_loop(map_file, route, bag_file):
    """A robot in the route's world (its database_metadata.yaml) starting at the route's first
    pose, driven to its last frame by the Python module's LiveSession: each frame rendered at the
    robot's pose, pushed with that pose as odometry, and the robot moved by the command's
    velocity for a frame period, as a base controller would move it on cmd_vel. Writes the
    frames and odometry on /nav/image_raw and /nav/odom of `bag_file`; returns every frame's
    LiveCommand. Checks against the renderer's poses that the robot reached the goal."""
    import omninav
    import rosbag
    import rospy
    from nav_msgs.msg import Odometry
    from sensor_msgs.msg import Image

    with open(os.path.join(route, "database_entries.csv"), newline="") as file:
        rows = [{key.strip(): value.strip() for key, value in row.items()}
                for row in csv.DictReader(file)]
    start, goal = (omninav.CameraPose(float(row["X [mm]"]) / 1000, float(row["Y [mm]"]) / 1000,
                                      float(row["Z [mm]"]) / 1000,
                                      heading_rad=math.radians(float(row["Heading [degrees]"])))
                   for row in (rows[0], rows[-1]))
    renderer = omninav.Renderer(omninav.World("room:seed=3", width_px=48, height_px=12))
    session = omninav.LiveSession(map_file)
    session.navigate_to(omninav.read_image(os.path.join(route, rows[-1]["Filename"])))
    pose, commands = start, []
    with rosbag.Bag(bag_file, "w") as bag:
        # Stamps from the route bag's (bob_route.py), so that the two bags play together.
        for index in range(NAVIGATION_FRAMES):
            stamp = rospy.Time(1_700_000_000 + index // 10, (index % 10) * 100_000_000)
            image = renderer.render(pose)
            commands.append(session.push(image, stamp.to_sec(), pose.on_floor()).command)
            message = Image(height=image.shape[0], width=image.shape[1], encoding="bgr8",
                            step=3 * image.shape[1], data=image.tobytes())
            message.header.stamp = stamp
            bag.write("/nav/image_raw", message, stamp)
            odometry = Odometry()
            odometry.header.stamp = stamp
            odometry.pose.pose.position.x, odometry.pose.pose.position.y = pose.x_m, pose.y_m
            odometry.pose.pose.orientation.z = math.sin(pose.heading_rad / 2)
            odometry.pose.pose.orientation.w = math.cos(pose.heading_rad / 2)
            bag.write("/nav/odom", odometry, stamp + rospy.Duration(0, 1000))
            if len(commands) > 2 and commands[-3].state != "driving":
                break  # two frames more after the end: the robot is still told to stand still
            linear, angular = velocity(commands[-1])
            heading = pose.heading_rad + angular * NAVIGATION_PERIOD_S
            pose = omninav.CameraPose(
                pose.x_m + linear * NAVIGATION_PERIOD_S * math.cos(heading),
                pose.y_m + linear * NAVIGATION_PERIOD_S * math.sin(heading), pose.z_m,
                heading_rad=heading)
    assert commands[-1].state == "reached", commands[-1]
    # The trials' criterion (navigation.yaml, trials.goal_radius_m).
    assert math.hypot(pose.x_m - goal.x_m, pose.y_m - goal.y_m) < 0.3, (pose, goal)
    # The frames between the navigator's views carried its commands out part by part.
    assert sum(command.new_step for command in commands) < len(commands) / 2, commands
    return commands


def expect_navigation(twists, navigation, commands):
    """The node's cmd_vel and ~navigation against the library's commands, frame for frame."""
    assert len(twists) == len(commands) == len(navigation), (len(twists), len(navigation))
    states = {"driving": 0, "reached": 1, "failed": 2}
    fields = navigation[0].layout.dim[0].label.split(",")
    for index, (twist, message, command) in enumerate(zip(twists, navigation, commands)):
        got = dict(zip(fields, message.data))
        assert got["state"] == states[command.state], (index, got, command)
        assert got["step"] == command.step and got["place"] == command.place, (index, got)
        assert abs(got["turn_rad"] - command.turn_rad) < 1e-6, (index, got, command)
        assert abs(got["distance_m"] - command.distance_m) < 1e-6, (index, got, command)
        assert (twist.linear.x, twist.angular.z) == velocity(command), (index, twist, command)
        assert (twist.linear.y, twist.linear.z, twist.angular.x, twist.angular.y) == (0, 0, 0, 0)


def main():
    omninav, package_path, launch_file, writers, module_dir = sys.argv[1:6]
    missing = [program for program in ("rosmaster", "roslaunch", "rosbag")
               if shutil.which(program) is None]
    try:
        import rospy  # noqa: F401
        from geometry_msgs.msg import PoseWithCovarianceStamped  # noqa: F401
        from std_srvs.srv import Trigger  # noqa: F401
    except ImportError as error:
        missing.append(str(error))
    sys.path.insert(0, module_dir)
    try:
        import omninav as _  # noqa: F401
    except ImportError as error:
        missing.append("the Python module omninav (OMNINAV_BUILD_PYTHON): " + str(error))
    if missing:
        print("SKIP: the ROS node test needs Debian's python3-rosmaster, python3-roslaunch, "
              "python3-rosbag, python3-rospy and python3-std-srvs, and the Python module; "
              "missing: " + ", ".join(missing))
        return SKIP
    import rospy
    from geometry_msgs.msg import PoseWithCovarianceStamped, Twist
    from nav_msgs.msg import Odometry
    from sensor_msgs.msg import Image
    from std_msgs.msg import Float64MultiArray, UInt32
    from std_srvs.srv import Trigger

    with tempfile.TemporaryDirectory(prefix="omninav_ros_test_") as scratch:
        bag = os.path.join(scratch, "route.bag")
        run([sys.executable, os.path.join(writers, "write_ros1_bag.py"),
             os.path.join(writers, "route"), bag, "--encoding", "bgr8", "--poses", "odometry"])
        map_file = os.path.join(scratch, "route.vmem")
        run([omninav, "-q", "explore", "--input", bag, "--pose-topic", "/odom", "--all-frames",
             "--out", map_file])
        # The route's frames are 15 cm apart (tests/io/bags/route: 0.3 m/s at 2 frames/s).
        run([omninav, "-q", "organise", map_file, "--step-m", "0.15"])
        compass_csv = os.path.join(scratch, "compass.csv")
        run([omninav, "-q", "compass", "--input", bag, "--pose-topic", "/odom", "--out",
             compass_csv])
        with open(compass_csv, newline="") as file:
            offline = list(csv.DictReader(file))
        assert len(offline) == FRAMES, offline
        # The navigator node's map: the route's, as the first node changes it by exploring.
        navigation_map = os.path.join(scratch, "navigation.vmem")
        shutil.copy(map_file, navigation_map)
        navigation_bag = os.path.join(scratch, "navigation.bag")
        commands = drive_closed_loop(navigation_map, os.path.join(writers, "route"),
                                     navigation_bag)
        png_bag = os.path.join(scratch, "route_png.bag")
        run([sys.executable, os.path.join(writers, "write_ros1_bag.py"),
             os.path.join(writers, "route"), png_bag, "--encoding", "png"])
        png_csv = os.path.join(scratch, "compass_png.csv")
        run([omninav, "-q", "compass", "--input", png_bag, "--out", png_csv])
        with open(png_csv, newline="") as file:
            offline_png = list(csv.DictReader(file))
        assert len(offline_png) == FRAMES, offline_png

        port = free_port()
        environment = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d" % port,
                           ROS_HOSTNAME="127.0.0.1", ROS_HOME=scratch,
                           ROS_PACKAGE_PATH=package_path,
                           ROS_LOG_DIR=os.path.join(scratch, "log"))
        os.environ.update(environment)
        processes = []
        logs = {}

        def start(name, command):
            logs[name] = open(os.path.join(scratch, name + ".log"), "w+")
            processes.append(subprocess.Popen(command, env=environment, stdout=logs[name],
                                              stderr=subprocess.STDOUT, start_new_session=True))
            return processes[-1]

        try:
            start("rosmaster", ["rosmaster", "--core", "-p", str(port)])
            import rosgraph
            wait_for("the rosmaster", lambda: rosgraph.Master("/test").is_online(), 15)
            omninav_ros = start("omninav_ros", [
                "roslaunch", launch_file, "map:=" + map_file, "use_odometry:=true"])
            start("omninav_compressed", [
                os.path.join(package_path, "omninav", "omninav_ros"), "__name:=compressed",
                "_compressed:=true", "image:=/camera/image_raw"])
            start("navigator", [
                os.path.join(package_path, "omninav", "omninav_ros"), "__name:=navigator",
                "_map:=" + navigation_map, "_use_odometry:=true",
                "_goal_image:=" + os.path.join(writers, "route", "image_%05d.png" % (FRAMES - 1)),
                "_max_linear_speed:=%g" % MAX_LINEAR_M_S,
                "_max_angular_speed:=%g" % MAX_ANGULAR_RAD_S,
                "image:=/nav/image_raw", "odom:=/nav/odom", "cmd_vel:=/nav/cmd_vel"])
            rospy.init_node("omninav_ros_test", disable_signals=True)
            headings, places, new_places, compressed = [], [], [], []
            rospy.Subscriber("/compressed/heading", PoseWithCovarianceStamped, compressed.append)
            rospy.Subscriber("/omninav/heading", PoseWithCovarianceStamped, headings.append)
            rospy.Subscriber("/omninav/place", Float64MultiArray, places.append)
            rospy.Subscriber("/omninav/new_place", UInt32, new_places.append)
            twists, navigation = [], []
            rospy.Subscriber("/nav/cmd_vel", Twist, twists.append)
            rospy.Subscriber("/navigator/navigation", Float64MultiArray, navigation.append)
            rospy.wait_for_service("/omninav/start_exploring", timeout=20)
            rospy.wait_for_service("/compressed/start_exploring", timeout=20)
            rospy.wait_for_service("/navigator/navigate", timeout=20)
            assert omninav_ros.poll() is None, "omninav_ros ended"
            response = rospy.ServiceProxy("/omninav/start_exploring", Trigger)()
            assert response.success, response.message
            response = rospy.ServiceProxy("/navigator/navigate", Trigger)()
            assert response.success, response.message
            # Without odometry the node refuses to navigate (docs/ros.md).
            response = rospy.ServiceProxy("/compressed/navigate", Trigger)()
            assert not response.success and "odometry" in response.message, response.message
            # At five times the recorded rate: the outputs do not depend on it.
            run(["rosbag", "play", "-q", "--wait-for-subscribers", "-r", "5", bag, png_bag,
                 navigation_bag], env=environment, stdout=subprocess.DEVNULL)
            wait_for("%d headings, places and commands" % FRAMES,
                     lambda: len(headings) >= FRAMES and len(places) >= FRAMES and
                     len(compressed) >= FRAMES and len(twists) >= len(commands), 20)
            response = rospy.ServiceProxy("/navigator/stop_navigating", Trigger)()
            assert response.success, response.message
            # Bad input after the bag's last frame: an unknown encoding, then a smaller image,
            # which the odometry after it lets through to the session.
            last = rospy.Time.from_sec(float(offline[-1]["time_s"]))
            images = rospy.Publisher("/camera/image_raw", Image, queue_size=10)
            odometry = rospy.Publisher("/odom", Odometry, queue_size=10)
            wait_for("the node's subscriptions", lambda: images.get_num_connections() > 0 and
                     odometry.get_num_connections() > 0, 10)
            for encoding, width in (("unknown_encoding", 48), ("bgr8", 24)):
                image = Image(height=12, width=width, encoding=encoding, step=3 * width,
                              data=bytes(3 * width * 12))
                image.header.stamp = last + rospy.Duration(1)
                images.publish(image)
            pose = Odometry()
            pose.header.stamp = last + rospy.Duration(2)
            pose.pose.pose.orientation.w = 1.0
            odometry.publish(pose)
            for service in ("/omninav/stop_exploring", "/omninav/save_map"):
                response = rospy.ServiceProxy(service, Trigger)()
                assert response.success, service + ": " + response.message
            time.sleep(0.5)  # any late message would show as one too many
        finally:
            for process in reversed(processes):
                stop(process)
            rospy.signal_shutdown("done")
            output = {}
            for name, log in logs.items():
                log.seek(0)
                output[name] = log.read()
                print("--- %s\n%s" % (name, output[name]))

        summary = ("omninav: skipped 1 frames the session refused, 1 that could not be decoded, "
                   "0 that failed")
        assert summary in output["omninav_ros"], "no line: " + summary

        assert len(places) == FRAMES, len(places)
        # One Twist per frame, then the stop's zero Twist.
        assert len(twists) == len(commands) + 1, (len(twists), len(commands))
        assert (twists[-1].linear.x, twists[-1].angular.z) == (0, 0)
        expect_navigation(twists[:-1], navigation, commands)
        expect_headings(headings, offline)
        expect_headings(compressed, offline_png)
        fields = places[0].layout.dim[0].label.split(",")
        for index, message in enumerate(places):
            place = dict(zip(fields, message.data))
            assert place["place"] == index, (index, place)
            assert 0.0 < place["confidence"] <= 1.0, (index, place)
            assert place["similarity"] == 1000.0, (index, place)  # its own image
        # Exploring during the play: the route's first frame at least became a place, saved.
        assert len(new_places) >= 1, new_places
        with sqlite3.connect(map_file) as database:
            saved = database.execute("SELECT COUNT(*) FROM places").fetchone()[0]
        assert saved == FRAMES + len(new_places), (saved, len(new_places))
    print("omninav_ros: %d frames raw and compressed, headings as `omninav compass`, places as "
          "made, %d places explored and saved; %d frames navigated to the goal, cmd_vel as the "
          "library's" % (FRAMES, len(new_places), len(commands)))
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Writes a ROS 1 bag of the BoB database `route` with Debian's python3-rosbag: an image
independent of omninav's C++ reader, for the io tests (run by them at test time).

  /usr/bin/python3 write_ros1_bag.py DATABASE OUT.bag [--encoding rgb8|bgr8|rgba8|bgra8|mono8|
      mono16|bayer_rggb8|png] [--poses odometry|pose_stamped] [--second-camera]
      [--truncate-bytes N] [--compression none|bz2|lz4] [--chunk-bytes N]
      [--first-pose X,Y,Z,QX,QY,QZ,QW] [--png-file FILE] [--overlong-message N]

Images on /camera/image_raw (sensor_msgs/Image) or, with --encoding png,
/camera/image_raw/compressed (sensor_msgs/CompressedImage, the PNG files' bytes); poses on /odom
(nav_msgs/Odometry) or /pose (geometry_msgs/PoseStamped), stamped as the images and recorded
just after them. --second-camera adds /camera2/image_raw; --truncate-bytes cuts the file;
--first-pose replaces the first pose (damage: 1e300, nan, a quaternion of zeros); --png-file
gives every CompressedImage that file's bytes (a decompression bomb, a broken PNG);
--overlong-message makes the N-th message record written declare 256 MB more data than it holds,
inside its chunk and before the chunk is compressed (damage that only the decompressed chunk
shows, its sizes and index otherwise consistent)."""

import os

import rosbag
import rosbag.bag
import rospy
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import CompressedImage, Image

from bob_route import argument_parser, encode, frames


def overlong_message(damaged):
    """Makes the message record written `damaged`-th declare 256 MB more data than follows it."""
    write = rosbag.Bag._write_message_data_record
    written = [0]

    def write_damaged(bag, connection_id, t, serialized_bytes):
        if written[0] == damaged:
            header = {"op": rosbag.bag._pack_uint8(rosbag.bag._OP_MSG_DATA),
                      "conn": rosbag.bag._pack_uint32(connection_id),
                      "time": rosbag.bag._pack_time(t)}
            rosbag.bag._write_header(bag._output_file, header)
            bag._output_file.write(rosbag.bag._pack_uint32(len(serialized_bytes) + (256 << 20)))
            bag._output_file.write(serialized_bytes)
        else:
            write(bag, connection_id, t, serialized_bytes)
        written[0] += 1

    rosbag.Bag._write_message_data_record = write_damaged


def main():
    parser = argument_parser()
    parser.add_argument("--compression", choices=["none", "bz2", "lz4"], default="none")
    parser.add_argument("--chunk-bytes", type=int, default=768 * 1024)
    parser.add_argument("--first-pose")
    parser.add_argument("--png-file")
    parser.add_argument("--overlong-message", type=int)
    args = parser.parse_args()
    png = open(args.png_file, "rb").read() if args.png_file else None
    if args.overlong_message is not None:
        overlong_message(args.overlong_message)

    with rosbag.Bag(args.out, "w", compression=args.compression,
                    chunk_threshold=args.chunk_bytes) as bag:
        for index, frame in enumerate(frames(args.database)):
            stamp = rospy.Time(frame["sec"], frame["nanosec"])
            if args.encoding == "png":
                image = CompressedImage(format="png", data=png or frame["png"])
                topic = "/camera/image_raw/compressed"
            else:
                step, data = encode(frame["rows"], args.encoding)
                image = Image(height=frame["height"], width=frame["width"],
                              encoding=args.encoding, is_bigendian=0, step=step, data=data)
                topic = "/camera/image_raw"
            image.header.stamp = stamp
            image.header.seq = index
            image.header.frame_id = "camera"
            bag.write(topic, image, stamp)
            if args.second_camera:
                step, data = encode(frame["rows"], "bgr8")
                second = Image(height=frame["height"], width=frame["width"], encoding="bgr8",
                               step=step, data=data)
                second.header.stamp = stamp
                bag.write("/camera2/image_raw", second, stamp)
            if args.poses:
                pose = Odometry() if args.poses == "odometry" else PoseStamped()
                pose.header.stamp = stamp
                pose.header.frame_id = "odom"
                target = pose.pose.pose if args.poses == "odometry" else pose.pose
                target.position.x, target.position.y, target.position.z = frame["position"]
                (target.orientation.x, target.orientation.y, target.orientation.z,
                 target.orientation.w) = frame["quaternion"]
                if args.first_pose and index == 0:
                    values = [float(v) for v in args.first_pose.split(",")]
                    target.position.x, target.position.y, target.position.z = values[:3]
                    (target.orientation.x, target.orientation.y, target.orientation.z,
                     target.orientation.w) = values[3:]
                bag.write("/odom" if args.poses == "odometry" else "/pose", pose,
                          stamp + rospy.Duration(0, 1000))
    if args.truncate_bytes:
        os.truncate(args.out, args.truncate_bytes)


if __name__ == "__main__":
    main()

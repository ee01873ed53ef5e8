"""Writes a ROS 2 SQLite bag (rosbag2's .db3 storage, with its metadata.yaml) of the BoB
database `route`, with Python's sqlite3 and the small CDR writer below: an implementation
independent of omninav's C++ reader, for the io tests (run by them at test time).

  python3 write_ros2_db3.py DATABASE OUT_FOLDER [--encoding rgb8|bgr8|rgba8|bgra8|mono8|mono16|
      png] [--poses odometry|pose_stamped] [--second-camera] [--big-endian] [--truncate-bytes N]

Writes OUT_FOLDER/OUT_FOLDER.db3 and OUT_FOLDER/metadata.yaml. Topics as write_ros1_bag.py's,
with ROS 2's type names (sensor_msgs/msg/Image ...)."""

import os
import sqlite3
import struct
from pathlib import Path

from bob_route import argument_parser, encode, frames


class Cdr:
    """XCDR1 as ROS 2 serialises: a 4-byte encapsulation header (0, 1 little-endian; 0, 0 big),
    then primitives aligned to their size from the end of the header."""

    def __init__(self, big_endian=False):
        self.order = ">" if big_endian else "<"
        self.data = bytearray(b"\x00\x00\x00\x00" if big_endian else b"\x00\x01\x00\x00")

    def _put(self, code, size, value):
        while (len(self.data) - 4) % size:
            self.data.append(0)
        self.data += struct.pack(self.order + code, value)

    def u8(self, value):
        self._put("B", 1, value)

    def u32(self, value):
        self._put("I", 4, value)

    def i32(self, value):
        self._put("i", 4, value)

    def f64(self, value):
        self._put("d", 8, value)

    def string(self, text):
        encoded = text.encode() + b"\x00"
        self.u32(len(encoded))
        self.data += encoded

    def octets(self, data):
        self.u32(len(data))
        self.data += data

    def header(self, frame, frame_id):
        self.i32(frame["sec"])
        self.u32(frame["nanosec"])
        self.string(frame_id)

    def pose(self, frame):
        for value in frame["position"] + frame["quaternion"]:
            self.f64(value)


def image_message(frame, encoding, big_endian):
    cdr = Cdr(big_endian)
    cdr.header(frame, "camera")
    if encoding == "png":
        cdr.string("png")
        cdr.octets(frame["png"])
        return bytes(cdr.data)
    step, data = encode(frame["rows"], encoding)
    cdr.u32(frame["height"])
    cdr.u32(frame["width"])
    cdr.string(encoding)
    cdr.u8(0)  # is_bigendian: the pixels' order, little-endian as encode() writes them
    cdr.u32(step)
    cdr.octets(data)
    return bytes(cdr.data)


def pose_message(frame, kind, big_endian):
    cdr = Cdr(big_endian)
    cdr.header(frame, "odom")
    if kind == "odometry":
        cdr.string("base_link")
        cdr.pose(frame)
        for _ in range(36):
            cdr.f64(0.0)  # pose covariance
        for _ in range(6 + 36):
            cdr.f64(0.0)  # twist and its covariance
    else:
        cdr.pose(frame)
    return bytes(cdr.data)


def main():
    parser = argument_parser()
    parser.add_argument("--big-endian", action="store_true")
    args = parser.parse_args()

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    storage = out / (out.name + ".db3")
    db = sqlite3.connect(storage)
    db.executescript("""
        CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);
        CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL,
                              metadata TEXT NOT NULL);
        CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,
                            serialization_format TEXT NOT NULL,
                            offered_qos_profiles TEXT NOT NULL);
        CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL,
                              timestamp INTEGER NOT NULL, data BLOB NOT NULL);
        CREATE INDEX timestamp_idx ON messages (timestamp ASC);
        INSERT INTO schema VALUES (3, 'humble');
    """)
    image_topic = ("/camera/image_raw/compressed", "sensor_msgs/msg/CompressedImage") \
        if args.encoding == "png" else ("/camera/image_raw", "sensor_msgs/msg/Image")
    topics = [image_topic]
    if args.second_camera:
        topics.append(("/camera2/image_raw", "sensor_msgs/msg/Image"))
    if args.poses == "odometry":
        topics.append(("/odom", "nav_msgs/msg/Odometry"))
    elif args.poses == "pose_stamped":
        topics.append(("/pose", "geometry_msgs/msg/PoseStamped"))
    for number, (name, kind) in enumerate(topics, start=1):
        db.execute("INSERT INTO topics VALUES (?, ?, ?, 'cdr', '')", (number, name, kind))
    count = 0
    for frame in frames(args.database):
        stamp_ns = frame["sec"] * 1_000_000_000 + frame["nanosec"]
        rows = [(1, image_message(frame, args.encoding, args.big_endian))]
        if args.second_camera:
            rows.append((2, image_message(frame, "bgr8", args.big_endian)))
        if args.poses:
            rows.append((len(topics), pose_message(frame, args.poses, args.big_endian)))
        for topic_id, data in rows:
            db.execute("INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)",
                       (topic_id, stamp_ns, data))
            count += 1
    db.commit()
    db.close()
    (out / "metadata.yaml").write_text(
        "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
        f"  relative_file_paths:\n    - {storage.name}\n  message_count: {count}\n")
    if args.truncate_bytes:
        os.truncate(storage, args.truncate_bytes)


if __name__ == "__main__":
    main()

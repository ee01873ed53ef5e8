"""A small BoB robotics image database (tests/io/bags/route, rendered by `omninav render`) as
the messages of a robot recording, for the bag writers of the io tests. Standard library only,
so that the writers need nothing beyond Debian's python3-rosbag: PNG decoding with zlib, the
grey levels by BT.601's weights in 14-bit integers."""

import argparse
import csv
import math
import struct
import zlib
from pathlib import Path

# Stamps start here (2023-11-14), so that a reader that dropped the seconds would be caught.
STAMP_BASE_S = 1_700_000_000


def png_rgb(data):
    """(width, height, rows of RGB bytes) of an 8-bit RGB, non-interlaced PNG."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    position, idat = 8, b""
    while position < len(data):
        length, kind = struct.unpack(">I4s", data[position:position + 8])
        body = data[position + 8:position + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour == 2 and interlace == 0, "8-bit RGB PNGs only"
        elif kind == b"IDAT":
            idat += body
        position += 12 + length
    raw = zlib.decompress(idat)
    stride = 3 * width
    rows, previous = [], bytearray(stride)
    for row in range(height):
        start = row * (stride + 1)
        kind, line = raw[start], bytearray(raw[start + 1:start + 1 + stride])
        for i in range(stride):
            left = line[i - 3] if i >= 3 else 0
            up = previous[i]
            up_left = previous[i - 3] if i >= 3 else 0
            if kind == 1:
                line[i] = (line[i] + left) & 0xFF
            elif kind == 2:
                line[i] = (line[i] + up) & 0xFF
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 0xFF
            elif kind == 4:
                p = left + up - up_left
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - up_left)
                predictor = left if pa <= pb and pa <= pc else (up if pb <= pc else up_left)
                line[i] = (line[i] + predictor) & 0xFF
        rows.append(bytes(line))
        previous = line
    return width, height, rows


def grey(rgb_row):
    """BT.601 luma in 14-bit integers: (R*4899 + G*9617 + B*1868 + 8192) >> 14."""
    return bytes((rgb_row[i] * 4899 + rgb_row[i + 1] * 9617 + rgb_row[i + 2] * 1868 + 8192) >> 14
                 for i in range(0, len(rgb_row), 3))


def encode(rows, encoding):
    """(step, data) of the image in a sensor_msgs/Image encoding (little-endian for 16 bits)."""
    if encoding == "rgb8":
        lines = rows
    elif encoding == "bgr8":
        lines = [bytes(b for i in range(0, len(r), 3) for b in (r[i + 2], r[i + 1], r[i]))
                 for r in rows]
    elif encoding == "rgba8":
        lines = [bytes(b for i in range(0, len(r), 3) for b in (r[i], r[i + 1], r[i + 2], 255))
                 for r in rows]
    elif encoding == "bgra8":
        lines = [bytes(b for i in range(0, len(r), 3) for b in (r[i + 2], r[i + 1], r[i], 255))
                 for r in rows]
    elif encoding == "mono8":
        lines = [grey(r) for r in rows]
    elif encoding == "bayer_rggb8":
        # R G R G ... on even rows, G B G B ... on odd rows.
        lines = [bytes(r[3 * c + (0 if row % 2 == 0 and c % 2 == 0 else
                                  2 if row % 2 == 1 and c % 2 == 1 else 1)]
                       for c in range(len(r) // 3)) for row, r in enumerate(rows)]
    elif encoding == "mono16":
        lines = [b"".join(struct.pack("<H", 257 * g) for g in grey(r)) for r in rows]
    else:
        raise ValueError("unknown encoding " + encoding)
    return len(lines[0]), b"".join(lines)


def yaw_quaternion(heading_deg):
    """(x, y, z, w) of a rotation by `heading_deg` about +z."""
    half = math.radians(heading_deg) / 2.0
    return (0.0, 0.0, math.sin(half), math.cos(half))


def frames(database):
    """Each entry of the database: dict of stamp (sec, nanosec), position (m), quaternion,
    width, height, png (the file's bytes), rows (RGB)."""
    database = Path(database)
    with open(database / "database_entries.csv", newline="") as table:
        reader = csv.reader(table, skipinitialspace=True)
        header = next(reader)
        column = {name: header.index(name) for name in header}
        for row in reader:
            png = (database / row[column["Filename"]]).read_bytes()
            width, height, rows = png_rgb(png)
            milliseconds = int(row[column["Timestamp [ms]"]])
            yield {
                "sec": STAMP_BASE_S + milliseconds // 1000,
                "nanosec": (milliseconds % 1000) * 1_000_000,
                "position": tuple(float(row[column[c]]) / 1000.0
                                  for c in ("X [mm]", "Y [mm]", "Z [mm]")),
                "quaternion": yaw_quaternion(float(row[column["Heading [degrees]"]])),
                "width": width,
                "height": height,
                "png": png,
                "rows": rows,
            }


def argument_parser():
    """The arguments both Python writers take: DATABASE OUT, the image encoding (or png for
    sensor_msgs/CompressedImage), the pose message, a second camera, and a length to cut the
    written file to (a recording killed mid-write)."""
    parser = argparse.ArgumentParser()
    parser.add_argument("database")
    parser.add_argument("out")
    parser.add_argument("--encoding", default="rgb8")
    parser.add_argument("--poses", choices=["odometry", "pose_stamped"])
    parser.add_argument("--second-camera", action="store_true")
    parser.add_argument("--truncate-bytes", type=int)
    return parser

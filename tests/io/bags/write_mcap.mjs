// Writes the MCAP test files of tests/io/bags (route_*.mcap) from the BoB database `route` with
// the npm registry's MCAP writer (@mcap/core) and ROS 2 CDR serialiser
// (@foxglove/rosmsg2-serialization): an implementation independent of omninav's C++ readers.
// The files are committed, so that neither the tests nor CI need node or npm. Remade with:
//
//   mkdir -p /tmp/mcap-writer && cd /tmp/mcap-writer && npm init -y >/dev/null &&
//   npm install @mcap/core@2.2.2 @foxglove/rosmsg2-serialization@3.1.0 \
//     @foxglove/rosmsg-msgs-common@3.2.3 @foxglove/rosmsg@5.0.5 @foxglove/wasm-zstd@1.0.1 \
//     lz4js@0.2.0 &&
//   NODE_PATH=/tmp/mcap-writer/node_modules node <repo>/tests/io/bags/write_mcap.mjs <repo>/tests/io/bags
//
// route_raw.mcap   uncompressed chunks: sensor_msgs/msg/Image rgb8 on /camera/image_raw,
//                  nav_msgs/msg/Odometry on /odom
// route_zstd.mcap  zstd chunks: sensor_msgs/msg/CompressedImage (the PNG files) on
//                  /camera/image_raw/compressed, geometry_msgs/msg/PoseStamped on /pose
// route_lz4.mcap   lz4 chunks: Image mono16 on /camera/image_raw, Image bgr8 on
//                  /camera2/image_raw, Odometry on /odom
// Stamps are 1,700,000,000 s plus the database's Timestamp; poses are stamped as the images.

import { createRequire } from "node:module";
import fs from "node:fs";
import path from "node:path";
import zlib from "node:zlib";

const require = createRequire(path.join(process.env.NODE_PATH ?? process.cwd(), "x.js"));
const { McapWriter } = require("@mcap/core");
const { MessageWriter } = require("@foxglove/rosmsg2-serialization");
const { ros2jazzy } = require("@foxglove/rosmsg-msgs-common");
const { stringify } = require("@foxglove/rosmsg");
const zstd = require("@foxglove/wasm-zstd");
const lz4 = require("lz4js");

const STAMP_BASE_S = 1_700_000_000;

// (width, height, rows of RGB bytes) of an 8-bit RGB, non-interlaced PNG.
function pngRgb(data) {
  let position = 8;
  let width = 0;
  let height = 0;
  const idat = [];
  while (position < data.length) {
    const length = data.readUInt32BE(position);
    const kind = data.toString("latin1", position + 4, position + 8);
    const body = data.subarray(position + 8, position + 8 + length);
    if (kind === "IHDR") {
      width = body.readUInt32BE(0);
      height = body.readUInt32BE(4);
      if (body[8] !== 8 || body[9] !== 2 || body[12] !== 0) throw new Error("8-bit RGB PNGs only");
    } else if (kind === "IDAT") {
      idat.push(body);
    }
    position += 12 + length;
  }
  const raw = zlib.inflateSync(Buffer.concat(idat));
  const stride = 3 * width;
  const rows = [];
  let previous = new Uint8Array(stride);
  for (let row = 0; row < height; ++row) {
    const start = row * (stride + 1);
    const kind = raw[start];
    const line = Uint8Array.from(raw.subarray(start + 1, start + 1 + stride));
    for (let i = 0; i < stride; ++i) {
      const left = i >= 3 ? line[i - 3] : 0;
      const up = previous[i];
      const upLeft = i >= 3 ? previous[i - 3] : 0;
      let predictor = 0;
      if (kind === 1) predictor = left;
      else if (kind === 2) predictor = up;
      else if (kind === 3) predictor = Math.floor((left + up) / 2);
      else if (kind === 4) {
        const p = left + up - upLeft;
        const pa = Math.abs(p - left);
        const pb = Math.abs(p - up);
        const pc = Math.abs(p - upLeft);
        predictor = pa <= pb && pa <= pc ? left : pb <= pc ? up : upLeft;
      }
      line[i] = (line[i] + predictor) & 0xff;
    }
    rows.push(line);
    previous = line;
  }
  return { width, height, rows };
}

// BT.601 luma in 14-bit integers: (R*4899 + G*9617 + B*1868 + 8192) >> 14.
const grey = (r, g, b) => (r * 4899 + g * 9617 + b * 1868 + 8192) >> 14;

function encode(rows, encoding) {
  const out = [];
  for (const row of rows) {
    for (let i = 0; i < row.length; i += 3) {
      const [r, g, b] = [row[i], row[i + 1], row[i + 2]];
      if (encoding === "rgb8") out.push(r, g, b);
      else if (encoding === "bgr8") out.push(b, g, r);
      else if (encoding === "mono16") {
        const value = 257 * grey(r, g, b);
        out.push(value & 0xff, value >> 8);
      } else throw new Error(`unknown encoding ${encoding}`);
    }
  }
  return { step: out.length / rows.length, data: Uint8Array.from(out) };
}

function readRoute(database) {
  const lines = fs.readFileSync(path.join(database, "database_entries.csv"), "utf8").trim().split("\n");
  const header = lines[0].split(",").map((s) => s.trim());
  const column = (name) => header.indexOf(name);
  return lines.slice(1).map((line) => {
    const fields = line.split(",").map((s) => s.trim());
    const png = fs.readFileSync(path.join(database, fields[column("Filename")]));
    const milliseconds = Number(fields[column("Timestamp [ms]")]);
    const half = (Number(fields[column("Heading [degrees]")]) * Math.PI) / 180 / 2;
    return {
      stamp: { sec: STAMP_BASE_S + Math.floor(milliseconds / 1000), nanosec: (milliseconds % 1000) * 1e6 },
      position: ["X [mm]", "Y [mm]", "Z [mm]"].map((c) => Number(fields[column(c)]) / 1000),
      orientation: { x: 0, y: 0, z: Math.sin(half), w: Math.cos(half) },
      png,
      ...pngRgb(png),
    };
  });
}

// A ROS 2 type: its CDR writer and its ros2msg schema text (the definitions it uses).
function rosType(name) {
  const all = Object.entries(ros2jazzy).map(([n, d]) => ({ ...d, name: n }));
  const root = all.find((d) => d.name === name);
  const used = [];
  const visit = (definition) => {
    for (const field of definition.definitions) {
      if (field.isComplex && !used.some((d) => d.name === field.type)) {
        const child = all.find((d) => d.name === field.type);
        used.push(child);
        visit(child);
      }
    }
  };
  visit(root);
  const definitions = [{ ...root, name: undefined }, ...used];
  return {
    schemaName: name.replace("/", "/msg/"),
    writer: new MessageWriter(definitions),
    schema: new TextEncoder().encode(stringify(definitions)),
  };
}

class FileWritable {
  constructor(file) {
    this.fd = fs.openSync(file, "w");
    this.size = 0n;
  }
  position() {
    return this.size;
  }
  async write(buffer) {
    fs.writeSync(this.fd, buffer);
    this.size += BigInt(buffer.byteLength);
  }
  close() {
    fs.closeSync(this.fd);
  }
}

async function writeFile(file, compression, topics, route) {
  const writable = new FileWritable(file);
  const compressChunk =
    compression === "zstd"
      ? (data) => ({ compression: "zstd", compressedData: zstd.compress(data, 19) })
      : compression === "lz4"
        ? (data) => ({ compression: "lz4", compressedData: Uint8Array.from(lz4.compress(data)) })
        : undefined;
  // Small chunks, a message or two each, so that a truncated copy keeps most of its frames.
  const writer = new McapWriter({ writable, useChunks: true, chunkSize: 1024, compressChunk });
  await writer.start({ profile: "ros2", library: "omninav tests/io/bags/write_mcap.mjs" });
  const channels = [];
  for (const topic of topics) {
    const type = rosType(topic.type);
    const schemaId = await writer.registerSchema({
      name: type.schemaName,
      encoding: "ros2msg",
      data: type.schema,
    });
    const channelId = await writer.registerChannel({
      topic: topic.name,
      schemaId,
      messageEncoding: "cdr",
      metadata: new Map(),
    });
    channels.push({ ...topic, type, channelId });
  }
  let sequence = 0;
  for (const frame of route) {
    const time = BigInt(frame.stamp.sec) * 1_000_000_000n + BigInt(frame.stamp.nanosec);
    for (const channel of channels) {
      const header = { stamp: frame.stamp, frame_id: channel.frame ?? "camera" };
      const message = channel.make(frame, header);
      await writer.addMessage({
        channelId: channel.channelId,
        sequence: sequence++,
        logTime: time,
        publishTime: time,
        data: channel.type.writer.writeMessage(message),
      });
    }
  }
  await writer.end();
  writable.close();
}

const image = (encoding) => (frame, header) => {
  const { step, data } = encode(frame.rows, encoding);
  return { header, height: frame.height, width: frame.width, encoding, is_bigendian: 0, step, data };
};
const pose = (frame) => ({
  position: { x: frame.position[0], y: frame.position[1], z: frame.position[2] },
  orientation: frame.orientation,
});
const odometry = (frame, header) => ({
  header: { ...header, frame_id: "odom" },
  child_frame_id: "base_link",
  pose: { pose: pose(frame), covariance: new Array(36).fill(0) },
  twist: {
    twist: { linear: { x: 0, y: 0, z: 0 }, angular: { x: 0, y: 0, z: 0 } },
    covariance: new Array(36).fill(0),
  },
});

const folder = process.argv[2];
await zstd.isLoaded;
const route = readRoute(path.join(folder, "route"));
await writeFile(path.join(folder, "route_raw.mcap"), "none", [
  { name: "/camera/image_raw", type: "sensor_msgs/Image", make: image("rgb8") },
  { name: "/odom", type: "nav_msgs/Odometry", make: odometry },
], route);
await writeFile(path.join(folder, "route_zstd.mcap"), "zstd", [
  {
    name: "/camera/image_raw/compressed",
    type: "sensor_msgs/CompressedImage",
    make: (frame, header) => ({ header, format: "png", data: Uint8Array.from(frame.png) }),
  },
  { name: "/pose", type: "geometry_msgs/PoseStamped", make: (frame, header) => ({ header, pose: pose(frame) }) },
], route);
await writeFile(path.join(folder, "route_lz4.mcap"), "lz4", [
  { name: "/camera/image_raw", type: "sensor_msgs/Image", make: image("mono16") },
  { name: "/camera2/image_raw", type: "sensor_msgs/Image", make: image("bgr8") },
  { name: "/odom", type: "nav_msgs/Odometry", make: odometry },
], route);

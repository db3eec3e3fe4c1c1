// Writes the MCAP files ECO's recording readers are tested on, with foxglove's MCAP writer and
// ROS 2 CDR serialiser (not ECO's code): PointCloud2 as Ouster, Velodyne, Hesai, Robosense and
// Livox drivers lay them out, uncompressed, lz4 and zstd chunks, and files for the errors. Beside
// them, expected.json: what each cloud must decode to, computed here from the same numbers.
//
// usage: node write_mcap.mjs OUT_DIR

import { McapWriter } from "@mcap/core";
import { open } from "node:fs/promises";
import { writeFileSync, mkdirSync } from "node:fs";
import { COMPRESSORS, FileWritable, ODOMETRY, POINT, POINT_CLOUD2, POSE_STAMPED, TF_MESSAGE, cdrWriter } from "./ros2_messages.mjs";

const OUT = process.argv[2];
mkdirSync(OUT, { recursive: true });
const cloudWriter = cdrWriter(POINT_CLOUD2);
const pointWriter = cdrWriter(POINT);
const odometryWriter = cdrWriter(ODOMETRY);
const poseStampedWriter = cdrWriter(POSE_STAMPED);
const tfWriter = cdrWriter(TF_MESSAGE);

const T = { INT8: 1, UINT8: 2, INT16: 3, UINT16: 4, INT32: 5, UINT32: 6, FLOAT32: 7, FLOAT64: 8 };
const SIZE = { 1: 1, 2: 1, 3: 2, 4: 2, 5: 4, 6: 4, 7: 4, 8: 8 };
const STAMP0 = 1700000000; // s
const PERIOD_NS = 100000000;

// drivers' layouts: fields (name, type, offset), point_step, and how a point's time is written
const LAYOUTS = {
  ouster: {
    fields: [["x", T.FLOAT32, 0], ["y", T.FLOAT32, 4], ["z", T.FLOAT32, 8], ["intensity", T.FLOAT32, 16],
             ["t", T.UINT32, 20], ["reflectivity", T.UINT16, 24], ["ring", T.UINT16, 26]],
    step: 48, time: "t", unit: "ns", absolute: false, intensity: "intensity",
  },
  velodyne: {  // time at an odd offset: fields need not be aligned
    fields: [["x", T.FLOAT32, 0], ["y", T.FLOAT32, 4], ["z", T.FLOAT32, 8], ["intensity", T.FLOAT32, 12],
             ["ring", T.UINT16, 16], ["time", T.FLOAT32, 18]],
    step: 22, time: "time", unit: "s", absolute: false, intensity: "intensity",
  },
  hesai: {
    fields: [["x", T.FLOAT32, 0], ["y", T.FLOAT32, 4], ["z", T.FLOAT32, 8], ["intensity", T.FLOAT32, 12],
             ["timestamp", T.FLOAT64, 16], ["ring", T.UINT16, 24]],
    step: 26, time: "timestamp", unit: "s", absolute: true, intensity: "intensity",
  },
  robosense: {  // coordinates as float64
    fields: [["x", T.FLOAT64, 0], ["y", T.FLOAT64, 8], ["z", T.FLOAT64, 16], ["intensity", T.UINT8, 24],
             ["ring", T.UINT16, 25], ["timestamp", T.FLOAT64, 27]],
    step: 35, time: "timestamp", unit: "s", absolute: true, intensity: "intensity",
  },
  livox: {
    fields: [["x", T.FLOAT32, 0], ["y", T.FLOAT32, 4], ["z", T.FLOAT32, 8], ["reflectivity", T.UINT8, 12],
             ["tag", T.UINT8, 13], ["line", T.UINT8, 14], ["offset_time", T.UINT32, 15]],
    step: 19, time: "offset_time", unit: "ns", absolute: false, intensity: "reflectivity",
  },
  plain: {  // no time, no intensity
    fields: [["x", T.FLOAT32, 0], ["y", T.FLOAT32, 4], ["z", T.FLOAT32, 8]],
    step: 12, time: null, intensity: null,
  },
};

function put(view, type, offset, value) {
  switch (type) {
    case T.INT8: return view.setInt8(offset, value);
    case T.UINT8: return view.setUint8(offset, value);
    case T.INT16: return view.setInt16(offset, value, true);
    case T.UINT16: return view.setUint16(offset, value, true);
    case T.INT32: return view.setInt32(offset, value, true);
    case T.UINT32: return view.setUint32(offset, value, true);
    case T.FLOAT32: return view.setFloat32(offset, value, true);
    case T.FLOAT64: return view.setFloat64(offset, value, true);
  }
}

function get(view, type, offset) {
  switch (type) {
    case T.INT8: return view.getInt8(offset);
    case T.UINT8: return view.getUint8(offset);
    case T.INT16: return view.getInt16(offset, true);
    case T.UINT16: return view.getUint16(offset, true);
    case T.INT32: return view.getInt32(offset, true);
    case T.UINT32: return view.getUint32(offset, true);
    case T.FLOAT32: return view.getFloat32(offset, true);
    case T.FLOAT64: return view.getFloat64(offset, true);
  }
}

// cloud k of a layout: `points` points (height rows), some not finite, some at the origin; its
// message and what ECO must decode of it (points in order, intensities, times after the stamp)
function cloud(layoutName, k, points, height = 1) {
  const layout = LAYOUTS[layoutName];
  const width = points / height;
  const data = new Uint8Array(points * layout.step);
  const view = new DataView(data.buffer);
  const field = Object.fromEntries(layout.fields.map(([name, type, offset]) => [name, { type, offset }]));
  const stampNs = BigInt(STAMP0) * 1000000000n + BigInt(k * PERIOD_NS);
  const expected = { stamp_ns: stampNs.toString(), points: [], intensities: [], times: [] };
  for (let i = 0; i < points; i++) {
    const at = i * layout.step;
    let xyz = [5 + 0.01 * i + k, ((i * 7) % 13) - 6 + 0.001 * k, (i % 5) * 0.3 - 0.6];
    if (i % 50 === 7) xyz = [NaN, 1, 2];
    if (i % 61 === 3) xyz = [0, 0, 0];
    ["x", "y", "z"].forEach((c, j) => put(view, field[c].type, at + field[c].offset, xyz[j]));
    for (const [name, type, offset] of layout.fields) {
      if (!["x", "y", "z"].includes(name)) put(view, type, at + offset, name === "ring" ? i % 32 : (i * 3) % 200);
    }
    const offsetS = (0.1 * i) / points;
    if (layout.time) {
      const f = field[layout.time];
      const value = layout.unit === "ns" ? Math.round(offsetS * 1e9) : layout.absolute ? STAMP0 + k * 0.1 + offsetS : offsetS;
      put(view, f.type, at + f.offset, value);
    }
    if (!xyz.every(Number.isFinite) || xyz.every((v) => v === 0)) continue;
    expected.points.push(["x", "y", "z"].map((c) => get(view, field[c].type, at + field[c].offset)));
    if (layout.intensity) expected.intensities.push(get(view, field[layout.intensity].type, at + field[layout.intensity].offset));
    if (layout.time) {
      const raw = get(view, field[layout.time].type, at + field[layout.time].offset);
      expected.times.push(layout.unit === "ns" ? raw * 1e-9 : layout.absolute ? raw - Number(stampNs) * 1e-9 : raw);
    }
  }
  const message = {
    header: { stamp: { sec: Number(stampNs / 1000000000n), nanosec: Number(stampNs % 1000000000n) }, frame_id: "lidar" },
    height, width,
    fields: layout.fields.map(([name, datatype, offset]) => ({ name, offset, datatype, count: 1 })),
    is_bigendian: false, point_step: layout.step, row_step: layout.step * width, data, is_dense: false,
  };
  return { bytes: cloudWriter.writeMessage(message), message, expected, stampNs };
}

// topics: [{ topic, layout, clouds, points, height }] and extra topics; returns the expected clouds
async function writeMcap(name, { topics, compression = "zstd", chunked = true, chunkSize = 64 * 1024, extra = [] }) {
  const handle = await open(`${OUT}/${name}`, "w");
  const writer = new McapWriter({ writable: new FileWritable(handle), useChunks: chunked, chunkSize,
                                  compressChunk: COMPRESSORS[compression] });
  await writer.start({ profile: "ros2", library: "eco-tests" });
  const cloudSchema = await writer.registerSchema({ name: "sensor_msgs/msg/PointCloud2", encoding: "ros2msg",
                                                     data: new TextEncoder().encode(POINT_CLOUD2) });
  const expected = {};
  const messages = [];
  for (const t of topics) {
    const channel = await writer.registerChannel({ topic: t.topic, schemaId: cloudSchema, messageEncoding: "cdr", metadata: new Map() });
    expected[t.topic] = { layout: t.layout, clouds: [] };
    for (let k = 0; k < t.clouds; k++) {
      const c = cloud(t.layout, k, t.points, t.height ?? 1);
      expected[t.topic].clouds.push(c.expected);
      messages.push({ channelId: channel, sequence: k, logTime: c.stampNs + 1000n, publishTime: c.stampNs, data: c.bytes });
    }
  }
  for (const e of extra.filter((x) => x.poses)) {
    // poses half a frame off the clouds': x = 10 m/s × t, a yaw of 0.5 rad/s × t (interpolated at a cloud's stamp)
    const isOdometry = e.type === "nav_msgs/msg/Odometry";
    const child = e.child ?? "lidar";
    const schema = await writer.registerSchema({ name: e.type, encoding: "ros2msg",
                                                 data: new TextEncoder().encode(isOdometry ? ODOMETRY : POSE_STAMPED) });
    const channel = await writer.registerChannel({ topic: e.topic, schemaId: schema, messageEncoding: "cdr", metadata: new Map() });
    for (let k = 0; k < e.count; k++) {
      const tNs = BigInt(STAMP0) * 1000000000n + BigInt(k * PERIOD_NS) - 50000000n;
      const t = Number(tNs - BigInt(STAMP0) * 1000000000n) * 1e-9;
      const header = { stamp: { sec: Number(tNs / 1000000000n), nanosec: Number(tNs % 1000000000n) }, frame_id: "odom" };
      const pose = { position: { x: 10 * t, y: 0, z: 0 }, orientation: { x: 0, y: 0, z: Math.sin(0.25 * t), w: Math.cos(0.25 * t) } };
      const data = isOdometry
        ? odometryWriter.writeMessage({ header, child_frame_id: child, pose: { pose, covariance: new Float64Array(36) },
                                        twist: { twist: { linear: { x: 0, y: 0, z: 0 }, angular: { x: 0, y: 0, z: 0 } },
                                                 covariance: new Float64Array(36) } })
        : poseStampedWriter.writeMessage({ header, pose });
      messages.push({ channelId: channel, sequence: k, logTime: tNs, publishTime: tNs, data });
    }
  }
  for (const e of extra.filter((x) => x.tf)) {
    // tf's tree (as recording_test.cpp expects it): map -> odom fixed at (0, 5, 0) on /tf at the
    // ends; odom -> base_link moving as the poses above, at 20 Hz; base_link -> lidar at (1, 0, 2)
    // turned 90 degrees, and base_link -> camera, on /tf_static
    const schema = await writer.registerSchema({ name: "tf2_msgs/msg/TFMessage", encoding: "ros2msg",
                                                 data: new TextEncoder().encode(TF_MESSAGE) });
    const dynamic = await writer.registerChannel({ topic: "/tf", schemaId: schema, messageEncoding: "cdr", metadata: new Map() });
    const fixed = await writer.registerChannel({ topic: "/tf_static", schemaId: schema, messageEncoding: "cdr", metadata: new Map() });
    const stamped = (tNs, parent, child, translation, yaw) => ({
      header: { stamp: { sec: Number(tNs / 1000000000n), nanosec: Number(tNs % 1000000000n) }, frame_id: parent },
      child_frame_id: child,
      transform: { translation: { x: translation[0], y: translation[1], z: translation[2] },
                   rotation: { x: 0, y: 0, z: Math.sin(yaw / 2), w: Math.cos(yaw / 2) } } });
    const t0 = BigInt(STAMP0) * 1000000000n;
    messages.push({ channelId: fixed, sequence: 0, logTime: t0 - 100000000n, publishTime: t0, data: tfWriter.writeMessage({
      transforms: [stamped(t0, "base_link", "lidar", [1, 0, 2], Math.PI / 2), stamped(t0, "base_link", "camera", [0.5, 0, 1], 0)] }) });
    for (let k = 0; k < 12; k++) {
      const tNs = t0 + BigInt(k) * 50000000n - 50000000n;
      const t = Number(tNs - t0) * 1e-9;
      const transforms = [stamped(tNs, "odom", "base_link", [10 * t, 0, 0], 0.5 * t)];
      if (k === 0 || k === 11) transforms.push(stamped(tNs, "map", "odom", [0, 5, 0], 0));
      messages.push({ channelId: dynamic, sequence: k, logTime: tNs, publishTime: tNs, data: tfWriter.writeMessage({ transforms }) });
    }
  }
  for (const e of extra.filter((x) => !x.poses && !x.tf)) {
    const schema = await writer.registerSchema({ name: e.type, encoding: "ros2msg", data: new TextEncoder().encode(POINT) });
    const channel = await writer.registerChannel({ topic: e.topic, schemaId: schema, messageEncoding: "cdr", metadata: new Map() });
    for (let k = 0; k < e.count; k++) {
      messages.push({ channelId: channel, sequence: k, logTime: BigInt(STAMP0) * 1000000000n + BigInt(k * PERIOD_NS) + 500n,
                      publishTime: 0n, data: pointWriter.writeMessage({ position: { x: k, y: 0, z: 0 } }) });
    }
  }
  messages.sort((a, b) => (a.logTime < b.logTime ? -1 : a.logTime > b.logTime ? 1 : 0));
  for (const m of messages) await writer.addMessage(m);
  await writer.end();
  await handle.close();
  return expected;
}

const expected = {};
for (const compression of ["none", "lz4", "zstd"]) {
  expected[`ouster_${compression}.mcap`] = await writeMcap(`ouster_${compression}.mcap`,
    { compression, topics: [{ topic: "/ouster/points", layout: "ouster", clouds: 5, points: 1024, height: 16 }] });
}
for (const layout of ["velodyne", "hesai", "robosense", "livox", "plain"]) {
  expected[`${layout}.mcap`] = await writeMcap(`${layout}.mcap`, { topics: [{ topic: `/${layout}/points`, layout, clouds: 4, points: 600 }] });
}
expected["unchunked.mcap"] = await writeMcap("unchunked.mcap", { chunked: false,
  topics: [{ topic: "/points", layout: "velodyne", clouds: 3, points: 300 }] });
expected["two_lidars.mcap"] = await writeMcap("two_lidars.mcap", {
  topics: [{ topic: "/front/points", layout: "ouster", clouds: 3, points: 256 },
           { topic: "/rear/points", layout: "livox", clouds: 2, points: 256 }],
  extra: [{ topic: "/odom", type: "geometry_msgs/msg/Point", count: 4 }] });
expected["no_clouds.mcap"] = await writeMcap("no_clouds.mcap", { topics: [],
  extra: [{ topic: "/odom", type: "geometry_msgs/msg/Point", count: 3 }] });
expected["empty.mcap"] = await writeMcap("empty.mcap", { topics: [] });
expected["posed.mcap"] = await writeMcap("posed.mcap", {
  topics: [{ topic: "/points", layout: "velodyne", clouds: 4, points: 300 }],
  extra: [{ topic: "/odom", type: "nav_msgs/msg/Odometry", count: 6, poses: true },
          { topic: "/pose", type: "geometry_msgs/msg/PoseStamped", count: 6, poses: true }] });
expected["tf.mcap"] = await writeMcap("tf.mcap", {
  topics: [{ topic: "/points", layout: "velodyne", clouds: 4, points: 300 }],
  extra: [{ tf: true }, { topic: "/odom", type: "nav_msgs/msg/Odometry", child: "base_link", count: 12, poses: true }] });

// the raw CDR messages of one topic, for the rosbag2 SQLite file write_db3.py makes
const db3 = [];
for (let k = 0; k < 4; k++) {
  const c = cloud("ouster", k, 512, 8);
  db3.push({ timestamp: (c.stampNs + 1000n).toString(), data: Buffer.from(c.bytes).toString("base64") });
}
expected["ouster.db3"] = { "/ouster/points": { layout: "ouster", clouds: [0, 1, 2, 3].map((k) => cloud("ouster", k, 512, 8).expected) } };
writeFileSync(`${OUT}/expected.json`, JSON.stringify(expected));
writeFileSync(`${OUT}/db3_messages.json`, JSON.stringify({ topic: "/ouster/points", type: "sensor_msgs/msg/PointCloud2", messages: db3 }));
console.log(`wrote ${Object.keys(expected).length} recordings into ${OUT}`);

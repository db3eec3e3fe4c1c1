// Writes a KITTI-layout folder's scans (velodyne/*.bin: x y z reflectance, float32) as one MCAP
// file of sensor_msgs/PointCloud2 on /points (zstd chunks), with foxglove's writers: the same
// frames as a robot's recording, for comparing the two through `eco run`.
//
// usage: node kitti_to_mcap.mjs KITTI_DIR OUT.mcap [none|lz4|zstd (default)] [--cdr OUT.cdrs]
// --cdr also writes the messages as they are (u64 log time, u32 length, CDR bytes, little-endian)
// for a rosbag2 SQLite file to be made of them.

import { McapWriter } from "@mcap/core";
import { open } from "node:fs/promises";
import { readdirSync, readFileSync, openSync, writeSync, closeSync } from "node:fs";
import { COMPRESSORS, FileWritable, POINT_CLOUD2, cdrWriter } from "./ros2_messages.mjs";

const [dir, out, compression = "zstd"] = process.argv.slice(2);
const cdrAt = process.argv.indexOf("--cdr");
const cdr = cdrAt > 0 ? openSync(process.argv[cdrAt + 1], "w") : null;
const writer = cdrWriter(POINT_CLOUD2);
const handle = await open(out, "w");
const mcap = new McapWriter({ writable: new FileWritable(handle), compressChunk: COMPRESSORS[compression] });
await mcap.start({ profile: "ros2", library: "eco-tests kitti_to_mcap" });
const schema = await mcap.registerSchema({ name: "sensor_msgs/msg/PointCloud2", encoding: "ros2msg",
                                           data: new TextEncoder().encode(POINT_CLOUD2) });
const channel = await mcap.registerChannel({ topic: "/points", schemaId: schema, messageEncoding: "cdr", metadata: new Map() });
const scans = readdirSync(`${dir}/velodyne`).filter((f) => f.endsWith(".bin")).sort();
for (const [k, file] of scans.entries()) {
  const bytes = readFileSync(`${dir}/velodyne/${file}`);
  const data = new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const stamp = BigInt(k) * 100000000n;
  const message = {
    header: { stamp: { sec: Number(stamp / 1000000000n), nanosec: Number(stamp % 1000000000n) }, frame_id: "velodyne" },
    height: 1, width: data.length / 16,
    fields: [["x", 0], ["y", 4], ["z", 8], ["intensity", 12]].map(([name, offset]) => ({ name, offset, datatype: 7, count: 1 })),
    is_bigendian: false, point_step: 16, row_step: data.length, data, is_dense: true,
  };
  const bytes_out = writer.writeMessage(message);
  await mcap.addMessage({ channelId: channel, sequence: k, logTime: stamp, publishTime: stamp, data: bytes_out });
  if (cdr !== null) {
    const head = Buffer.alloc(12);
    head.writeBigUInt64LE(stamp, 0);
    head.writeUInt32LE(bytes_out.byteLength, 8);
    writeSync(cdr, head);
    writeSync(cdr, bytes_out);
  }
}
await mcap.end();
await handle.close();
if (cdr !== null) closeSync(cdr);
console.log(`wrote ${scans.length} clouds to ${out}`);

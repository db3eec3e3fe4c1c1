// What the test recordings' writers share: ROS 2 message definitions (as ros2msg text, for
// foxglove's CDR serialiser and for the MCAP schema records), the serialisers made of them, chunk
// compressors (lz4js, foxglove's zstd) and a file McapWriter can write to.

import { parse } from "@foxglove/rosmsg";
import { MessageWriter } from "@foxglove/rosmsg2-serialization";
import * as zstd from "@foxglove/wasm-zstd";
import lz4 from "lz4js";

await zstd.isLoaded;

const SEPARATOR = "\n================================================================================\n";
const HEADER = `MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id${SEPARATOR}MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec`;
const QUATERNION = `MSG: geometry_msgs/Quaternion
float64 x
float64 y
float64 z
float64 w`;
const VECTOR3 = `MSG: geometry_msgs/Vector3
float64 x
float64 y
float64 z`;
const POSE = `MSG: geometry_msgs/Pose
Point position
Quaternion orientation${SEPARATOR}MSG: geometry_msgs/Point
float64 x
float64 y
float64 z${SEPARATOR}${QUATERNION}`;

export const POINT_CLOUD2 = `std_msgs/Header header
uint32 height
uint32 width
sensor_msgs/PointField[] fields
bool is_bigendian
uint32 point_step
uint32 row_step
uint8[] data
bool is_dense${SEPARATOR}${HEADER}${SEPARATOR}MSG: sensor_msgs/PointField
uint8 INT8=1
uint8 UINT8=2
uint8 INT16=3
uint16 UINT16=4
uint8 INT32=5
uint8 UINT32=6
uint8 FLOAT32=7
uint8 FLOAT64=8
string name
uint32 offset
uint8 datatype
uint32 count`;
export const POINT = `float64 x
float64 y
float64 z`;
export const ODOMETRY = `std_msgs/Header header
string child_frame_id
geometry_msgs/PoseWithCovariance pose
geometry_msgs/TwistWithCovariance twist${SEPARATOR}MSG: geometry_msgs/PoseWithCovariance
Pose pose
float64[36] covariance${SEPARATOR}MSG: geometry_msgs/TwistWithCovariance
Twist twist
float64[36] covariance${SEPARATOR}MSG: geometry_msgs/Twist
Vector3 linear
Vector3 angular${SEPARATOR}${VECTOR3}${SEPARATOR}${HEADER}${SEPARATOR}${POSE}`;
export const POSE_STAMPED = `std_msgs/Header header
geometry_msgs/Pose pose${SEPARATOR}${HEADER}${SEPARATOR}${POSE}`;

export const TF_MESSAGE = `geometry_msgs/TransformStamped[] transforms${SEPARATOR}MSG: geometry_msgs/TransformStamped
std_msgs/Header header
string child_frame_id
Transform transform${SEPARATOR}MSG: geometry_msgs/Transform
Vector3 translation
Quaternion rotation${SEPARATOR}${VECTOR3}${SEPARATOR}${QUATERNION}${SEPARATOR}${HEADER}`;

/// A CDR serialiser of the message `definition` describes.
export function cdrWriter(definition) {
  return new MessageWriter(parse(definition, { ros2: true }));
}

export const COMPRESSORS = {
  none: undefined,
  lz4: (data) => ({ compression: "lz4", compressedData: lz4.compress(data) }),
  zstd: (data) => ({ compression: "zstd", compressedData: zstd.compress(data, 3) }),
};

/// An open file as McapWriter writes it: bytes appended, their count its position.
export class FileWritable {
  constructor(handle) { this.handle = handle; this.size = 0n; }
  async write(buffer) { await this.handle.write(buffer); this.size += BigInt(buffer.byteLength); }
  position() { return this.size; }
}

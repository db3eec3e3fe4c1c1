"""Writes the ROS 1 bags ECO's reader is tested on with Debian's rosbag (python3-rosbag), not ECO's
code: Ouster-laid PointCloud2 clouds in an uncompressed, a bz2 and an lz4 bag, a recording split
over two bags in a folder, a bag with two cloud topics and an odometry topic, and one with tf's
tree (the tree and motion of write_mcap.mjs's tf.mcap). Beside them,
ros1_expected.json: what each cloud must decode to (the formula of write_mcap.mjs).

usage: write_ros1_bags.py OUT_DIR"""

import json
import math
import os
import struct
import sys

import rosbag
import rospy
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import PointCloud2, PointField
from tf2_msgs.msg import TFMessage

OUT = sys.argv[1]
STAMP0 = 1700000000
# Ouster's layout: x y z float32, intensity float32 at 16, t uint32 ns at 20, reflectivity, ring
FIELDS = [("x", PointField.FLOAT32, 0), ("y", PointField.FLOAT32, 4), ("z", PointField.FLOAT32, 8),
          ("intensity", PointField.FLOAT32, 16), ("t", PointField.UINT32, 20), ("reflectivity", PointField.UINT16, 24),
          ("ring", PointField.UINT16, 26)]
STEP = 48


def f32(v):
    return struct.unpack("<f", struct.pack("<f", v))[0]


def cloud(k, points, height):
    """Cloud k and what it decodes to: points, intensities, times (skipping NaN and zero points)."""
    data = bytearray(points * STEP)
    expected = {"stamp_ns": str(STAMP0 * 10**9 + k * 10**8), "points": [], "intensities": [], "times": []}
    for i in range(points):
        xyz = [5 + 0.01 * i + k, ((i * 7) % 13) - 6 + 0.001 * k, (i % 5) * 0.3 - 0.6]
        if i % 50 == 7:
            xyz = [math.nan, 1, 2]
        if i % 61 == 3:
            xyz = [0, 0, 0]
        t = round(0.1 * i / points * 1e9)
        struct.pack_into("<fff", data, i * STEP, *xyz)
        struct.pack_into("<fIHH", data, i * STEP + 16, (i * 3) % 200, t, (i * 3) % 200, i % 32)
        if not all(math.isfinite(v) for v in xyz) or all(v == 0 for v in xyz):
            continue
        expected["points"].append([f32(v) for v in xyz])
        expected["intensities"].append(f32((i * 3) % 200))
        expected["times"].append(t * 1e-9)
    msg = PointCloud2()
    msg.header.stamp = rospy.Time(STAMP0, k * 10**8)
    msg.header.frame_id = "lidar"
    msg.height, msg.width = height, points // height
    msg.fields = [PointField(name, offset, datatype, 1) for name, datatype, offset in FIELDS]
    msg.is_bigendian = False
    msg.point_step, msg.row_step = STEP, STEP * (points // height)
    msg.data = bytes(data)
    msg.is_dense = False
    return msg, expected


def write(path, topics, compression="none", odometry=0):
    expected = {}
    with rosbag.Bag(path, "w", compression=compression) as bag:
        for topic, first, count, points in topics:
            expected[topic] = {"layout": "ouster", "clouds": []}
            for k in range(first, first + count):
                msg, want = cloud(k, points, 8)
                bag.write(topic, msg, msg.header.stamp + rospy.Duration(0, 1000))
                expected[topic]["clouds"].append(want)
        for k in range(odometry):
            odom = Odometry()
            odom.header.stamp = rospy.Time(STAMP0, k * 10**8)
            odom.pose.pose.position.x = float(k)
            odom.pose.pose.orientation.w = 1.0
            bag.write("/odom", odom, odom.header.stamp)
    return expected


def transform(stamp, parent, child, translation, yaw):
    t = TransformStamped()
    t.header.stamp, t.header.frame_id, t.child_frame_id = stamp, parent, child
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = translation
    t.transform.rotation.z, t.transform.rotation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    return t


def write_tf(path):
    """4 clouds of /points in frame lidar; /tf_static: base_link -> lidar at (1, 0, 2) turned 90
    degrees, base_link -> camera; /tf: odom -> base_link at x = 10 m/s * t, yaw 0.5 rad/s * t, 20 Hz,
    and map -> odom at (0, 5, 0) at the ends."""
    expected = write(path, [("/points", 0, 4, 512)])
    t0 = rospy.Time(STAMP0)
    with rosbag.Bag(path, "a") as bag:
        static = TFMessage([transform(t0, "base_link", "lidar", (1, 0, 2), math.pi / 2),
                            transform(t0, "base_link", "camera", (0.5, 0, 1), 0)])
        bag.write("/tf_static", static, t0)
        for k in range(12):
            stamp = t0 + rospy.Duration(0, k * 50000000) - rospy.Duration(0, 50000000)
            t = (stamp - t0).to_sec()
            transforms = [transform(stamp, "odom", "base_link", (10 * t, 0, 0), 0.5 * t)]
            if k in (0, 11):
                transforms.append(transform(stamp, "map", "odom", (0, 5, 0), 0))
            bag.write("/tf", TFMessage(transforms), stamp)
    return expected


expected = {}
expected["tf.bag"] = write_tf(os.path.join(OUT, "tf.bag"))
for compression in ["none", "bz2", "lz4"]:
    expected[f"ouster_{compression}.bag"] = write(os.path.join(OUT, f"ouster_{compression}.bag"),
                                                  [("/os_cloud_node/points", 0, 4, 512)], compression)
os.makedirs(os.path.join(OUT, "split_bags"), exist_ok=True)
first = write(os.path.join(OUT, "split_bags", "drive_0.bag"), [("/points", 0, 2, 256)], "lz4")
second = write(os.path.join(OUT, "split_bags", "drive_1.bag"), [("/points", 2, 3, 256)], "lz4")
expected["split_bags"] = {"/points": {"layout": "ouster", "clouds": first["/points"]["clouds"] + second["/points"]["clouds"]}}
expected["two_lidars.bag"] = write(os.path.join(OUT, "two_lidars.bag"),
                                   [("/front/points", 0, 3, 256), ("/rear/points", 0, 2, 256)], "bz2", odometry=4)
with open(os.path.join(OUT, "ros1_expected.json"), "w") as f:
    json.dump(expected, f)
print(f"wrote {len(expected)} ROS 1 recordings into {OUT}")

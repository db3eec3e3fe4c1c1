"""Writes a drive as a robot records it, with Debian's rosbag (python3-rosbag), not ECO's code:
a KITTI-layout folder's scans (every 4th point) as sensor_msgs/PointCloud2 on /points in frame
`lidar`, each point timed by its azimuth across a 0.1 s sweep (a uint32 field t, ns after the
stamp, as Ouster's), the sensor's motion (a curve at 8 m/s, turning 0.4 rad/s) as nav_msgs/Odometry
on /odom and as tf (map -> lidar) at 20 Hz, from before the first sweep to after the last.

usage: write_drive_bag.py KITTI_DIR OUT.bag FRAMES"""

import math
import os
import struct
import sys

import numpy as np
import rosbag
import rospy
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import PointCloud2, PointField
from tf2_msgs.msg import TFMessage

folder, out, frames = sys.argv[1], sys.argv[2], int(sys.argv[3])
STAMP0 = 1700000000.0


def pose_at(t):
    """(x, y, z), yaw at t seconds after STAMP0."""
    yaw = 0.4 * t
    return (8.0 * t, 0.5 * t * t, 0.1 * math.sin(t)), yaw


def stamp(t):
    return rospy.Time.from_sec(STAMP0 + t)


def cloud(k, points):
    xyz = points[::4, :3]
    azimuth = np.arctan2(xyz[:, 1], xyz[:, 0])
    t_ns = np.round((azimuth + math.pi) / (2 * math.pi) * 0.1e9).astype(np.uint32)
    record = np.zeros(len(xyz), dtype=[("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("intensity", "<f4"), ("t", "<u4")])
    record["x"], record["y"], record["z"] = xyz[:, 0], xyz[:, 1], xyz[:, 2]
    record["intensity"] = points[::4, 3]
    record["t"] = t_ns
    msg = PointCloud2()
    msg.header.seq = k
    msg.header.stamp = stamp(0.1 * k)
    msg.header.frame_id = "lidar"
    msg.height, msg.width = 1, len(xyz)
    msg.fields = [PointField("x", 0, PointField.FLOAT32, 1), PointField("y", 4, PointField.FLOAT32, 1),
                  PointField("z", 8, PointField.FLOAT32, 1), PointField("intensity", 12, PointField.FLOAT32, 1),
                  PointField("t", 16, PointField.UINT32, 1)]
    msg.is_bigendian = False
    msg.point_step, msg.row_step = 20, 20 * len(xyz)
    msg.data = record.tobytes()
    msg.is_dense = True
    return msg


def motion(t):
    (x, y, z), yaw = pose_at(t)
    odom = Odometry()
    odom.header.stamp = stamp(t)
    odom.header.frame_id, odom.child_frame_id = "map", "lidar"
    odom.pose.pose.position.x, odom.pose.pose.position.y, odom.pose.pose.position.z = x, y, z
    odom.pose.pose.orientation.z, odom.pose.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    tf = TransformStamped()
    tf.header = odom.header
    tf.child_frame_id = "lidar"
    tf.transform.translation.x, tf.transform.translation.y, tf.transform.translation.z = x, y, z
    tf.transform.rotation = odom.pose.pose.orientation
    return odom, TFMessage([tf])


scans = sorted(f for f in os.listdir(os.path.join(folder, "velodyne")) if f.endswith(".bin"))[:frames]
with rosbag.Bag(out, "w") as bag:
    # the motion at 20 Hz, each pose logged 0.05 s before its stamp (a driver's odometry leads its
    # LiDAR's sweep), so that a cloud, logged as its sweep ends, finds every pose it needs
    for j in range(-1, 2 * len(scans) + 3):
        odom, tf = motion(0.05 * j)
        bag.write("/odom", odom, stamp(0.05 * j - 0.05))
        bag.write("/tf", tf, stamp(0.05 * j - 0.05))
    for k, name in enumerate(scans):
        points = np.fromfile(os.path.join(folder, "velodyne", name), dtype="<f4").reshape(-1, 4)
        bag.write("/points", cloud(k, points), stamp(0.1 * k + 0.1))
print(f"wrote {len(scans)} clouds to {out}")

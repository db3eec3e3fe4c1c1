"""Writes a KITTI-layout folder as a robot's ROS 1 bag, with Debian's rosbag (python3-rosbag): each
scan (velodyne/*.bin) as sensor_msgs/PointCloud2 on /points in frame `velodyne` at its times.txt
stamp, numbered by seq, and the LiDAR's pose (poses.txt through calib.txt's Tr: inv(Tr) P Tr) as
nav_msgs/Odometry on /odom (map -> velodyne), logged just before its cloud.

usage: kitti_to_bag.py KITTI_DIR OUT.bag [FRAMES]"""

import os
import sys

import numpy as np
import rosbag
import rospy
from nav_msgs.msg import Odometry
from scipy.spatial.transform import Rotation
from sensor_msgs.msg import PointCloud2, PointField

STAMP0 = 1700000000.0


def lidar_poses(folder):
    rows = np.loadtxt(os.path.join(folder, "poses.txt"), ndmin=2)
    tr = np.eye(4)
    with open(os.path.join(folder, "calib.txt")) as f:
        for line in f:
            if line.startswith("Tr:"):
                tr[:3, :4] = np.array(line.split()[1:], dtype=float).reshape(3, 4)
    poses = []
    for row in rows:
        p = np.eye(4)
        p[:3, :4] = row.reshape(3, 4)
        poses.append(np.linalg.inv(tr) @ p @ tr)
    return poses


def main(folder, out, frames=None):
    scans = sorted(f for f in os.listdir(os.path.join(folder, "velodyne")) if f.endswith(".bin"))[:frames]
    times = np.loadtxt(os.path.join(folder, "times.txt"), ndmin=1)
    poses = lidar_poses(folder)
    with rosbag.Bag(out, "w") as bag:
        for k, name in enumerate(scans):
            stamp = rospy.Time.from_sec(STAMP0 + times[k])
            odom = Odometry()
            odom.header.seq, odom.header.stamp, odom.header.frame_id, odom.child_frame_id = k, stamp, "map", "velodyne"
            position = odom.pose.pose.position
            position.x, position.y, position.z = poses[k][:3, 3]
            q = Rotation.from_matrix(poses[k][:3, :3]).as_quat()  # x, y, z, w
            o = odom.pose.pose.orientation
            o.x, o.y, o.z, o.w = q
            bag.write("/odom", odom, stamp - rospy.Duration(0, 1000000))
            with open(os.path.join(folder, "velodyne", name), "rb") as f:
                data = f.read()
            msg = PointCloud2()
            msg.header.seq, msg.header.stamp, msg.header.frame_id = k, stamp, "velodyne"
            msg.height, msg.width = 1, len(data) // 16
            msg.fields = [PointField(n, o, PointField.FLOAT32, 1) for n, o in (("x", 0), ("y", 4), ("z", 8), ("intensity", 12))]
            msg.point_step, msg.row_step, msg.is_dense = 16, len(data), True
            msg.data = data
            bag.write("/points", msg, stamp)
    return len(scans)


if __name__ == "__main__":
    n = main(sys.argv[1], sys.argv[2], int(sys.argv[3]) if len(sys.argv) > 3 else None)
    print(f"wrote {n} clouds to {sys.argv[2]}")

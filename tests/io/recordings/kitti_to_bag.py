"""Writes a KITTI-layout folder's scans (velodyne/*.bin: float32 x y z reflectance) as a ROS 1
bag of sensor_msgs/PointCloud2 on /points with Debian's rosbag (python3-rosbag): the same frames
as a robot's recording, for comparing the two through `eco run`.

usage: kitti_to_bag.py KITTI_DIR OUT.bag [none|bz2|lz4]"""

import os
import sys

import rosbag
import rospy
from sensor_msgs.msg import PointCloud2, PointField

folder, out = sys.argv[1], sys.argv[2]
compression = sys.argv[3] if len(sys.argv) > 3 else "lz4"
scans = sorted(f for f in os.listdir(os.path.join(folder, "velodyne")) if f.endswith(".bin"))
with rosbag.Bag(out, "w", compression=compression) as bag:
    for k, name in enumerate(scans):
        with open(os.path.join(folder, "velodyne", name), "rb") as f:
            data = f.read()
        msg = PointCloud2()
        msg.header.stamp = rospy.Time(0, 0) + rospy.Duration(0, k * 100000000)
        msg.header.frame_id = "velodyne"
        msg.height, msg.width = 1, len(data) // 16
        msg.fields = [PointField(n, o, PointField.FLOAT32, 1) for n, o in (("x", 0), ("y", 4), ("z", 8), ("intensity", 12))]
        msg.is_bigendian = False
        msg.point_step, msg.row_step = 16, len(data)
        msg.data = data
        msg.is_dense = True
        bag.write("/points", msg, msg.header.stamp if k > 0 else rospy.Time(0, 1))
print(f"wrote {len(scans)} clouds to {out}")

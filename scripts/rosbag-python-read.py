"""What reading a ROS 1 bag's clouds costs the usual Python way: Debian's rosbag (python3-rosbag)
and numpy, each cloud's x, y, z taken as a structured view and its non-finite and zero points
dropped, as eco does. Prints the mean ms a cloud.

usage: /usr/bin/python3 scripts/rosbag-python-read.py BAG [TOPIC]"""

import sys
import time

import numpy as np
import rosbag

TYPES = {1: "i1", 2: "u1", 3: "<i2", 4: "<u2", 5: "<i4", 6: "<u4", 7: "<f4", 8: "<f8"}
bag_path, topic = sys.argv[1], (sys.argv[2] if len(sys.argv) > 2 else "/points")
start = time.perf_counter()
clouds = points = 0
with rosbag.Bag(bag_path) as bag:
    for _, msg, _ in bag.read_messages(topics=[topic]):
        dtype = np.dtype({"names": [f.name for f in msg.fields], "formats": [TYPES[f.datatype] for f in msg.fields],
                          "offsets": [f.offset for f in msg.fields], "itemsize": msg.point_step})
        cloud = np.frombuffer(msg.data, dtype=dtype, count=msg.width * msg.height)
        xyz = np.stack([cloud["x"], cloud["y"], cloud["z"]], axis=1).astype(np.float32)
        keep = np.isfinite(xyz).all(axis=1) & (xyz != 0).any(axis=1)
        points += int(keep.sum())
        clouds += 1
print(f"{(time.perf_counter() - start) * 1000 / clouds:.2f} ms a cloud ({clouds} clouds, {points} points kept)")

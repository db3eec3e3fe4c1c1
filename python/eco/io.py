"""KITTI-layout sequences read one scan at a time, and single-file readers and writers.

    seq = eco.io.KittiSequence("sequences/00")
    for pose, points in seq:        # (4, 4) float64 world_T_lidar, (N, 3) float32 lidar frame
        tree.update(pose, points)

open (any source: KITTI, point-cloud files, MCAP and rosbag2 recordings), Source, KittiSequence, Scan,
PoseFrame; read_kitti_scan, read_kitti_poses, read_ply, read_pcd, write_ply,
write_pcd. Every reader raises eco.io.Error (an OSError) naming the file and the line or byte at
fault.
"""

from ._eco import io as _native
from ._reexport import reexport

__all__ = reexport(_native, globals(), __name__)

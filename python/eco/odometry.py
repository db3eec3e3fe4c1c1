"""A LiDAR odometry on ECO's map: scans in, poses out.

    odo = eco.odometry.Odometry()                    # or Odometry(map="voxel_hash", max_range=40)
    for pose, points in eco.sim.Simulator(frames=100):
        report = odo.register_frame(points)          # FrameReport: pose, iterations, timings
    eco.odometry.trajectory_errors(odo.poses, reference)

Odometry, OdometryConfig, FrameReport, trajectory_errors, map_names.
"""

from ._eco import odometry as _native
from ._reexport import reexport

__all__ = reexport(_native, globals(), __name__)

"""ECO — the Ego-Centric Octree, from Python.

An octree of the LiDAR points inside a cube of side L that travels with the sensor: each update
drops what the robot left behind and takes in what the new scan shows; queries (k nearest
neighbours, radius, box, voxel map) are exact over the held points.

    import numpy as np, eco

    tree = eco.EgoOctree(box_side=20.0, insert_policy="AllInBox")
    for pose, points in eco.sim.Simulator(frames=20):   # (4, 4) float64, (N, 3) float32
        tree.update(pose, points)
        nearest, sq_dists = tree.knn(np.zeros((1, 3)) + pose[:3, 3], k=5)

Modules: eco (EgoOctree, Config and its enums, Stats, UpdateStats), eco.io (KittiSequence, PLY,
PCD, KITTI files), eco.sim (Simulator, SimConfig), eco.odometry (a LiDAR odometry on ECO's map:
Odometry, trajectory_errors). Every class and function has a docstring.

Importing eco calls eco.keep_freed_heap(): the C library keeps what a frame frees for the next
frame (up to 128 MiB) instead of handing it back to the kernel, so that the arrays a frame loop
makes each frame do not fault fresh pages every frame (include/eco/process_heap.hpp).
"""

from . import _eco
from ._reexport import reexport

__all__ = reexport(_eco, globals(), __name__) + ["io", "sim", "odometry"]
__version__ = _eco.__version__
_eco.keep_freed_heap()

from . import io, odometry, sim  # noqa: E402  (after the core names, which they use)

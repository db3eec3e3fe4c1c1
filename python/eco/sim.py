"""The LiDAR simulator: a procedural city drive, for running ECO with no download.

    for pose, points in eco.sim.Simulator(frames=100, seed=1):
        tree.update(pose, points)

    eco.sim.Simulator(frames=300).write_kitti("data/sim")   # then eco.io.KittiSequence("data/sim")

Simulator, SimConfig, LidarModel, CityModel.
"""

from ._eco import sim as _native
from ._reexport import reexport

__all__ = reexport(_native, globals(), __name__)

#!/usr/bin/python3
"""ECO in five minutes: stream a simulated city drive through an Ego-Centric Octree, ask for
nearest neighbours, and plot what each update cost.

    make python                                      # once: builds and installs the package `eco`
    /usr/bin/python3 examples/python/quickstart.py   # writes results/eco_quickstart.png
"""

import argparse
import os
import time

import matplotlib

matplotlib.use("Agg")  # files only: runs without a display
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import eco  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--frames", type=int, default=100, help="frames to simulate (default 100)")
    parser.add_argument("--out", default="results/eco_quickstart.png", help="the plot to write (its folder is made)")
    args = parser.parse_args()

    # A 20 m cube around the sensor; raw scans, so insert everything in the box, at most two
    # points per 10 cm cell to keep memory bounded while the car waits at a light.
    tree = eco.EgoOctree(box_side=20.0, insert_policy="AllInBox",
                         density_cap=eco.DensityCap(cell_size=0.1, max_points=2))
    drive = eco.sim.Simulator(frames=args.frames, seed=1)  # 64 beams, 10 Hz, 1 m per frame

    update_ms, held = [], []
    for pose, points in drive:  # pose: (4, 4) world_T_lidar; points: (N, 3) float32, lidar frame
        start = time.perf_counter()
        tree.update(pose, points)
        update_ms.append(1e3 * (time.perf_counter() - start))
        held.append(len(tree))

    # Exact k nearest neighbours for a batch of queries around the sensor (world frame).
    rng = np.random.default_rng(0)
    queries = pose[:3, 3] + rng.uniform(-5.0, 5.0, size=(1000, 3))
    start = time.perf_counter()
    neighbours, sq_dists = tree.knn(queries, k=5)  # (1000, 5, 3), (1000, 5)
    knn_ms = 1e3 * (time.perf_counter() - start)

    stats = tree.stats()
    print(f"{len(drive)} frames, {stats.points} points held in {stats.nodes} nodes "
          f"({stats.bytes / 2**20:.1f} MiB), leaf depth {stats.mean_leaf_depth:.2f}")
    print(f"update: median {np.median(update_ms[1:]):.2f} ms, first frame {update_ms[0]:.2f} ms")
    print(f"knn: 1000 queries, k = 5, in {knn_ms:.2f} ms; "
          f"mean nearest distance {np.sqrt(sq_dists[:, 0]).mean():.3f} m")

    figure, (timing, top) = plt.subplots(1, 2, figsize=(13, 5))
    timing.plot(update_ms, color="tab:blue")
    timing.set_xlabel("frame")
    timing.set_ylabel("update time [ms]", color="tab:blue")
    timing.set_title("ECO update time per frame")
    count = timing.twinx()
    count.plot(held, color="tab:gray", linestyle="--")
    count.set_ylabel("points held", color="tab:gray")

    points = tree.points()
    top.scatter(points[:, 0], points[:, 1], c=points[:, 2], s=0.2, cmap="viridis")
    top.scatter(queries[:30, 0], queries[:30, 1], c="red", s=10, label="queries")
    top.scatter(neighbours[:30, :, 0].ravel(), neighbours[:30, :, 1].ravel(), c="orange", s=10,
                marker="x", label="their 5 nearest")
    top.set_aspect("equal")
    top.set_title("held points at the last frame (top view, colour = height)")
    top.legend(loc="upper right")
    figure.tight_layout()
    os.makedirs(os.path.dirname(args.out) or ".", exist_ok=True)
    figure.savefig(args.out, dpi=110)
    print(f"plot: {args.out}")


if __name__ == "__main__":
    main()

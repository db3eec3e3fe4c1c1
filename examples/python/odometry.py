#!/usr/bin/python3
"""A LiDAR odometry on ECO's map, from Python: track a simulated city drive, score the track
against the simulator's exact poses, and draw both from above.

    make python                                     # once: builds and installs the package `eco`
    /usr/bin/python3 examples/python/odometry.py    # writes results/eco_odometry.png
"""

import argparse
import os

import matplotlib

matplotlib.use("Agg")  # files only: runs without a display
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import eco  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--frames", type=int, default=150, help="frames to simulate (default 150)")
    parser.add_argument("--out", default="results/eco_odometry.png", help="the plot to write (its folder is made)")
    args = parser.parse_args()

    drive = eco.sim.Simulator(frames=args.frames, seed=1)
    tracks = {}
    for name in eco.odometry.map_names():  # "eco", "eco_ball" (a ball of max_range), KISS-ICP's voxel-hash map
        odo = eco.odometry.Odometry(map=name)  # KISS-ICP's settings for a 100 m LiDAR
        odo.set_start(drive.pose(0))           # share the reference's world frame
        frame_ms = [odo.register_frame(points).total_ms for _, points in drive]
        errors = eco.odometry.trajectory_errors(odo.poses, [drive.pose(i) for i in range(len(drive))])
        tracks[name] = odo.poses
        drift = f"drift {errors['translation_pct']:.3f} %, " if errors["by_length"] else ""
        print(f"{name:10s} {np.mean(frame_ms[1:]):6.2f} ms a frame, {drift}ATE {errors['ate_rmse'] * 100:.1f} cm "
              f"over {errors['path_length']:.0f} m")

    reference = np.array([drive.pose(i)[:2, 3] for i in range(len(drive))])
    plt.figure(figsize=(6, 6))
    plt.plot(reference[:, 0], reference[:, 1], "k--", label="reference")
    for (name, poses), marker in zip(tracks.items(), ["s", "^"]):
        plt.plot(poses[:, 0, 3], poses[:, 1, 3], marker=marker, markevery=max(1, len(poses) // 12), label=name)
    plt.axis("equal")
    plt.xlabel("x [m]")
    plt.ylabel("y [m]")
    plt.legend()
    plt.title("The odometry's track from above")
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    plt.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""What ECO saves a Python user: the map around the sensor kept by ECO, against what one writes
without it — keep the points inside the box in a numpy array (crop, append the new scan) and
rebuild scipy's cKDTree on it every frame. Both hold the points of every scan inside the ego box
(ECO's AllInBox policy, no density cap); python/tests prove ECO's answers equal cKDTree's.

    /usr/bin/python3 examples/python/versus_scipy.py --frames 60

Prints per-frame means and their ratios (numpy+cKDTree time / ECO time: above 1, ECO is faster),
measured in this one run (times drift between runs on a shared machine; compare the ratios).
KNN is timed for queries near the surfaces (held points moved by 5 cm, as in registration) and
anywhere in the box (as in planning); cKDTree runs with scipy's defaults.
"""

import argparse
import time

import numpy as np
from scipy.spatial import cKDTree

import eco


def inside(points, lo, hi):
    return np.all((points >= lo) & (points < hi), axis=1)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--frames", type=int, default=60)
    parser.add_argument("--queries", type=int, default=1000, help="KNN queries per frame (k = 5)")
    args = parser.parse_args()

    drive = eco.sim.Simulator(frames=args.frames, seed=1)
    tree = eco.EgoOctree(insert_policy="AllInBox")
    half = tree.config.box_side / 2
    held = np.zeros((0, 3))
    rng = np.random.default_rng(0)
    eco_update, numpy_upkeep = [], []
    eco_knn = {"near": [], "anywhere": []}
    scipy_knn = {"near": [], "anywhere": []}
    for pose, points in drive:
        start = time.perf_counter()
        tree.update(pose, points)
        eco_update.append(time.perf_counter() - start)

        start = time.perf_counter()
        lo, hi = pose[:3, 3] - half, pose[:3, 3] + half
        world = points.astype(np.float64) @ pose[:3, :3].T + pose[:3, 3]
        held = np.concatenate([held[inside(held, lo, hi)], world[inside(world, lo, hi)]])
        kd = cKDTree(held)  # scipy's defaults, as most code calls it
        numpy_upkeep.append(time.perf_counter() - start)

        queries = {  # registration asks near surfaces; planning asks anywhere in the box
            "near": held[rng.integers(0, len(held), args.queries)] + rng.normal(0.0, 0.05, (args.queries, 3)),
            "anywhere": pose[:3, 3] + rng.uniform(-8.0, 8.0, size=(args.queries, 3)),
        }
        for kind, batch in queries.items():
            start = time.perf_counter()
            tree.knn(batch, 5)
            eco_knn[kind].append(time.perf_counter() - start)
            start = time.perf_counter()
            kd.query(batch, 5)
            scipy_knn[kind].append(time.perf_counter() - start)

    def ms(values):
        return 1e3 * float(np.mean(values[1:]))  # the first frame builds from nothing for both

    print(f"{args.frames} simulated frames; at the end ECO holds {len(tree)} points, numpy {len(held)} "
          f"(they differ only at the box's walls, by float rounding); {args.queries} KNN queries (k = 5) "
          f"a frame; means over frames 1..{args.frames - 1}")
    print(f"  map upkeep:                 ECO update {ms(eco_update):7.2f} ms, numpy crop + append + "
          f"cKDTree build {ms(numpy_upkeep):7.2f} ms -> {ms(numpy_upkeep) / ms(eco_update):.2f}x")
    for kind in ("near", "anywhere"):
        print(f"  KNN batch, queries {kind:8s}: ECO {ms(eco_knn[kind]):7.2f} ms, "
              f"cKDTree {ms(scipy_knn[kind]):7.2f} ms -> {ms(scipy_knn[kind]) / ms(eco_knn[kind]):.2f}x")


if __name__ == "__main__":
    main()

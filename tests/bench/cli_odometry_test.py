"""eco odometry as a user drives it: five maps on the same simulated frames, each writing its
poses (KITTI format, one line a frame) and per-frame figures, the summary naming every map with
its accuracy; a folder without poses runs without accuracy figures and says so; fewer poses than
scans, an unknown map, a folder of bad scans: refused with a message naming what is wrong.

usage: cli_odometry_test.py ECO_CLI WORK_DIR"""

import json
import os
import shutil
import sys

from eco_command import check, eco, start

CLI, WORK = start(sys.argv)


def path(*parts):
    return os.path.join(WORK, *parts)


def lines(*parts):
    with open(path(*parts)) as f:
        return f.read().splitlines()


eco("simulate", "--out", "sim", "--frames", "8", "--seed", "3")
done = eco("odometry", "--data", "sim", "--map", "all", "--out", "all")
maps = ["eco", "eco_ball", "voxel_hash", "nanoflann", "pcl_octree"]
for m in maps:
    poses = lines("all", m, "poses.txt")
    check(len(poses) == 8 and all(len(p.split()) == 12 for p in poses), f"{m}/poses.txt: {poses}")
    frames = lines("all", m, "frames.csv")
    check(len(frames) == 9 and frames[0].startswith("frame,registered"), f"{m}/frames.csv: {frames[:2]}")
    check(f"| {m} " in done.stdout, f"{m} is missing from the printed table:\n{done.stdout}")
summary_md = open(path("all", "summary.md")).read()
for m in maps:
    check(f"| {m} |" in summary_md, f"{m} is missing from summary.md:\n{summary_md}")
check("too short for any" in summary_md, "a drive of 8 m has no 100 m segment:\n" + summary_md)
check(max(len(line) for line in done.stdout.splitlines()) <= 100, "the printed table is wider than a terminal")
summary = json.load(open(path("all", "summary.json")))
check([m["map"] for m in summary["maps"]] == maps, str(summary))
for m in summary["maps"]:  # the simulator's 8 frames are recovered to a few centimetres by every map
    check(m["errors"]["ate_rmse_m"] < 0.05, f"{m['map']}: ATE {m['errors']['ate_rmse_m']} m")
svg = open(path("all", "trajectory.svg")).read()
check(svg.count("class='estimate'") == 5 and "class='reference'" in svg, "trajectory.svg lacks a line")
config = json.load(open(path("all", "config.json")))
check(os.path.isabs(config["odometry"]["data"]), "config.json keeps the data folder as typed")

# the estimate in the reference's convention: the simulator's poses are camera-frame (calib.txt)
first_estimate = [float(v) for v in lines("all", "eco", "poses.txt")[0].split()]
first_reference = [float(v) for v in lines("sim", "poses.txt")[0].split()]
check(max(abs(a - b) for a, b in zip(first_estimate, first_reference)) < 1e-6, "the first pose is not the reference's")

# scans alone: the run goes on, without accuracy figures
shutil.copytree(path("sim"), path("no-poses"))
os.remove(path("no-poses", "poses.txt"))
alone = eco("odometry", "--data", "no-poses", "--out", "alone")
check("no reference poses" in alone.stdout and "no accuracy figures" in alone.stdout.lower(), alone.stdout)
check(len(lines("alone", "eco", "poses.txt")) == 8, "no poses written without a reference")

# refused by name
shutil.copytree(path("sim"), path("short"))
with open(path("short", "poses.txt"), "w") as f:
    f.write("\n".join(lines("sim", "poses.txt")[:5]) + "\n")
short = eco("odometry", "--data", "short", "--out", "short-run", ok=False)
check("poses.txt" in short.stderr and "5 poses for 8 scans" in short.stderr, short.stderr)
unknown = eco("odometry", "--map", "kdtree", "--frames", "2", ok=False)
check("kdtree" in unknown.stderr, unknown.stderr)
shutil.copytree(path("sim"), path("cut"))
with open(path("cut", "velodyne", "000003.bin"), "r+b") as f:
    f.truncate(10)
cut = eco("odometry", "--data", "cut", "--out", "cut-run", ok=False)
check("000003.bin" in cut.stderr, cut.stderr)
bad = eco("odometry", "--frames", "2", "--voxel-size", "-1", ok=False)
check("voxel_size" in bad.stderr, bad.stderr)
print("ok")

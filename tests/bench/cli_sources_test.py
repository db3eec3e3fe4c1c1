"""--data as a robot's owner uses it: the simulator's drive as a KITTI folder, as an MCAP file of
PointCloud2 written by foxglove's writer, as a ROS 1 bag written by Debian's rosbag, and as
folders of .bin and .pcd files, each placed by the
same poses file, run through `eco run`: the same points held frame by frame and the same saved
map, byte for byte. Then --poses for a KITTI folder kept elsewhere, the warning for poses without
calib.txt, `eco bench` and `eco odometry` on a recording, and what is refused, by name.

usage: cli_sources_test.py ECO_CLI WORK_DIR NPM_DIR"""

import os
import shutil
import struct
import subprocess
import sys

import numpy as np

from eco_command import check, eco, start

CLI, WORK = start(sys.argv)
NPM = sys.argv[3]


def path(*parts):
    return os.path.join(WORK, *parts)


def held_rows(stdout):
    """The per-frame rows of eco run, without the update time (the only figure that may differ)."""
    rows = [line.split() for line in stdout.splitlines() if line.split() and line.split()[0].isdigit()]
    return [row[:9] for row in rows]


eco("simulate", "--out", "sim", "--frames", "8", "--seed", "3")

# the poses as the LiDAR's, in one file every source is given
def kitti_poses(file):
    return [np.vstack([np.array(line.split(), float).reshape(3, 4), [0, 0, 0, 1]]) for line in open(file) if line.strip()]


tr = [line for line in open(path("sim", "calib.txt")) if line.startswith("Tr:")][0].split()[1:]
velo_to_cam = np.vstack([np.array(tr, float).reshape(3, 4), [0, 0, 0, 1]])
with open(path("lidar_poses.txt"), "w") as f:
    for camera in kitti_poses(path("sim", "poses.txt")):
        lidar = np.linalg.inv(velo_to_cam) @ camera @ velo_to_cam
        f.write(" ".join(repr(v) for v in lidar[:3].reshape(-1)) + "\n")

os.makedirs(path("kitti", "velodyne"))
os.makedirs(path("bins"))
os.makedirs(path("pcds"))
for name in sorted(os.listdir(path("sim", "velodyne"))):
    shutil.copy(path("sim", "velodyne", name), path("kitti", "velodyne", name))
    shutil.copy(path("sim", "velodyne", name), path("bins", name))
    scan = np.fromfile(path("sim", "velodyne", name), dtype=np.float32).reshape(-1, 4)
    with open(path("pcds", name.replace(".bin", ".pcd")), "wb") as f:  # binary PCD, written here
        f.write(("# .PCD v0.7\nVERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n"
                 f"WIDTH {len(scan)}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {len(scan)}\nDATA binary\n").encode())
        f.write(scan.astype("<f4").tobytes())
shutil.copy(path("lidar_poses.txt"), path("kitti", "poses.txt"))
done = subprocess.run(["node", os.path.join(NPM, "kitti_to_mcap.mjs"), path("kitti"), path("drive.mcap")],
                      capture_output=True, text=True)
check(done.returncode == 0, f"kitti_to_mcap: {done.stderr}")
RECORDINGS = os.path.join(os.path.dirname(__file__), "..", "io", "recordings")
done = subprocess.run(["/usr/bin/python3", os.path.join(RECORDINGS, "kitti_to_bag.py"), path("kitti"), path("drive.bag")],
                      capture_output=True, text=True)
check(done.returncode == 0, f"kitti_to_bag: {done.stderr}")

# the same frames from four sources: the same points held, the same map saved
kitti = eco("run", "--data", "kitti", "--out", "run-kitti", "--save", "kitti.eco")
check("the poses are taken as the LiDAR's: there is no calib.txt" in kitti.stderr, f"no warning: {kitti.stderr}")
rows = held_rows(kitti.stdout)
check(len(rows) == 8, f"eco run on the KITTI folder: {kitti.stdout}")
for source in ["drive.mcap", "drive.bag", "bins", "pcds"]:
    run = eco("run", "--data", source, "--poses", "lidar_poses.txt", "--out", f"run-{source}", "--save", f"{source}.eco")
    check(held_rows(run.stdout) == rows, f"{source} holds other points than the KITTI folder:\n{run.stdout}\n{kitti.stdout}")
    check(open(path(f"{source}.eco"), "rb").read() == open(path("kitti.eco"), "rb").read(), f"{source}: another map saved")
check("drive.mcap (MCAP), topic /points: 8 clouds; no per-point time; intensity: intensity"
      in eco("run", "--data", "drive.mcap", "--poses", "lidar_poses.txt", "--frames", "1").stdout, "the recording's first line")

# --start: every source begins at the frame asked for, the simulator's drive too
for source in ["kitti", "drive.mcap", "drive.bag"]:
    late = eco("run", "--data", source, "--poses", "lidar_poses.txt", "--start", "3", "--frames", "4", "--out", "run-late")
    scans = [row[1] for row in held_rows(late.stdout)]
    check(scans == [row[1] for row in rows[3:7]], f"{source} --start 3: scans {scans}, not those of frames 3-6")
check("--start 8 is past the last of the 8 frames" in eco("run", "--data", "kitti", "--start", "8", ok=False).stderr,
      "--start past the end")
simulated = [row[1] for row in held_rows(eco("run", "--frames", "6", "--out", "run-sim").stdout)]
late_sim = [row[1] for row in held_rows(eco("run", "--start", "2", "--frames", "4", "--out", "run-sim-late").stdout)]
check(late_sim == simulated[2:6], f"the simulator from frame 2: {late_sim}, not {simulated[2:6]}")

# a KITTI folder whose poses are kept elsewhere (as KITTI's own are)
os.makedirs(path("kitti-bare"))
shutil.copytree(path("kitti", "velodyne"), path("kitti-bare", "velodyne"))
bare = eco("run", "--data", "kitti-bare", "--poses", "lidar_poses.txt", "--out", "run-bare")
check(held_rows(bare.stdout) == rows, "--poses on a KITTI folder")

# the benchmark and the odometry on a recording
bench = eco("bench", "--data", "drive.mcap", "--poses", "lidar_poses.txt", "--workload", "dynamic", "--methods",
            "eco,nanoflann", "--out", "bench-mcap")
check("| eco |" in bench.stdout and "| nanoflann |" in bench.stdout, bench.stdout)
odometry = eco("odometry", "--data", "drive.mcap", "--out", "odometry-mcap")
check("no reference poses" in odometry.stdout, odometry.stdout)
check(len(open(path("odometry-mcap", "eco", "poses.txt")).read().splitlines()) == 8, "the odometry's poses")
with_reference = eco("odometry", "--data", "drive.mcap", "--poses", "lidar_poses.txt", "--out", "odometry-reference")
check("ATE" in open(path("odometry-reference", "summary.md")).read(), "no accuracy figures with --poses")

# refused by name
no_poses = eco("run", "--data", "drive.mcap", ok=False)
check("drive.mcap has no poses" in no_poses.stderr and "eco odometry --data drive.mcap" in no_poses.stderr, no_poses.stderr)
topic = eco("run", "--data", "drive.mcap", "--topic", "/velodyne_points", ok=False)
check("has no topic /velodyne_points; its topics:" in topic.stderr and "/points" in topic.stderr, topic.stderr)
with open(path("short_poses.txt"), "w") as f:
    f.write("".join(open(path("lidar_poses.txt")).readlines()[:5]))
short = eco("run", "--data", "bins", "--poses", "short_poses.txt", ok=False)
check("5 poses for 8 point-cloud files" in short.stderr, short.stderr)
short = eco("run", "--data", "drive.mcap", "--poses", "short_poses.txt", ok=False)
check("5 poses for 8 clouds" in short.stderr, short.stderr)
no_tf = eco("run", "--data", "drive.mcap", "--pose-topic", "tf", ok=False)
check("has no /tf or /tf_static topic of tf2_msgs/TFMessage; its topics:" in no_tf.stderr, no_tf.stderr)
fixed = eco("run", "--data", "drive.mcap", "--fixed_frame", "map", ok=False)
check("--fixed-frame map is for --pose-topic tf" in fixed.stderr, fixed.stderr)
os.makedirs(path("empty"))
empty = eco("run", "--data", "empty", ok=False)
check("is none of what --data reads" in empty.stderr, empty.stderr)
open(path("cut.bag"), "wb").write(b"#ROSBAG V2.0\n")
bag = eco("run", "--data", "cut.bag", ok=False)
check("cut.bag: " in bag.stderr and "ROS 1 bag" in bag.stderr, bag.stderr)
missing = eco("run", "--data", "nowhere", ok=False)
check("nowhere: no such file or folder" in missing.stderr, missing.stderr)
unit = eco("run", "--data", "drive.mcap", "--time-unit", "minutes", ok=False)
check("--time-unit" in unit.stderr, unit.stderr)
print("ok")

#!/usr/bin/env bash
# docs/benchmarks.md's reading figures: one simulated drive written by foxglove's MCAP writer
# (plain, lz4 and zstd chunks), as a rosbag2 SQLite file and as a ROS 1 bag (Debian's rosbag), each run through `eco run` against the
# same KITTI folder (the time to read and decode a frame against ECO's update of it, and the points
# held, frame by frame), and the ROS 1 bag read by Debian's Python rosbag; then the peak memory of reading FRAMES_LONG frames against FRAMES_SHORT.
# usage: scripts/recording-read-speed.sh [BUILD_DIR] [OUT_DIR]   (after make test: build/npm holds the writers)
set -euo pipefail
build="${1:-build}" out="${2:-$build/read-speed}"
eco="$(realpath "$build/bin/eco")" npm="$(realpath "$build/npm")" here="$(cd "$(dirname "$0")/.." && pwd)"
frames="${FRAMES:-120}" long="${FRAMES_LONG:-1000}" short="${FRAMES_SHORT:-100}"
mkdir -p "$out" && cd "$out"
rm -rf sim lidar && "$eco" simulate --out sim --frames "$frames" --seed 1 > /dev/null
# the poses as the LiDAR's, in one file every source is given
/usr/bin/python3 - <<'PY'
import numpy as np
tr = [l for l in open("sim/calib.txt") if l.startswith("Tr:")][0].split()[1:]
T = np.vstack([np.array(tr, float).reshape(3, 4), [0, 0, 0, 1]])
with open("lidar_poses.txt", "w") as f:
    for line in open("sim/poses.txt"):
        P = np.vstack([np.array(line.split(), float).reshape(3, 4), [0, 0, 0, 1]])
        f.write(" ".join(repr(v) for v in (np.linalg.inv(T) @ P @ T)[:3].reshape(-1)) + "\n")
PY
mkdir -p lidar && cp -r sim/velodyne lidar/ && cp lidar_poses.txt lidar/poses.txt
for c in none lz4 zstd; do node "$npm/kitti_to_mcap.mjs" lidar "drive_$c.mcap" "$c" $([ "$c" = none ] && echo --cdr drive.cdrs); done
/usr/bin/python3 "$here/tests/io/recordings/cdrs_to_db3.py" drive.cdrs drive.db3 /points
/usr/bin/python3 "$here/tests/io/recordings/kitti_to_bag.py" lidar drive.bag none > /dev/null
ls -l drive_*.mcap drive.db3 drive.bag
held() { grep -E '^ +[0-9]+ ' | awk '{print $1,$2,$3,$4,$5,$6,$7}'; }
"$eco" run --data lidar --out run-kitti > kitti.txt 2>/dev/null
for source in drive_none.mcap drive_lz4.mcap drive_zstd.mcap drive.db3 drive.bag; do
  "$eco" run --data "$source" --poses lidar_poses.txt --out "run-$source" > "$source.txt" 2>/dev/null
  same=$(diff <(held < kitti.txt) <(held < "$source.txt") > /dev/null && echo "the same points held" || echo "OTHER POINTS HELD")
  echo "$source: $(grep '^a frame:' "$source.txt"); $same as the KITTI folder"
done
echo "KITTI folder: $(grep '^a frame:' kitti.txt)"
echo "drive.bag through Debian's Python rosbag and numpy: $(/usr/bin/python3 "$here/scripts/rosbag-python-read.py" drive.bag)"

# peak memory: the same recording read for SHORT and LONG frames (16 beams, to keep the file small)
rm -rf long && "$eco" simulate --out long --frames "$long" --seed 1 --beams 16 --columns 1000 > /dev/null
node "$npm/kitti_to_mcap.mjs" long long.mcap zstd > /dev/null
for n in "$short" "$long"; do
  /usr/bin/time -f "%M" -o "peak_$n.txt" "$eco" odometry --data long.mcap --frames "$n" --out "odometry-$n" > /dev/null 2>&1
  echo "eco odometry --data long.mcap --frames $n: peak $(cat "peak_$n.txt") kB"
done

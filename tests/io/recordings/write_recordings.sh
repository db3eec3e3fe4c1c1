#!/usr/bin/env bash
# Writes the recordings the readers' tests read into OUT_DIR, with other people's writers:
# foxglove's MCAP and CDR writers from the npm registry (installed once into NPM_DIR, the build
# folder's), SQLite through Debian's python3, ROS 1 bags through Debian's rosbag (python3-rosbag).
# usage: write_recordings.sh OUT_DIR NPM_DIR
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
out="$1" npm_dir="$2"
mkdir -p "$out" "$npm_dir"
if ! cmp -s "$here/package.json" "$npm_dir/package.json" || [ ! -d "$npm_dir/node_modules/@mcap/core" ]; then
  cp "$here/package.json" "$npm_dir/package.json"
  (cd "$npm_dir" && npm install --no-audit --no-fund --loglevel=error)
fi
cp "$here/write_mcap.mjs" "$here/kitti_to_mcap.mjs" "$here/ros2_messages.mjs" "$npm_dir/"
node "$npm_dir/write_mcap.mjs" "$out"
/usr/bin/python3 "$here/write_db3.py" "$out"
/usr/bin/python3 "$here/write_ros1_bags.py" "$out"

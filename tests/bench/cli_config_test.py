"""The eco command's configuration, as a user drives it: every command writes config.json, feeding it
back with --config repeats the run (the same summary up to timing), flags given beside it win, and a
bad file is refused naming the file, the key and the value.

usage: cli_config_test.py ECO_CLI WORK_DIR"""

import json
import os
import subprocess
import sys

from eco_command import check, eco, start

CLI, WORK = start(sys.argv)


def load(path):
    with open(os.path.join(WORK, path)) as f:
        return json.load(f)


# simulate: writes its config.json; fed back, the same drive byte for byte
eco("simulate", "--out", "sim", "--frames", "4", "--seed", "3")
eco("simulate", "--config", "sim/config.json", "--out", "sim2")
for name in sorted(os.listdir(os.path.join(WORK, "sim", "velodyne"))):
    with open(os.path.join(WORK, "sim", "velodyne", name), "rb") as a, \
         open(os.path.join(WORK, "sim2", "velodyne", name), "rb") as b:
        check(a.read() == b.read(), f"simulate --config wrote a different {name}")

# bench: a preset, a config flag and options; then the same run from its config.json
eco("bench", "--data", "sim", "--preset", "robot-cap-0.2", "--methods", "eco,nanoflann,octree_base",
    "--knn-queries", "50", "--box_side", "18", "--out", "A")
eco("bench", "--config", "A/config.json", "--out", "B")
a, b = load("A/summary.json"), load("B/summary.json")
check(a["methods"].keys() == b["methods"].keys(), "the rerun ran other methods")
for method in a["methods"]:
    for key in ("points", "nodes", "mean_depth", "max_depth", "chamfer_m", "frames"):
        check(a["methods"][method].get(key) == b["methods"][method].get(key),
              f"{method}.{key}: {a['methods'][method].get(key)} then {b['methods'][method].get(key)}")
ca, cb = load("A/config.json"), load("B/config.json")
check(ca["config"] == cb["config"] and ca["bench"] == cb["bench"], "the rerun's config.json differs")
check(ca["config"]["box_side"] == 18.0 and ca["config"]["insert_policy"] == "AllInBox", ca["config"])
check(ca["config"]["density_cap"] == {"cell_size": 0.2, "max_points": 1}, ca["config"])

# each run in a folder of its own: an earlier run's is refused before the run, and left as it was
before = open(os.path.join(WORK, "A", "summary.json")).read()
again = eco("bench", "--config", "A/config.json", "--out", "A", ok=False)
check("A: holds an earlier run (config.json): each run goes into a folder of its own" in again.stderr, again.stderr)
check(open(os.path.join(WORK, "A", "summary.json")).read() == before, "the earlier run was touched")
fresh = [eco("bench", "--frames", "1", "--sim-frames", "2", "--methods", "eco", "--knn-queries", "0").stdout for _ in range(2)]
folders = [line.split()[1] for out in fresh for line in out.splitlines() if line.startswith("results: ")]
check(len(folders) == 2 and folders[0] != folders[1] and all(f.startswith("results/bench-") for f in folders), folders)
check(all(os.path.exists(os.path.join(WORK, f, "summary.json")) for f in folders), folders)

# a flag beside --config wins over the file
eco("bench", "--config", "A/config.json", "--box_side", "16", "--frames", "2", "--out", "C")
cc = load("C/config.json")
check(cc["config"]["box_side"] == 16.0 and cc["bench"]["frames"] == 2, cc)
check(cc["config"]["density_cap"] == ca["config"]["density_cap"], "the file's other fields were lost")

# the bench aligns Config.voxel_size with --voxel unless --voxel_size is given
check(ca["config"]["voxel_size"] == ca["bench"]["voxel"] == 0.2, ca)
eco("bench", "--data", "sim", "--preset", "robot", "--methods", "eco", "--knn-queries", "0", "--frames", "2",
    "--voxel_size", "0.05", "--out", "V")
check(load("V/config.json")["config"]["voxel_size"] == 0.05, "an explicit --voxel_size was overridden")

# per-point attributes: the bench feeds ids, intensities and frame times to the tree methods; the
# columns cost memory, and an age limit in seconds reads the times
plain = ["bench", "--data", "sim", "--preset", "robot", "--methods", "eco,octree_base", "--knn-queries", "0",
         "--frames", "4"]
eco(*plain, "--out", "U")
eco(*plain, "--attributes.ids", "true", "--attributes.intensity", "true", "--attributes.time", "true", "--out", "T")
eco(*plain, "--attributes.time", "true", "--max_age_seconds", "0.15", "--out", "S")
u, t, aged = (load(f"{d}/summary.json")["methods"] for d in ("U", "T", "S"))
for method in ("eco", "octree_base"):
    check(t[method]["points"] == u[method]["points"], f"{method}: attributes changed what is held")
    check(t[method]["bytes_per_point"] > u[method]["bytes_per_point"] + 10, f"{method}: {t[method]} vs {u[method]}")
    check(0 < aged[method]["points"] < u[method]["points"], f"{method}: the age limit in seconds dropped nothing")
check(load("T/config.json")["config"]["attributes"] == {"ids": True, "intensity": True, "time": True}, "attributes")
ran = eco("run", "--data", "sim", "--frames", "3", "--attributes.ids", "true", "--max_age_seconds", "1",
          "--attributes.time", "true", "--out", "RA").stdout
check("invariants: all hold" in ran, ran)

# run takes the tree's config from a bench file, and writes its own
eco("run", "--config", "A/config.json", "--data", "sim", "--frames", "2", "--out", "R")
cr = load("R/config.json")
check(cr["config"] == ca["config"], f"run's config {cr['config']} is not the bench's {ca['config']}")
check(cr["run"]["frames"] == 2 and cr["run"]["data"] == os.path.realpath(os.path.join(WORK, "sim")), cr["run"])
eco("run", "--config", "R/config.json", "--out", "R2")
check(load("R2/config.json")["run"] == cr["run"], "run --config lost an option")
# the data folder is stored resolved: the file works from another folder too
elsewhere = subprocess.run([CLI, "run", "--config", "config.json", "--out", "R3"], capture_output=True, text=True,
                           cwd=os.path.join(WORK, "R"))
check(elsewhere.returncode == 0, f"run --config from the file's own folder failed:\n{elsewhere.stderr}")

# bad files and bad flags: refused, naming the file, the key and the value
bad = {
    "unknown_field.json": ({"config": {"box_sid": 3}}, ["unknown_field.json", "box_sid"]),
    "out_of_range.json": ({"config": {"density_cap": {"max_points": 5000}}}, ["out_of_range.json",
                                                                              "density_cap.max_points", "5000"]),
    "bad_choice.json": ({"config": {"insert_policy": "sideways"}}, ["bad_choice.json", "insert_policy", "sideways"]),
    "bad_option.json": ({"bench": {"frames": "many"}}, ["bad_option.json", "frames", "many"]),
    "unknown_option.json": ({"bench": {"framez": 3}}, ["unknown_option.json", "framez"]),
    "unknown_section.json": ({"benchmark": {}}, ["unknown_section.json", "benchmark"]),
}
for name, (content, words) in bad.items():
    with open(os.path.join(WORK, name), "w") as f:
        json.dump(content, f)
    message = eco("bench", "--config", name, "--out", "X", ok=False).stderr
    for word in words:
        check(word in message, f"{name}: '{word}' not in: {message}")
with open(os.path.join(WORK, "not_json.json"), "w") as f:
    f.write("{box_side: 3")
check("not_json.json" in eco("run", "--config", "not_json.json", ok=False).stderr, "a broken file not named")
message = eco("bench", "--density_cap.max_points", "1e5", "--out", "X", ok=False).stderr
check("density_cap.max_points = 1e5 is invalid" in message, f"the value not as typed: {message}")
message = eco("run", "--box_side", "1e5", "--density_cap.cell_size", "0.1", "--density_cap.max_points", "2",
              "--out", "X", ok=False).stderr
check("box_side = 100000" in message and "(given: --box_side 1e5, --density_cap.cell_size 0.1)" in message, message)
message = eco("bench", "--k", "0", "--out", "X", ok=False).stderr
check("k = 0 must be >= 1" in message, message)
message = eco("bench", "--leaf_capacity", "0", "--out", "X", ok=False).stderr
check("leaf_capacity" in message and "0" in message, message)
check(not os.path.exists(os.path.join(WORK, "X")), "a refused run wrote results")

# the Python package takes config.json's "config" as a Config, when it is on the path
try:
    import eco as eco_python
except ImportError:
    eco_python = None
if eco_python is not None:
    check(eco_python.Config(**ca["config"]).to_dict() == ca["config"], "Python reads config.json differently")
print("ok")

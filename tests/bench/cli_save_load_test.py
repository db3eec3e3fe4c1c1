"""eco run's --save, --save-every and --load, as a user drives them: a drive run in two halves, the
second loading the first's map, ends with the same map, byte for byte, as the drive run whole (a
folder's frames, and the simulator's drive made anew by each run); a bad map file or a
configuration flag beside --load is refused by name.

usage: cli_save_load_test.py ECO_CLI WORK_DIR"""

import os
import sys

from eco_command import check, eco, start

CLI, WORK = start(sys.argv)


def read(path):
    with open(os.path.join(WORK, path), "rb") as f:
        return f.read()


def frame_rows(stdout):
    """The per-frame rows by frame: the counts, not bytes a point or the update's time."""
    rows = {}
    for line in stdout.splitlines():
        cells = line.split()
        if len(cells) == 11 and cells[0].isdigit():
            rows[int(cells[0])] = cells[:8]
    return rows


eco("simulate", "--out", "sim", "--frames", "10", "--seed", "2")
clearing = ["--clearing.enabled", "true", "--density_cap.cell_size", "0.2", "--density_cap.max_points", "1",
            "--attributes.ids", "true"]

whole = eco("run", "--data", "sim", "--out", "whole", "--export-every", "1", "--save", "whole/map.eco", *clearing)
first = eco("run", "--data", "sim", "--frames", "5", "--out", "first", "--save-every", "2", *clearing)
check("saved the map after frame 4 to first/map.eco" in first.stdout, first.stdout)
rest = eco("run", "--data", "sim", "--out", "rest", "--load", "first/map.eco", "--export-every", "1",
           "--save", "rest/map.eco")
check("loaded first/map.eco" in rest.stdout and "after frame 4" in rest.stdout, rest.stdout)
check("free-space clearing on" in rest.stdout, "the loaded map's settings are not printed:\n" + rest.stdout)
a, b = frame_rows(whole.stdout), frame_rows(rest.stdout)
check(sorted(b) == [5, 6, 7, 8, 9], f"the second run took frames {sorted(b)}")
for t in b:
    check(a[t] == b[t], f"frame {t}: whole run {a[t]}, after loading {b[t]}")
for t in range(5, 10):
    for kind in ("points", "voxels"):
        name = f"{t:06d}_{kind}.ply"
        check(read(f"whole/{name}") == read(f"rest/{name}"), f"{name} differs after loading")
check(read("whole/map.eco") == read("rest/map.eco"), "the map saved after the last frame differs")

# the same on the simulator's drive, made anew by each run for its own length: the world is the
# seed's whatever the length, so half a drive saved and the rest loaded is the whole drive
eco("run", "--frames", "6", "--out", "sim-whole", "--save", "sim-whole/map.eco", *clearing)
eco("run", "--frames", "3", "--out", "sim-first", "--save", "sim-first/map.eco", *clearing)
eco("run", "--frames", "6", "--out", "sim-rest", "--load", "sim-first/map.eco", "--save", "sim-rest/map.eco")
check(read("sim-whole/map.eco") == read("sim-rest/map.eco"), "the simulator's drive in two halves ends in another map")

# --config repeats a run that loaded a map: the same map again, saved where the first run saved it
saved = read("rest/map.eco")
os.remove(os.path.join(WORK, "rest/map.eco"))
again = eco("run", "--config", "rest/config.json", "--out", "again")
check("loaded" in again.stdout and read("rest/map.eco") == saved, "--config did not repeat the loading run")

# refused by name: a flag of the configuration beside --load, a file that is not a map, a cut map
done = eco("run", "--data", "sim", "--load", "first/map.eco", "--box_side", "30", ok=False)
check("drop --box_side 30" in done.stderr, done.stderr)
with open(os.path.join(WORK, "not-a-map.eco"), "wb") as f:
    f.write(b"hello, world, this is not a map file at all")
done = eco("run", "--data", "sim", "--load", "not-a-map.eco", ok=False)
check("not-a-map.eco: byte 0: not a map file" in done.stderr, done.stderr)
with open(os.path.join(WORK, "cut.eco"), "wb") as f:
    f.write(read("first/map.eco")[:1000])
done = eco("run", "--data", "sim", "--load", "cut.eco", ok=False)
check("cut.eco: byte 12:" in done.stderr and "truncated" in done.stderr, done.stderr)
print("ok")

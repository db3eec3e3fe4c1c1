#!/usr/bin/env python3
"""The region's figures on docs/benchmarks.md: ECO holding the cube, a ball and a box turned with
the heading (`eco`, `eco_ball`, `eco_box`), in one `eco bench` run per case on the same frames, on
the simulator's manoeuvres and the KITTI minis; then the budget (region.max_points) against the same
ball without one; then `eco odometry` on the cube and on a ball of max_range. Each command runs
alone on the second core; the results go under results/region/<case>/, the tables to stdout.

usage: scripts/region-cases.py [DATA_DIR] [--reuse]   (default ../shared/data; --reuse: keep the cases
already in results/region, running only those missing)"""

import csv
import json
import os
import shutil
import subprocess
import sys

ARGS = [a for a in sys.argv[1:] if a != "--reuse"]
REUSE = "--reuse" in sys.argv[1:]
DATA = ARGS[0] if ARGS else "../shared/data"
ECO = "build/bin/eco"
OUT = "results/region"
METHODS = "eco,eco_ball,eco_box"
# the robot's case: raw scans, 2 points kept per 0.1 m cell
PRESET = ["--preset", "robot-cap-0.1", "--knn-queries", "0"]
CASES = [  # name, what it is, its flags
    ("route", "the streets, 7 m corners at 10 m/s", ["--sim-manoeuvre", "route", "--sim-frames", "150"]),
    ("uturn", "U-turns of radius 2.5 m at 5 m/s", ["--sim-manoeuvre", "uturn", "--sim-speed", "5", "--sim-frames", "200"]),
    ("roundabout", "a 6 m circle at 9.42 m/s: 90 deg/s", ["--sim-manoeuvre", "roundabout", "--sim-speed", "9.42",
                                                         "--sim-frames", "100"]),
    ("spin", "turning in place at 1,000 deg/s", ["--sim-manoeuvre", "spin", "--sim-frames", "100"]),
    ("straight-30", "a straight at 30 m/s", ["--sim-manoeuvre", "straight", "--sim-speed", "30", "--sim-frames", "100"]),
    ("still", "standing still", ["--sim-manoeuvre", "still", "--sim-frames", "100"]),
]
TURNS = ["route", "uturn", "roundabout"]


def bench(name, flags):
    folder = os.path.join(OUT, name)
    summary = os.path.join(folder, "summary.json")
    if REUSE and os.path.exists(summary):
        with open(summary) as f:
            return json.load(f)["methods"]
    shutil.rmtree(folder, ignore_errors=True)
    command = ["taskset", "-c", "1", ECO, "bench", *flags, "--out", folder]
    print("== " + " ".join(command), file=sys.stderr)
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)["methods"]


def per_point(m):
    return m["update_ms"] / m["points"]


def region_table(results):
    print("| case | cube: held, update ms | ball: held, update ms, tested/frame | box: held, update ms, tested/frame "
          "| box / cube per held point | box p99 / mean |")
    print("|---|--:|--:|--:|--:|--:|")
    for name, what, m in results:
        c, b, x = m["eco"], m["eco_ball"], m["eco_box"]
        print(f"| {name} ({what}) | {c['points']:,.0f}, {c['update_ms']:.2f} "
              f"| {b['points']:,.0f}, {b['update_ms']:.2f}, {b['region_tested']:,.0f} "
              f"| {x['points']:,.0f}, {x['update_ms']:.2f}, {x['region_tested']:,.0f} "
              f"| {per_point(x) / per_point(c):.2f}x | {x['update_ms_p99'] / x['update_ms']:.2f}x |")


def frames(name, method):
    with open(os.path.join(OUT, name, method + ".csv")) as f:
        return list(csv.DictReader(f))


def budget_case():
    """The route's ball with a budget of 60 % of what it holds on average, against the same ball
    without one: frames over the budget, and frames under 0.95 x the budget where the whole
    ball holds more."""
    ball = ["--region.shape", "ball", "--region.radius", "10"]
    whole = bench("budget-none", PRESET + CASES[0][2] + ball + ["--methods", "eco"])["eco"]
    budget = int(0.6 * whole["points"])
    capped = bench("budget", PRESET + CASES[0][2] + ball + ["--region.max_points", str(budget), "--methods", "eco"])["eco"]
    short = sum(1 for a, b in zip(frames("budget-none", "eco"), frames("budget", "eco"))
                if int(a["points"]) > budget and int(b["points"]) < 0.95 * budget)
    print(f"\nBudget {budget:,} points (60 % of the ball's mean {whole['points']:,.0f}) on the route: "
          f"{capped['frames_over_budget']} frames over it; {short} frames under 0.95 x it where the whole ball "
          f"held more; smallest scale {capped['region_scale_min']:.2f}; update {capped['update_ms']:.2f} ms against "
          f"{whole['update_ms']:.2f} ms without the budget.")


def odometry_case():
    folder = os.path.join(OUT, "odometry")
    if not REUSE:
        shutil.rmtree(folder, ignore_errors=True)
    frames_, maps = "300", {}
    for m in ["eco", "eco_ball"]:  # one after the other on the same frames, as --map all runs them
        if REUSE and os.path.exists(os.path.join(folder, m, "summary.json")):
            with open(os.path.join(folder, m, "summary.json")) as f:
                maps[m] = json.load(f)["maps"][0]
            continue
        command = ["taskset", "-c", "1", ECO, "odometry", "--frames", frames_, "--map", m, "--out",
                   os.path.join(folder, m)]
        print("== " + " ".join(command), file=sys.stderr)
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
        with open(os.path.join(folder, m, "summary.json")) as f:
            maps[m] = json.load(f)["maps"][0]
    c, b = maps["eco"], maps["eco_ball"]
    print(f"\nOdometry, simulator, {frames_} frames: frame {b['frame_ms']:.2f} ms with a ball of max_range against "
          f"{c['frame_ms']:.2f} ms with the 200 m cube ({b['frame_ms'] / c['frame_ms']:.2f}x); drift "
          f"{b['errors']['translation_pct']:.3f} % against {c['errors']['translation_pct']:.3f} % (KITTI's segments).")


def main():
    results = [(name, what, bench(name, PRESET + flags + ["--methods", METHODS])) for name, what, flags in CASES]
    for seq in sorted(d for d in os.listdir(DATA) if d.startswith("kitti") and os.path.isdir(os.path.join(DATA, d))):
        results.append((seq, "KITTI", bench(seq, PRESET + ["--data", os.path.join(DATA, seq), "--methods", METHODS])))
    region_table(results)
    turns = [per_point(m["eco_box"]) / per_point(m["eco"]) for name, _, m in results
             if name in TURNS or name.startswith("kitti")]
    print(f"\nBox / cube per held point through turns: {min(turns):.2f}x to {max(turns):.2f}x (goal <= 1.2x).")
    budget_case()
    odometry_case()


if __name__ == "__main__":
    main()

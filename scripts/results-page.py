#!/usr/bin/env python3
"""The tables of docs/benchmarks.md from one sitting's results folders (scripts/results-sitting.sh):
per scenario a table of every sequence, then each goal with its verdict over the sequences.

usage: scripts/results-page.py [RESULTS_DIR]   (default results/page)"""

import json
import os
import sys

ROOT = sys.argv[1] if len(sys.argv) > 1 else "results/page"


def load(name):
    path = os.path.join(ROOT, name, "summary.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)["methods"]


def sequences():
    names = sorted({d.rsplit("-robot", 1)[0] for d in os.listdir(ROOT) if "-robot" in d})
    return [n for n in names if n != "sim"] + ["sim"]


def label(seq):
    return "simulator" if seq == "sim" else seq


def ratio(a, b):
    return a / b if a and b else float("nan")


def verdict(values, goal, at_most):
    met = [v <= goal if at_most else v >= goal for v in values]
    if all(met):
        return "met on all"
    if not any(met):
        return "**not met**"
    return f"met on {sum(met)} of {len(met)}"


def robot(preset):
    rows, figures = [], {"eco / scan_pass": [], "pcl / eco": [], "nanoflann / eco": [], "vox": [], "knn": [],
                         "bpp": [], "p99": [], "caller": []}
    print(f"| sequence | held | eco update / voxel / KNN ms | scan_pass | pcl_octree update / voxel / KNN | "
          f"nanoflann update / voxel / KNN | octree_base | update × scan_pass | pcl × eco | nanoflann × eco | "
          f"voxel × pcl | KNN × nanoflann | B/pt | p99 / mean | caller × scan_pass's |")
    print("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|")
    for seq in sequences():
        m = load(f"{seq}-{preset}")
        if m is None:
            continue
        e, s, p, k, o = m["eco"], m["scan_pass"], m["pcl_octree"], m["nanoflann"], m["octree_base"]
        f = {"eco / scan_pass": ratio(e["update_ms"], s["update_ms"]), "pcl / eco": ratio(p["update_ms"], e["update_ms"]),
             "nanoflann / eco": ratio(k["update_ms"], e["update_ms"]), "vox": ratio(e["voxel_ms"], p["voxel_ms"]),
             "knn": ratio(e["knn_ms"], k["knn_ms"]), "bpp": e["bytes_per_point"],
             "p99": ratio(e["update_ms_p99"], e["update_ms"]), "caller": ratio(e["caller_ms"], s["caller_ms"])}
        for key, v in f.items():
            figures[key].append(v)
        trio = lambda x: f"{x['update_ms']:.2f} / {x['voxel_ms']:.2f} / {x['knn_ms']:.2f}"
        print(f"| {label(seq)} | {e['points'] / 1000:.0f} k | {trio(e)} | {s['update_ms']:.2f} | {trio(p)} | {trio(k)} | "
              f"{o['update_ms']:.2f} | {f['eco / scan_pass']:.2f}× | {f['pcl / eco']:.2f}× | {f['nanoflann / eco']:.2f}× | "
              f"{f['vox']:.2f}× | {f['knn']:.2f}× | {f['bpp']:.1f} | {f['p99']:.2f}× | {f['caller']:.2f}× |")
    return figures


def goal_row(name, values, goal, at_most, unit="×"):
    shown = ", ".join(f"{v:.2f}{unit}" if unit == "×" else f"{v:.1f}{unit}" for v in values)
    print(f"| {name} | {'≤' if at_most else '≥'} {goal}{unit} | {shown} | {verdict(values, goal, at_most)} |")


def measured(values, goal, at_most, unit="×"):
    """A verdict with the range it was given on: one cell of the presets' goal table."""
    if not values:
        return ""
    digits = 2 if unit == "×" else 1
    return f"{verdict(values, goal, at_most)} ({min(values):.{digits}f}–{max(values):.{digits}f}{unit})"


def main():
    presets = ("robot", "robot-cap-0.2", "robot-cap-0.1")
    figures = {}
    for preset in presets:
        print(f"\n### `--preset {preset}`\n")
        figures[preset] = robot(preset)
    rows = [  # name, line shown, figure, goal per preset (None: not a goal there), at most, unit
        ("eco update × scan_pass", "≤ 3.0× uncapped, ≤ 2.0× capped", "eco / scan_pass",
         {"robot": 3.0, "robot-cap-0.2": 2.0, "robot-cap-0.1": 2.0}, True, "×"),
        ("pcl_octree update × eco", "≥ 4.0×", "pcl / eco", {"robot": 4.0}, False, "×"),
        ("nanoflann update × eco", "≥ 2.0×", "nanoflann / eco", {"robot-cap-0.2": 2.0}, False, "×"),
        ("eco voxel map × pcl_octree", "≤ 1.0×", "vox", dict.fromkeys(presets, 1.0), True, "×"),
        ("eco KNN × nanoflann", "≤ 1.0×", "knn", dict.fromkeys(presets, 1.0), True, "×"),
        ("bytes a held point", "≤ 24 B", "bpp", dict.fromkeys(presets, 24), True, " B"),
        ("eco update p99 / mean", "≤ 2.0×", "p99", dict.fromkeys(presets, 2.0), True, "×"),
        ("caller's work after eco × after scan_pass", "≤ 1.05×", "caller", dict.fromkeys(presets, 1.05), True, "×"),
    ]
    print("\n| goal | line | " + " | ".join(f"`{p}`" for p in presets) + " |\n|---|--:|---|---|---|")
    for name, line, key, goal, at_most, unit in rows:
        cells = [measured(figures[p][key], goal[p], at_most, unit) if p in goal else "" for p in presets]
        print(f"| {name} | {line} | " + " | ".join(cells) + " |")
    print("\n### Free-space clearing (`--preset robot-cap-0.1 --methods eco,eco_clearing --knn-queries 0`)\n")
    print("| sequence | eco update ms | eco_clearing | on / off | Chamfer m: off → on |\n|---|--:|--:|--:|--:|")
    on_off = []
    for seq in sequences():
        m = load(f"{seq}-clearing")
        if m is None:
            continue
        e, c = m["eco"], m["eco_clearing"]
        on_off.append(ratio(c["update_ms"], e["update_ms"]))
        print(f"| {label(seq)} | {e['update_ms']:.2f} | {c['update_ms']:.2f} | {on_off[-1]:.2f}× | "
              f"{e['chamfer_m']:.4f} → {c['chamfer_m']:.4f} |")
    print("\n| goal | line | measured | verdict |\n|---|--:|---|---|")
    goal_row("update with clearing × without", on_off, 2.0, True)
    paper_goals = {"static": 10.0, "dynamic": 8.0}
    for workload in ("static", "dynamic"):
        print(f"\n### The paper's {workload} workload\n")
        print("| sequence | eco update ms | eco_exact | octree_base | ioctree_target | ioctree_global | nanoflann | "
              "pcl_octree | octree_base × eco | eco_exact × octree_base | ioctree_target × eco | "
              "eco KNN × nanoflann | eco B/pt |\n|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|")
        base, exact, target, knn, bpp = [], [], [], [], []
        for seq in paper_sequences():
            m = load(f"{seq}-paper-{workload}")
            e = m["eco"]
            base.append(ratio(m["octree_base"]["update_ms"], e["update_ms"]))
            exact.append(ratio(m["eco_exact"]["update_ms"], m["octree_base"]["update_ms"]))
            target.append(ratio(m["ioctree_target"]["update_ms"], e["update_ms"]))
            knn.append(ratio(e["knn_ms"], m["nanoflann"]["knn_ms"]))
            bpp.append(e["bytes_per_point"])
            times = " | ".join(f"{m[n]['update_ms']:.2f}" for n in
                               ("eco_exact", "octree_base", "ioctree_target", "ioctree_global", "nanoflann", "pcl_octree"))
            print(f"| {label(seq)} | {e['update_ms']:.2f} | {times} | {base[-1]:.2f}× | {exact[-1]:.2f}× | "
                  f"{target[-1]:.2f}× | {knn[-1]:.2f}× | {bpp[-1]:.1f} |")
        print("\n| goal | line | measured (sequences in the table's order) | verdict |\n|---|--:|---|---|")
        goal_row("octree_base update × eco", base, paper_goals[workload], False)
        if workload == "static":
            goal_row("ioctree_target update × eco", target, 15.0, False)
        goal_row("eco KNN × nanoflann", knn, 1.0, True)
        goal_row("bytes a held point", bpp, 24, True, unit=" B")
        print(f"\neco_exact × octree_base (the paper's own algorithm): {', '.join(f'{v:.2f}×' for v in exact)}")


def paper_sequences():
    names = sorted({d.rsplit("-paper-", 1)[0] for d in os.listdir(ROOT) if "-paper-" in d})
    return [n for n in names if n != "sim"] + ["sim"]

main()

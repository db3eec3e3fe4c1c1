"""eco_node's figures on real frames: KITTI folders written as ROS 1 bags (kitti_to_bag.py), each
played at its own rate (1x, 10 Hz) by `rosbag play` into eco_node (placed by the bag's /odom),
on a roscore of its own, with a subscriber to the map as rviz would be.

  cloud received -> map published, p99 / EgoOctree::update's p99 on the same frames (~stats)
  frames dropped: clouds in the bag the node did not take (never received, or skipped)
  the node's map after the last frame / `eco run --data` on the same bag: the same points

usage: bench_node.py --eco-node BIN --eco BIN --out DIR [--cores 0] [--param name=value ...] KITTI_DIR...
Writes DIR/node.json and DIR/node.md and prints the table."""

import argparse
import json
import os
import subprocess
import sys
import threading
import time

import numpy as np
import rospy
from std_msgs.msg import String

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import kitti_to_bag  # noqa: E402
from ros_graph import Graph, stop  # noqa: E402


def percentile(values, q):
    return float(np.percentile(np.asarray(values), q)) if values else float("nan")


def saved_points(path):
    """A saved map's points (sorted rows), read by the eco Python module; None when it is not importable."""
    try:
        import eco as eco_module
    except ImportError:
        return None
    points = np.asarray(eco_module.EgoOctree.load(path).points())
    return points[np.lexsort(points.T[::-1])]


def run_one(graph, args, folder, work):
    name = os.path.basename(os.path.normpath(folder))
    bag = os.path.join(work, name + ".bag")
    frames = kitti_to_bag.main(folder, bag)
    stats, lock = [], threading.Lock()

    def on_stats(msg):
        with lock:
            stats.append(json.loads(msg.data))

    node = "eco_" + name
    subscribers = [rospy.Subscriber(f"/{node}/stats", String, on_stats, queue_size=1000),
                   rospy.Subscriber(f"/{node}/map", rospy.AnyMsg, lambda msg: None, queue_size=2)]  # sent, not decoded
    parameters = dict(cloud_topic="/points", pose_topic="/odom", fixed_frame="map", save_on_exit="true",
                      save_path=os.path.join(work, name + "_node.eco"))
    parameters.update(args.param)
    prefix = ["taskset", "-c", args.cores] if args.cores else []
    process = graph.node(args.eco_node, node, parameters, prefix)
    graph.wait_for_service(f"/{node}/save", process)
    time.sleep(1.0)
    subprocess.run(["rosbag", "play", "-q", "--wait-for-subscribers", "--delay", "0.5", bag], env=graph.env(),
                   check=True, stdout=subprocess.DEVNULL)
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        with lock:
            if len(stats) >= frames:
                break
        time.sleep(0.1)
    time.sleep(0.5)
    code = stop(process)
    for s in subscribers:
        s.unregister()
    run_args = [args.eco, "run", "--data", bag, "--pose-topic", "/odom", "--out", os.path.join(work, name + "_run"),
                "--save", os.path.join(work, name + "_run.eco")]
    for key, value in args.param.items():
        run_args += ["--" + key.replace("/", "."), value]
    subprocess.run(run_args, check=True, stdout=subprocess.DEVNULL)
    node_points = saved_points(os.path.join(work, name + "_node.eco"))
    run_points = saved_points(os.path.join(work, name + "_run.eco"))
    same = None if node_points is None else bool(np.array_equal(node_points, run_points))
    published = [s for s in stats if s["map_published"]]
    return {"sequence": name, "frames_in_bag": frames, "frames_taken": len(stats),
            "dropped": frames - len(stats), "lost_upstream": stats[-1]["lost"] if stats else None,
            "latency_ms": [s["latency_ms"] for s in published], "update_ms": [s["update_ms"] for s in stats],
            "taken_ms": [s["taken_ms"] for s in published],
            "held": stats[-1]["held"] if stats else 0, "same_points_as_eco_run": same, "exit": code}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--eco-node", required=True)
    parser.add_argument("--eco", required=True, help="the eco command, for eco run on the same bag")
    parser.add_argument("--out", required=True)
    parser.add_argument("--cores", default="", help="taskset's list for the node: 0 runs it on one core")
    parser.add_argument("--param", action="append", default=[], help="a node parameter, name=value")
    parser.add_argument("folders", nargs="+")
    args = parser.parse_args()
    args.param = dict(p.split("=", 1) for p in args.param)
    os.makedirs(args.out, exist_ok=True)
    results = []
    with Graph(os.path.join(args.out, "graph")) as graph:
        rospy.init_node("eco_bench", anonymous=True, disable_signals=True)
        for folder in args.folders:
            results.append(run_one(graph, args, folder, args.out))
    latency = [v for r in results for v in r["latency_ms"]]
    update = [v for r in results for v in r["update_ms"]]
    summary = {"command": " ".join(sys.argv), "cores": args.cores or "all", "parameters": args.param,
               "frames": sum(r["frames_in_bag"] for r in results), "dropped": sum(r["dropped"] for r in results),
               "latency_p50_ms": percentile(latency, 50), "latency_p99_ms": percentile(latency, 99),
               "update_p50_ms": percentile(update, 50), "update_p99_ms": percentile(update, 99),
               "same_points_as_eco_run": all(r["same_points_as_eco_run"] for r in results), "runs": results}
    summary["latency_over_update_p99"] = summary["latency_p99_ms"] / summary["update_p99_ms"]
    with open(os.path.join(args.out, "node.json"), "w") as f:
        json.dump(summary, f, indent=1)
    table = ["| sequence | frames | dropped | held | update p99 ms | received → published p99 ms | same points as eco run |",
             "|---|---|---|---|---|---|---|"]
    for r in results:
        table.append(f"| {r['sequence']} | {r['frames_in_bag']} | {r['dropped']} | {r['held']} | "
                     f"{percentile(r['update_ms'], 99):.1f} | {percentile(r['latency_ms'], 99):.1f} | "
                     f"{'yes' if r['same_points_as_eco_run'] else 'no'} |")
    table.append(f"| all | {summary['frames']} | {summary['dropped']} | | {summary['update_p99_ms']:.1f} | "
                 f"{summary['latency_p99_ms']:.1f} ({summary['latency_over_update_p99']:.2f}×) | |")
    text = "\n".join(table) + "\n"
    with open(os.path.join(args.out, "node.md"), "w") as f:
        f.write(f"`{summary['command']}` (node on cores: {summary['cores']})\n\n" + text)
    print(text)


if __name__ == "__main__":
    main()

"""eco_node as a process on a real roscore (ros/scripts/ros_graph.py), fed by `rosbag play` of a bag
written by Debian's rosbag (write_drive_bag.py) or by this script's own publishers.

usage: node_test.py CASE ECO_NODE ECO_CLI KITTI_DIR WORK_DIR
  same_points     a pose-topic node and a tf node on one bag: their last published maps and saved
                  maps (~save, save_on_exit on SIGINT) hold what `eco run --data` holds
  waits_for_tf    a cloud before its tf is held back and taken once tf comes; one whose tf never
                  comes is skipped after ~tf_timeout with a warning; nothing lost silently
  bad_parameters  a bad value, an unknown name and a rule between fields stop the node at start,
                  named
  odometry        ~odometry: true publishes a pose (~odom and tf) for every cloud and maps them
  launch          the README's roslaunch of launch/eco.launch on a bag (ROS_PACKAGE_PATH: the build's
                  ros/ folder) maps every cloud; rviz's configuration shows the topics the node sends
Prints "ok" when every check holds."""

import json
import os
import subprocess
import sys
import threading
import time

import numpy as np
import rospy
from sensor_msgs.msg import PointCloud2, PointField
from std_msgs.msg import String
from std_srvs.srv import Trigger

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "ros", "scripts"))
from ros_graph import Graph, stop  # noqa: E402

case, ECO_NODE, ECO_CLI, KITTI, WORK = sys.argv[1:6]
FRAMES = 5
MAP = {"box_side": 40, "density_cap/cell_size": 0.2, "density_cap/max_points": 2}


def check(condition, what):
    if not condition:
        raise SystemExit("FAILED: " + what)


def cloud_points(msg):
    """A published cloud's x, y, z (float32) as rows."""
    names = [f.name for f in msg.fields]
    dtype = np.dtype({"names": names, "formats": ["<f4"] * len(names), "offsets": [f.offset for f in msg.fields],
                      "itemsize": msg.point_step})
    rows = np.frombuffer(msg.data, dtype=dtype)
    return np.stack([rows["x"], rows["y"], rows["z"]], axis=1)


def sorted_rows(points):
    points = np.asarray(points)
    return points[np.lexsort(points.T[::-1])]


def differing(a, b):
    """Points of `a` not within 1e-5 m of one of `b`, and the other way round."""
    from scipy.spatial import cKDTree
    return int((cKDTree(b).query(a)[0] > 1e-5).sum() + (cKDTree(a).query(b)[0] > 1e-5).sum())


def map_points(path):
    """The points a saved map holds (the eco Python module reads it)."""
    import eco
    return sorted_rows(eco.EgoOctree.load(path).points())


class Listener:
    """The last message on a topic and every stats line, from this process's rospy node."""

    def __init__(self, node):
        self.last_map, self.stats, self.lock = None, [], threading.Lock()
        self.topics = [rospy.Subscriber(f"/{node}/map", PointCloud2, self._map, queue_size=10),
                       rospy.Subscriber(f"/{node}/stats", String, self._stats, queue_size=1000)]

    def wait_connected(self, timeout=30):
        """Until the node's publishers have connected to these subscribers: what it sends next arrives."""
        deadline = time.monotonic() + timeout
        while any(t.get_num_connections() == 0 for t in self.topics):
            if time.monotonic() > deadline:
                raise SystemExit(f"FAILED: not connected to the node's topics within {timeout} s")
            time.sleep(0.02)

    def _map(self, msg):
        with self.lock:
            self.last_map = msg

    def _stats(self, msg):
        with self.lock:
            self.stats.append(json.loads(msg.data))

    def wait_frames(self, n, timeout=60):
        """Until the stats and the map of the node's frame n - 1 (its n-th) have come."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            with self.lock:
                if self.stats and self.stats[-1]["frame"] >= n - 1 and self.last_map is not None and \
                        self.last_map.header.stamp.to_sec() >= self.stats[-1]["stamp"] - 1e-6:
                    return
            time.sleep(0.05)
        raise SystemExit(f"FAILED: frames {[s['frame'] for s in self.stats]} of {n} within {timeout} s")


def eco_run(bag, out, *pose_flags):
    args = [ECO_CLI, "run", "--data", bag, *pose_flags, "--out", out, "--save", os.path.join(out, "map.eco")]
    for name, value in MAP.items():
        args += ["--" + name.replace("/", "."), str(value)]
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
    return map_points(os.path.join(out, "map.eco"))


def same_points(graph):
    bag = os.path.join(WORK, "drive.bag")
    subprocess.run(["/usr/bin/python3", os.path.join(os.path.dirname(__file__), "write_drive_bag.py"), KITTI, bag,
                    str(FRAMES)], check=True, stdout=subprocess.DEVNULL)
    rospy.init_node("eco_test", anonymous=True, disable_signals=True)
    by_topic = dict(MAP, cloud_topic="/points", pose_topic="/odom", save_on_exit="true",
                    save_path=os.path.join(WORK, "by_topic.eco"))
    by_tf = dict(MAP, cloud_topic="/points", fixed_frame="map", save_on_exit="true", save_path=os.path.join(WORK, "by_tf.eco"))
    nodes = {"by_topic": graph.node(ECO_NODE, "by_topic", by_topic), "by_tf": graph.node(ECO_NODE, "by_tf", by_tf)}
    listeners = {name: Listener(name) for name in nodes}
    for name, process in nodes.items():
        graph.wait_for_service(f"/{name}/save", process)  # its publishers are there
        listeners[name].wait_connected()
    subprocess.run(["rosbag", "play", "-q", "--wait-for-subscribers", "--delay", "0.5", bag], env=graph.env(), check=True, stdout=subprocess.DEVNULL)
    for listener in listeners.values():
        listener.wait_frames(FRAMES)

    want = eco_run(bag, os.path.join(WORK, "run_by_topic"), "--pose-topic", "/odom")
    listener = listeners["by_topic"]
    check([s["frame"] for s in listener.stats] == list(range(FRAMES)), f"frames {[s['frame'] for s in listener.stats]}")
    check(all(s["lost"] == 0 and s["skipped"] == 0 and s["refused"] == 0 for s in listener.stats), "a cloud lost or skipped")
    published = sorted_rows(cloud_points(listener.last_map))
    check(listener.last_map.header.frame_id == "map", "the map's frame " + listener.last_map.header.frame_id)
    check(len(want) > 1000 and published.shape == want.shape, f"published {published.shape}, eco run {want.shape}")
    check(np.array_equal(published, sorted_rows(want.astype(np.float32))), "the published map differs from eco run's")
    response = rospy.ServiceProxy("/by_topic/save", Trigger)()
    check(response.success, "~save: " + response.message)
    check(np.array_equal(map_points(os.path.join(WORK, "by_topic.eco")), want), "~save's map differs from eco run's")
    os.remove(os.path.join(WORK, "by_topic.eco"))

    want_tf = eco_run(bag, os.path.join(WORK, "run_by_tf"), "--pose-topic", "tf", "--fixed-frame", "map")
    # tf2 interpolates otherwise than eco::io::TransformTree (to the last bits), and a placed point
    # that rounds to the other float of a density cell's wall may change what the cell keeps: a few
    # points in 10^4 may differ, none by more than a cell
    published_tf = cloud_points(listeners["by_tf"].last_map)
    differ = differing(published_tf, want_tf.astype(np.float32))
    check(differ <= 1e-4 * len(want_tf), f"the tf node's map differs from eco run's in {differ} of {len(want_tf)} points")

    for name, process in nodes.items():
        check(stop(process) == 0, f"{name} did not stop cleanly on SIGINT:\n" + graph.log_of(name))
        check("saved the map" in graph.log_of(name), name + " did not say it saved")
    check(np.array_equal(map_points(os.path.join(WORK, "by_topic.eco")), want), "the map saved on exit differs")
    check(differing(map_points(os.path.join(WORK, "by_tf.eco")), want_tf) <= 1e-4 * len(want_tf),
          "the tf node's saved map differs")


def small_cloud(seq, stamp, frame):
    xyz = np.array([[5.0 + 0.5 * i, 1.0, 0.5] for i in range(10)], dtype="<f4")
    msg = PointCloud2()
    msg.header.seq, msg.header.stamp, msg.header.frame_id = seq, stamp, frame
    msg.height, msg.width = 1, len(xyz)
    msg.fields = [PointField(n, 4 * i, PointField.FLOAT32, 1) for i, n in enumerate("xyz")]
    msg.point_step, msg.row_step, msg.is_dense = 12, 12 * len(xyz), True
    msg.data = xyz.tobytes()
    return msg


def waits_for_tf(graph):
    from geometry_msgs.msg import TransformStamped
    from tf2_msgs.msg import TFMessage
    rospy.init_node("eco_test", anonymous=True, disable_signals=True)
    process = graph.node(ECO_NODE, "waiting", {"cloud_topic": "/points", "fixed_frame": "map", "tf_timeout": 1.5})
    listener = Listener("waiting")
    clouds = rospy.Publisher("/points", PointCloud2, queue_size=10)
    transforms = rospy.Publisher("/tf", TFMessage, queue_size=10)
    graph.wait_for_service("/waiting/save", process)
    while clouds.get_num_connections() == 0 or transforms.get_num_connections() == 0:
        time.sleep(0.05)
    listener.wait_connected()

    def tf(stamp, x):
        t = TransformStamped()
        t.header.stamp, t.header.frame_id, t.child_frame_id = stamp, "map", "lidar"
        t.transform.translation.x, t.transform.rotation.w = x, 1.0
        return t

    t0 = rospy.Time(1000)
    clouds.publish(small_cloud(0, t0, "lidar"))  # before any tf
    time.sleep(0.5)
    check(not listener.stats, "a cloud was taken before its tf came")
    transforms.publish(TFMessage([tf(t0 - rospy.Duration(0.1), 0.0), tf(t0 + rospy.Duration(0.1), 2.0)]))
    listener.wait_frames(1, timeout=10)
    check(listener.stats[0]["waited_ms"] >= 400, f"waited {listener.stats[0]['waited_ms']} ms")
    check(np.allclose(cloud_points(listener.last_map)[:, 0].min(), 6.0), "the held-back cloud was placed at x = 1")

    clouds.publish(small_cloud(1, t0 + rospy.Duration(0.05), "nowhere"))  # its tf never comes
    clouds.publish(small_cloud(2, t0 + rospy.Duration(0.05), "lidar"))
    listener.wait_frames(2, timeout=10)
    check(listener.stats[1]["skipped"] == 1, f"stats {listener.stats[1]}")
    check(listener.stats[1]["waited_ms"] >= 1400, "the next cloud did not wait behind the skipped one")
    clouds.impl.seq += 2  # rospy numbers what it sends: two clouds lost on the way, as a full queue drops them
    clouds.publish(small_cloud(5, t0 + rospy.Duration(0.06), "lidar"))
    listener.wait_frames(3, timeout=10)
    check(listener.stats[2]["lost"] == 2, f"stats {listener.stats[2]}")
    check(stop(process) == 0, "the node did not stop cleanly:\n" + graph.log_of("waiting"))
    log = graph.log_of("waiting")
    check("skipped, no pose" in log and "nowhere" in log, "no warning named the skipped cloud:\n" + log)
    check("never reached the node" in log, "no warning of the clouds lost upstream:\n" + log)
    check("3 frames taken; 1 clouds skipped" in log, "the summary:\n" + log)


def bad_parameters(graph):
    for parameters, said in [({"box_side": -3}, "~box_side = -3"),
                             ({"box_sid": 30}, "~box_sid is not a parameter of eco_node: did you mean ~box_side?"),
                             ({"insert_policy": "Sideways"}, "~insert_policy = Sideways"),
                             ({"density_cap/cell_size": "abc"}, "~density_cap/cell_size = abc"),
                             ({"tf_timeout": 0}, "~tf_timeout = 0"),
                             ({"max_age_seconds": 2}, "max_age_seconds"),
                             ({"odometry_voxel_size": -1}, "~odometry_voxel_size = -1")]:
        name = "bad_" + str(len(said))
        process = graph.node(ECO_NODE, name, parameters)
        code = process.wait(timeout=30)
        log = graph.log_of(name)
        check(code == 2, f"{parameters}: exit {code}\n{log}")
        check(said in log, f"{parameters}: the message does not name it:\n{log}")
        subprocess.run(["rosparam", "delete", f"/{name}"], env=graph.env(), stderr=subprocess.DEVNULL)


def launch(graph):
    import yaml
    bag = os.path.join(WORK, "drive.bag")
    subprocess.run(["/usr/bin/python3", os.path.join(os.path.dirname(__file__), "write_drive_bag.py"), KITTI, bag,
                    str(FRAMES)], check=True, stdout=subprocess.DEVNULL)
    rospy.init_node("eco_test", anonymous=True, disable_signals=True)
    listener = Listener("eco")
    env = graph.env()
    env["ROS_PACKAGE_PATH"] = os.path.join(os.path.dirname(os.path.dirname(ECO_NODE)), "ros") + ":/usr/share"
    log = open(os.path.join(WORK, "roslaunch.log"), "w")
    roslaunch = subprocess.Popen(["roslaunch", "eco_ros", "eco.launch", f"bag:={bag}", "cloud_topic:=/points",
                                  "pose_topic:=/odom", "rviz:=false"], env=env, stdout=log, stderr=subprocess.STDOUT)
    graph.started.append(roslaunch)
    listener.wait_frames(FRAMES)  # the node's counts are since it started: this test may join it late
    check(listener.stats[-1]["skipped"] == 0 and listener.stats[-1]["lost"] == 0, f"stats {listener.stats[-1]}")
    published = {t for t, _ in rospy.get_published_topics()}
    with open(os.path.join(os.path.dirname(os.path.dirname(ECO_NODE)), "ros", "eco_ros", "rviz", "eco.rviz")) as f:
        rviz = yaml.safe_load(f)
    shown = [d.get("Topic", d.get("Marker Topic")) for d in rviz["Visualization Manager"]["Displays"]]
    shown = [t for t in shown if t]
    check(sorted(shown) == ["/eco/map", "/eco/region", "/eco/voxels"], f"rviz shows {shown}")
    check(set(shown) <= published, f"rviz shows {shown}; the node publishes {sorted(published)}")
    check(stop(roslaunch) == 0, "roslaunch did not stop cleanly")
    log.close()
    with open(log.name) as f:
        said = f.read()
    check(f"{FRAMES} frames taken; 0 clouds skipped" in said, "every cloud of the bag taken:\n" + said)


def odometry(graph):
    bag = os.path.join(WORK, "drive.bag")
    subprocess.run(["/usr/bin/python3", os.path.join(os.path.dirname(__file__), "write_drive_bag.py"), KITTI, bag,
                    str(FRAMES)], check=True, stdout=subprocess.DEVNULL)
    from nav_msgs.msg import Odometry
    rospy.init_node("eco_test", anonymous=True, disable_signals=True)
    process = graph.node(ECO_NODE, "odo", dict(MAP, cloud_topic="/points", odometry="true", fixed_frame="odom", odometry_deskew="false"))
    listener = Listener("odo")
    poses = []
    odom = rospy.Subscriber("/odo/odom", Odometry, poses.append, queue_size=100)
    graph.wait_for_service("/odo/save", process)
    listener.wait_connected()
    while odom.get_num_connections() == 0:
        time.sleep(0.02)
    subprocess.run(["rosbag", "play", "-q", "--wait-for-subscribers", "--delay", "0.5", bag, "--topics", "/points"], env=graph.env(), check=True,
                   stdout=subprocess.DEVNULL)
    listener.wait_frames(FRAMES)
    deadline = time.monotonic() + 10
    while len(poses) < FRAMES and time.monotonic() < deadline:  # sent before the stats, on another connection
        time.sleep(0.02)
    check(len(poses) == FRAMES, f"{len(poses)} poses for {FRAMES} clouds")
    check(all(p.header.frame_id == "odom" and p.child_frame_id == "lidar" for p in poses), "the poses' frames")
    first = poses[0].pose.pose
    check(first.position.x == 0 and first.orientation.w == 1, "the first pose is not the start")
    # the simulated drive's own motion (the scans' points are its; the bag's made-up times are not
    # the sweep's, so the odometry does not deskew): the distance it went, to within 0.2 m
    rows = np.loadtxt(os.path.join(KITTI, "poses.txt"))[:FRAMES]
    went = np.linalg.norm(rows[-1, [3, 7, 11]] - rows[0, [3, 7, 11]])
    last = poses[-1].pose.pose.position
    check(abs(np.linalg.norm([last.x, last.y, last.z]) - went) < 0.2, f"the last pose {last}, the drive went {went} m")
    check(listener.stats[-1]["held"] > 1000, "the map holds nothing")
    check(stop(process) == 0, "the node did not stop cleanly:\n" + graph.log_of("odo"))


with Graph(WORK) as graph:
    {"same_points": same_points, "waits_for_tf": waits_for_tf, "bad_parameters": bad_parameters,
     "odometry": odometry, "launch": launch}[case](graph)
print("ok")

"""eco.io.open: what --data reads, from Python. An MCAP recording written by foxglove's writer
(tests/io/recordings/) gives each cloud's points, intensities and per-point times as its writer
put them; a KITTI folder and a folder of PCD files give the same frames; bad arguments and paths
are refused by name."""

import json
import os
from pathlib import Path

import numpy as np
import pytest

import eco

RECORDINGS = Path(os.environ.get("ECO_RECORDINGS", ""))


@pytest.fixture(scope="module")
def expected():
    if not (RECORDINGS / "expected.json").exists():
        pytest.fail("ECO_RECORDINGS names no folder of test recordings (tests/io/recordings/write_recordings.sh)")
    return json.loads((RECORDINGS / "expected.json").read_text())


def test_a_recording_yields_its_clouds_as_written(expected):
    source = eco.io.open(RECORDINGS / "hesai.mcap")
    want = expected["hesai.mcap"]["/hesai/points"]["clouds"]
    assert len(source) == len(want) and not source.has_poses
    assert "timestamp in s, absolute" in source.description
    for i, (pose, points) in enumerate(source):
        np.testing.assert_array_equal(pose, np.eye(4))
        np.testing.assert_array_equal(points, np.array(want[i]["points"], dtype=np.float32))
        scan = source.read(i)
        assert scan.time == int(want[i]["stamp_ns"]) * 1e-9
        np.testing.assert_array_equal(scan.intensity, np.array(want[i]["intensities"], dtype=np.float32))
        np.testing.assert_array_equal(scan.point_times, np.array(want[i]["times"]))


def test_a_pose_topic_places_the_clouds():
    source = eco.io.open(RECORDINGS / "posed.mcap", pose_topic="/odom")
    assert source.has_poses and len(source) == 4
    np.testing.assert_allclose([pose[0, 3] for pose, _ in source], [0.0, 1.0, 2.0, 3.0], atol=1e-5)
    assert eco.io.open(RECORDINGS / "posed.mcap").pose_topics == ["/odom (nav_msgs/msg/Odometry)",
                                                                  "/pose (geometry_msgs/msg/PoseStamped)"]


def test_tf_places_the_clouds_and_their_points(expected):
    # tf.mcap: odom -> base_link at x = 10 m/s * t, base_link -> lidar at (1, 0, 2) turned 90 degrees
    source = eco.io.open(RECORDINGS / "tf.mcap", pose_topic="tf", fixed_frame="odom")
    assert "poses: tf: odom -> base_link -> lidar" in source.description
    np.testing.assert_allclose([pose[:3, 3] for pose, _ in source][0], [1.0, 0.0, 2.0], atol=1e-5)
    placed, seen = source.read(3), eco.io.open(RECORDINGS / "tf.mcap", pose_topic="tf", place_points=False).read(3)
    assert placed.point_times is None and len(seen.point_times) == len(seen.points)
    np.testing.assert_array_equal(seen.points, np.array(expected["tf.mcap"]["/points"]["clouds"][3]["points"], dtype=np.float32))
    # the first point, seen at the stamp, stays; the last, seen 0.1 s later, moves by the sensor's motion
    # meanwhile (1 m forward, sideways in the LiDAR's turned frame, and 0.05 rad; recording_test.cpp has it exactly)
    np.testing.assert_allclose(placed.points[0], seen.points[0], atol=1e-6)
    assert 0.3 < np.linalg.norm(placed.points[-1] - seen.points[-1]) < 1.5
    with pytest.raises(eco.io.Error, match="no chain of transforms joins gps and lidar"):
        eco.io.open(RECORDINGS / "tf.mcap", pose_topic="tf", fixed_frame="gps")


def test_topic_and_time_options(expected):
    rear = eco.io.open(RECORDINGS / "two_lidars.mcap", topic="/rear/points")
    assert len(rear) == 2
    forced = eco.io.open(RECORDINGS / "velodyne.mcap", time_field="ring", time_unit="us")
    assert forced.read(0).point_times.max() < 32e-6
    with pytest.raises(eco.io.Error, match="several PointCloud2 topics"):
        eco.io.open(RECORDINGS / "two_lidars.mcap")
    with pytest.raises(ValueError, match="time_unit = 'minutes'"):
        eco.io.open(RECORDINGS / "velodyne.mcap", time_unit="minutes")
    with pytest.raises(TypeError, match="topic must be a str or None"):
        eco.io.open(RECORDINGS / "velodyne.mcap", topic=3)
    with pytest.raises(eco.io.Error, match="nowhere: no such file or folder"):
        eco.io.open("nowhere")


def test_a_kitti_folder_and_pcd_files_give_the_same_frames(tmp_path):
    simulator = eco.sim.Simulator(frames=3, seed=5, lidar={"beams": 16, "columns": 300})
    simulator.write_kitti(tmp_path / "kitti")
    (tmp_path / "pcd").mkdir()
    poses = []
    for i, (pose, points) in enumerate(simulator):
        eco.io.write_pcd(tmp_path / "pcd" / f"{i:04d}.pcd", points)
        poses.append(pose)
    with open(tmp_path / "poses.txt", "w") as f:
        for pose in poses:
            f.write(" ".join(repr(v) for v in pose[:3].reshape(-1)) + "\n")
    pcd = eco.io.open(tmp_path / "pcd", poses=tmp_path / "poses.txt")
    kitti = eco.io.open(tmp_path / "kitti")
    assert pcd.has_poses and kitti.has_poses and len(pcd) == len(kitti) == 3
    assert kitti.warnings == []  # the simulator writes calib.txt beside its camera-frame poses
    for i in range(3):
        np.testing.assert_allclose(pcd[i][0], poses[i], atol=1e-12)
        np.testing.assert_allclose(kitti[i][0], poses[i], atol=1e-9)
        np.testing.assert_array_equal(pcd[i][1], simulator[i][1])
        np.testing.assert_array_equal(kitti[i][1], simulator[i][1])

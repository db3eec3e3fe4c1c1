"""The odometry from Python: a simulated drive tracked to centimetres with both maps Python has,
the frame reports and poses as numpy, the trajectory errors against hand-worked figures, and bad
input refused by name (points not finite are skipped and counted, not refused)."""

import numpy as np
import pytest

import eco


def drive(frames=20):
    return eco.sim.Simulator(frames=frames, seed=4)


@pytest.mark.parametrize("map_name", eco.odometry.map_names())
def test_a_simulated_drive_is_tracked_to_centimetres(map_name):
    odo = eco.odometry.Odometry(map=map_name)
    simulator = drive()
    odo.set_start(simulator.pose(0))
    reference = []
    for pose, points in simulator:
        report = odo.register_frame(points)
        reference.append(pose)
        assert report.index == len(reference) - 1
        assert report.registered == (report.index > 0)
        assert report.scan_points == len(points) and report.map_points == odo.map_size
        assert report.pose.shape == (4, 4)
    poses = odo.poses
    assert poses.shape == (20, 4, 4) and poses.dtype == np.float64
    np.testing.assert_array_equal(poses[-1], report.pose)
    errors = eco.odometry.trajectory_errors(poses, reference)
    assert errors["frames"] == 20 and errors["by_length"] == []  # 19 m: no 100 m segment
    assert errors["ate_rmse"] < 0.05 and errors["rpe_rotation_rmse_deg"] < 0.1


def test_trajectory_errors_of_a_stretched_straight_drive():
    reference = [np.eye(4) for _ in range(300)]
    for i, pose in enumerate(reference):
        pose[0, 3] = float(i)
    estimate = [pose.copy() for pose in reference]
    for pose in estimate:
        pose[:3, 3] *= 1.02
    errors = eco.odometry.trajectory_errors(estimate, reference)
    assert [s["length"] for s in errors["by_length"]] == [100.0, 200.0]
    assert errors["translation_pct"] == pytest.approx(2.0, abs=1e-9)
    assert errors["rpe_translation_rmse"] == pytest.approx(0.02, abs=1e-9)


def test_settings_reports_and_bad_input():
    odo = eco.odometry.Odometry(max_range=60.0, voxel_size=0.6)
    assert odo.config.voxel_size == 0.6 and odo.config.to_dict()["max_range"] == 60.0
    points = np.array([[5.0, 0.0, 0.0], [np.nan, 1.0, 1.0], [0.5, 0.0, 0.0], [90.0, 0.0, 0.0]])
    report = odo.register_frame(points)
    assert (report.dropped_invalid, report.dropped_range, report.map_input) == (1, 2, 1)
    empty = odo.register_frame(np.zeros((0, 3)))
    assert not empty.registered and empty.source == 0
    with pytest.raises(ValueError, match="voxel_size"):
        eco.odometry.Odometry(voxel_size=-1.0)
    with pytest.raises(TypeError, match="neighbours"):
        eco.odometry.Odometry(neighbours="five")
    with pytest.raises(ValueError, match="kdtree"):
        eco.odometry.Odometry(map="kdtree")
    with pytest.raises(ValueError, match="points"):
        odo.register_frame(np.zeros((4, 2)))
    with pytest.raises(ValueError, match="before the first frame"):
        odo.set_start(np.eye(4))
    with pytest.raises(ValueError, match="same frames"):
        eco.odometry.trajectory_errors([np.eye(4)] * 3, [np.eye(4)] * 4)


def test_point_times_deskew_a_smeared_sweep():
    simulator = eco.sim.Simulator(frames=12, seed=2, speed=15.0, lidar={"beams": 32, "columns": 1000, "rolling_sweep": True})
    odo = eco.odometry.Odometry(map="eco")
    odo.set_start(simulator.pose(0))
    reports = [odo.register_frame(scan.points, scan.point_times) for scan in (simulator.frame(i) for i in range(12))]
    assert [r.deskewed for r in reports] == [False] + [True] * 11
    errors = eco.odometry.trajectory_errors(odo.poses, [simulator.pose(i) for i in range(12)])
    assert errors["ate_rmse"] < 0.05
    with pytest.raises(ValueError, match="times must have shape"):
        odo.register_frame(simulator.frame(0).points, np.zeros(3))
    assert eco.odometry.Odometry(map="eco", deskew=False).config.deskew is False

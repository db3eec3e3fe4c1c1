"""The simulator and the readers from Python: frames as (pose, points) numpy pairs, a simulated
sequence written in KITTI's layout and read back, the real KITTI frames streamed into a tree."""

import numpy as np
import pytest

import eco
from scipy_oracle import check_against_scipy


def tiny(**fields):
    return eco.sim.Simulator(frames=4, lidar={"beams": 16, "columns": 300}, **fields)


def test_simulator_yields_pose_points_pairs():
    simulator = tiny()
    frames = list(simulator)
    assert len(frames) == len(simulator) == 4
    for pose, points in frames:
        assert pose.shape == (4, 4) and pose.dtype == np.float64
        assert points.ndim == 2 and points.shape[1] == 3 and points.dtype == np.float32
        assert points.flags["C_CONTIGUOUS"] and len(points) > 1000
        np.testing.assert_allclose(pose[:3, :3].T @ pose[:3, :3], np.eye(3), atol=1e-12)
    np.testing.assert_array_equal(frames[2][0], simulator.pose(2))


def test_simulator_is_deterministic_and_seeded():
    a, b, c = tiny(seed=3), tiny(seed=3), tiny(seed=4)
    np.testing.assert_array_equal(a[1][1], b[1][1])
    assert a[1][1].shape != c[1][1].shape or not np.array_equal(a[1][1], c[1][1])


def test_a_manoeuvre_by_name_spins_in_place():
    sim = eco.sim.Simulator(frames=5, manoeuvre="spin", spin_rate_deg=100.0, sway_deg=0.0,
                            lidar={"beams": 8, "columns": 100})
    assert sim.config.manoeuvre == eco.sim.Manoeuvre.spin
    poses = [pose for pose, _ in sim]
    for a, b in zip(poses, poses[1:]):
        np.testing.assert_array_equal(a[:3, 3], b[:3, 3])
        turned = np.degrees(np.arctan2(b[1, 0], b[0, 0]) - np.arctan2(a[1, 0], a[0, 0]))
        assert (turned + 180.0) % 360.0 - 180.0 == pytest.approx(10.0)
    with pytest.raises(ValueError):
        eco.sim.Simulator(frames=5, manoeuvre="backflip")


def test_simulated_frame_carries_time_reflectance_and_labels():
    scan = tiny().frame(3)
    assert scan.index == 3 and scan.time == pytest.approx(0.3)
    assert scan.intensity.shape == (len(scan.points),) and scan.intensity.dtype == np.float32
    assert scan.labels.shape == (len(scan.points),) and scan.labels.dtype == np.uint32
    assert 40 in set(scan.labels.tolist())  # the road


def test_written_sequence_reads_back(tmp_path):
    simulator = tiny()
    simulator.write_kitti(tmp_path / "seq")
    sequence = eco.io.KittiSequence(tmp_path / "seq")
    assert len(sequence) == len(simulator) and sequence.poses_were_camera_frame and sequence.has_labels
    assert sequence.poses.shape == (4, 4, 4) and sequence.times.shape == (4,)
    for index, ((pose, points), (sim_pose, sim_points)) in enumerate(zip(sequence, simulator)):
        np.testing.assert_array_equal(points, sim_points)
        np.testing.assert_allclose(pose, sim_pose, atol=1e-9)
        np.testing.assert_array_equal(sequence.read(index).labels, simulator.frame(index).labels)
    np.testing.assert_array_equal(eco.io.read_kitti_poses(tmp_path / "seq" / "poses.txt").shape, (4, 4, 4))
    points, reflectance = eco.io.read_kitti_scan(tmp_path / "seq" / "velodyne" / "000001.bin")
    np.testing.assert_array_equal(points, simulator[1][1])
    assert reflectance.shape == (len(points),)


@pytest.mark.parametrize("write, read", [(eco.io.write_ply, eco.io.read_ply),
                                         (eco.io.write_pcd, eco.io.read_pcd)])
def test_point_files_round_trip(tmp_path, write, read):
    rng = np.random.default_rng(1)
    points = rng.normal(size=(100, 3)).astype(np.float32)
    intensity = rng.uniform(size=100).astype(np.float32)
    write(tmp_path / "cloud", points, intensity=intensity)
    got_points, got_intensity = read(tmp_path / "cloud")
    np.testing.assert_array_equal(got_points, points)
    np.testing.assert_array_equal(got_intensity, intensity)
    write(tmp_path / "plain", points.astype(np.float64))
    got_points, got_intensity = read(tmp_path / "plain")
    np.testing.assert_array_equal(got_points, points)
    assert got_intensity is None


@pytest.mark.parametrize("name", ["kitti_mini_00", "kitti_mini_02", "kitti_mini_08", "balm2_realworld_f20-99"])
def test_real_sequence_streams_and_matches_scipy(shared_dataset, name):
    sequence = eco.io.KittiSequence(shared_dataset(name))
    assert len(sequence) >= 10
    tree = eco.EgoOctree(insert_policy="AllInBox", density_cap={"cell_size": 0.1, "max_points": 2})
    rng = np.random.default_rng(5)
    frames = list(range(0, len(sequence), max(1, len(sequence) // 10)))
    for index in frames:
        pose, points = sequence[index]
        assert points.dtype == np.float32 and len(points) > 10000
        stats = tree.update(pose, points)
        assert stats.inserted > 0 and tree.check_invariants() == ""
    check_against_scipy(tree, rng, queries=60)
    lo, hi = tree.ego_box
    np.testing.assert_allclose((lo + hi) / 2, sequence.poses[frames[-1]][:3, 3], atol=1e-9)


def test_iterating_reads_only_poses_and_scans(tmp_path):
    tiny().write_kitti(tmp_path / "seq")
    (tmp_path / "seq" / "labels" / "000001.label").write_bytes(b"\x00")  # a broken label file
    sequence = eco.io.KittiSequence(tmp_path / "seq")
    assert len(sequence[1][1]) > 1000  # (pose, points): labels are not opened
    with pytest.raises(eco.io.Error, match="000001.label"):
        sequence.read(1)  # the whole Scan reads them, and names the file at fault

"""Bad input raises TypeError or ValueError naming the argument, and leaves the tree unchanged."""

import numpy as np
import pytest

import eco

GOOD_POINTS = np.array([[1.0, 2.0, 0.5], [-3.0, 1.0, 0.0], [4.0, -4.0, 1.0]], dtype=np.float32)


@pytest.fixture
def tree():
    tree = eco.EgoOctree(insert_policy="AllInBox")
    tree.update(np.eye(4), GOOD_POINTS)
    return tree


def snapshot(tree):
    return len(tree), tree.frame_count, tree.pose.tolist(), sorted(map(tuple, tree.points().tolist()))


def rejects(error, *words):
    """pytest.raises whose message must name every one of `words`."""
    return pytest.raises(error, match="(?s)" + "".join(f"(?=.*{w})" for w in words))


# --- update: points ---------------------------------------------------------------------------

@pytest.mark.parametrize("points, error, words", [
    (GOOD_POINTS.astype(np.complex128), TypeError, ["points", "real numbers", "complex128"]),
    (GOOD_POINTS > 0, TypeError, ["points", "real numbers", "bool"]),
    (GOOD_POINTS[:, :2].copy(), ValueError, ["points", r"\(N, 3\)", r"\(3, 2\)"]),
    (GOOD_POINTS.reshape(-1), ValueError, ["points", r"\(9,\)"]),
    (GOOD_POINTS[None], ValueError, ["points", r"\(1, 3, 3\)"]),
    ("1 2 3", TypeError, ["points", "numpy array", "str"]),
    ({"x": 1}, TypeError, ["points", "dict"]),
    ([["a", "b", "c"]], TypeError, ["points", "list of numbers"]),
])
def test_bad_points_are_refused_and_the_tree_is_unchanged(tree, points, error, words):
    before = snapshot(tree)
    with rejects(error, *words):
        tree.update(np.eye(4), points)
    assert snapshot(tree) == before


def test_non_finite_points_are_skipped_and_counted_not_raised(tree):
    points = np.array([[1, 1, 1], [np.nan, 0, 0], [0, np.inf, 0], [2, 2, 2]], dtype=np.float64)
    stats = tree.update(np.eye(4), points)
    assert stats.skipped_nonfinite == 2 and stats.scan_points == 4


def test_lists_of_points_are_taken_as_float64(tree):
    stats = tree.update(np.eye(4), [[0.25, 0.5, 0.75]])
    assert stats.inserted == 1


def test_empty_scan_is_fine(tree):
    stats = tree.update(np.eye(4), np.zeros((0, 3), dtype=np.float32))
    assert stats.scan_points == 0 and len(tree) == 3


# --- update: pose -----------------------------------------------------------------------------

def rotation_z(angle):
    c, s = np.cos(angle), np.sin(angle)
    pose = np.eye(4)
    pose[:2, :2] = [[c, -s], [s, c]]
    return pose


@pytest.mark.parametrize("pose, words", [
    (np.eye(3), ["pose", "4x4", r"\(3, 3\)"]),
    (np.eye(4)[None], ["pose", r"\(1, 4, 4\)"]),
    (np.vstack([np.full((3, 4), np.nan), [[0, 0, 0, 1]]]), ["pose", "not finite"]),
    (np.full((4, 4), np.nan), ["pose", "last row"]),
    (np.diag([2.0, 1.0, 1.0, 1.0]), ["pose", "orthonormal"]),
    (np.diag([-1.0, 1.0, 1.0, 1.0]), ["pose", "orthonormal"]),  # a reflection
    (np.vstack([np.eye(4)[:3], [[0, 0, 1, 1]]]), ["pose", r"last row \[0, 0, 0, 1\], got \[0, 0, 1, 1\]"]),
])
def test_bad_poses_are_refused_and_the_tree_is_unchanged(tree, pose, words):
    before = snapshot(tree)
    with rejects(ValueError, *words):
        tree.update(pose, GOOD_POINTS)
    with rejects(ValueError, *[w.replace("pose", "motion") for w in words]):
        tree.update_relative(pose, GOOD_POINTS)
    assert snapshot(tree) == before


def test_pose_of_the_wrong_kind(tree):
    with rejects(TypeError, "pose", "str"):
        tree.update("identity", GOOD_POINTS)
    with rejects(TypeError, "pose", "real numbers"):
        tree.update(np.eye(4).astype(complex), GOOD_POINTS)


def test_three_by_four_poses_and_other_real_dtypes_are_accepted(tree):
    tree.update(rotation_z(0.3)[:3], GOOD_POINTS)
    tree.update(np.eye(4, dtype=np.int32), GOOD_POINTS)
    assert tree.frame_count == 3


# --- queries ----------------------------------------------------------------------------------

def test_bad_queries(tree):
    before = snapshot(tree)
    with rejects(TypeError, "queries", "complex128"):
        tree.knn(np.zeros((2, 3), dtype=np.complex128), 1)
    with rejects(ValueError, "queries", r"\(N, 3\) or \(3,\)", r"\(2, 2\)"):
        tree.knn(np.zeros((2, 2)), 1)
    with rejects(ValueError, "queries row 1", "not finite"):  # found in a strided view too
        tree.knn(np.array([[0, 0, 0, 9], [np.inf, 0, 0, 9]])[:, :3], 1)
    with rejects(ValueError, "queries row 1", "not finite"):
        tree.knn(np.array([[0, 0, 0], [np.nan, 0, 0]]), 1)
    with rejects(ValueError, "queries", "not finite"):
        tree.radius([0.0, np.inf, 0.0], 1.0)
    assert snapshot(tree) == before


@pytest.mark.parametrize("k, error, words", [
    (0, ValueError, ["k = 0 must be >= 1"]),
    (-2, ValueError, ["k = -2 must be >= 1"]),
    (2.5, TypeError, ["k must be an integer", "float"]),
    ("3", TypeError, ["k must be an integer", "str"]),
    (True, TypeError, ["k must be an integer", "bool"]),
])
def test_bad_k(tree, k, error, words):
    with rejects(error, *words):
        tree.knn([0.0, 0.0, 0.0], k)


@pytest.mark.parametrize("workers, error, words", [
    (0, ValueError, ["workers = 0", ">= 1, or -1"]),
    (-2, ValueError, ["workers = -2"]),
    (1.5, TypeError, ["workers must be an integer"]),
])
def test_bad_workers(tree, workers, error, words):
    with rejects(error, *words):
        tree.knn(np.zeros((4, 3)), 1, workers=workers)
    with rejects(error, *words):
        tree.radius(np.zeros((4, 3)), 1.0, workers=workers)


def test_an_error_inside_a_worker_is_raised_not_lost(tree):
    with rejects(ValueError, "radius", "-1"):
        tree.radius(np.zeros((50, 3)), -1.0, workers=4)


def test_numpy_integers_are_integers(tree):
    points, _ = tree.knn([0.0, 0.0, 0.0], np.int64(2))
    assert points.shape == (2, 3)


def test_bad_radius_box_resolution_and_frame(tree):
    with rejects(ValueError, "radius", "-1"):
        tree.radius([0.0, 0.0, 0.0], -1.0)
    with rejects(TypeError, "radius must be a number", "str"):
        tree.radius([0.0, 0.0, 0.0], "far")
    with rejects(ValueError, "lo", "exceeds hi"):
        tree.box([1.0, 0.0, 0.0], [0.0, 1.0, 1.0])
    with rejects(ValueError, "hi", "3 coordinates", r"\(2,\)"):
        tree.box([0.0, 0.0, 0.0], [1.0, 1.0])
    with rejects(ValueError, "lo", "not finite"):
        tree.box([np.nan, 0.0, 0.0], [1.0, 1.0, 1.0])
    with rejects(ValueError, "resolution", "> 0"):
        tree.voxelize(0.0)
    with rejects(ValueError, "frame", "'sideways'", "World, Ego"):
        tree.knn([0.0, 0.0, 0.0], 1, frame="sideways")
    with rejects(TypeError, "frame must be a Frame"):
        tree.knn([0.0, 0.0, 0.0], 1, frame=3)


# --- configuration ----------------------------------------------------------------------------

@pytest.mark.parametrize("fields, error, words", [
    ({"box_side": -1.0}, ValueError, ["box_side", "-1"]),
    ({"box_side": float("nan")}, ValueError, ["box_side"]),
    ({"box_side": "20"}, TypeError, ["box_side must be a number", "str"]),
    ({"leaf_capacity": 0}, ValueError, ["leaf_capacity", "1..4294967295"]),
    ({"leaf_capacity": -3}, ValueError, ["leaf_capacity = -3", ">= 0"]),
    ({"leaf_capacity": 2 ** 40}, ValueError, ["leaf_capacity", "out of range"]),
    ({"leaf_capacity": 2 ** 70}, ValueError, ["leaf_capacity", "out of range"]),
    ({"leaf_capacity": 8.5}, TypeError, ["leaf_capacity must be an integer", "float"]),
    ({"leaf_capacity": True}, TypeError, ["leaf_capacity must be an integer", "bool"]),
    ({"quantum_levels": 9}, ValueError, ["quantum_levels", "1..5"]),
    ({"min_cell_size": 0.0}, ValueError, ["min_cell_size"]),
    ({"recentring": "sideways"}, ValueError, ["recentring", "Quantised, Exact"]),
    ({"recentring": 1}, TypeError, ["recentring must be a Recentring"]),
    ({"insert_policy": eco.Recentring.Exact}, TypeError, ["insert_policy must be a InsertPolicy"]),
    ({"density_cap": {"max_points": 2}}, ValueError, ["density_cap.cell_size"]),
    ({"density_cap": {"bogus": 1}}, TypeError, ["unexpected keyword argument 'density_cap.bogus'"]),
    ({"density_cap": 3}, TypeError, ["density_cap must be a DensityCap"]),
    ({"box_sid": 20.0}, TypeError, ["unexpected keyword argument 'box_sid'", "box_side"]),
])
def test_bad_config_names_the_field(fields, error, words):
    with rejects(error, *words):
        eco.Config(**fields)
    with rejects(error, *words):
        eco.EgoOctree(**fields)


def test_bad_attribute_assignment_names_the_field():
    config = eco.Config()
    with rejects(TypeError, "box_side must be a number"):
        config.box_side = None
    with rejects(ValueError, "max_points = -1"):
        config.density_cap.max_points = -1
    assert config == eco.Config()
    config.quantum_levels = 7  # assignments are checked for type; the whole is validated on use
    with rejects(ValueError, "quantum_levels"):
        eco.EgoOctree(config)
    with rejects(ValueError, "quantum_levels"):
        config.validate()


def test_config_and_fields_together_are_refused():
    with rejects(TypeError, "either config or keyword fields"):
        eco.EgoOctree(eco.Config(), box_side=3.0)
    with rejects(TypeError, "config must be a Config"):
        eco.EgoOctree("big")


def test_sixty_four_bit_seeds():
    assert eco.sim.SimConfig(seed=2 ** 64 - 1).seed == 2 ** 64 - 1
    with rejects(ValueError, "seed = 18446744073709551616 is out of range"):
        eco.sim.SimConfig(seed=2 ** 64)
    with rejects(ValueError, "seed = -1 is out of range"):
        eco.sim.SimConfig(seed=-1)


def test_bad_simulator_config():
    with rejects(ValueError, "SimConfig", "rate_hz"):
        eco.sim.Simulator(rate_hz=0.0)
    with rejects(TypeError, "lidar.beams must be an integer"):
        eco.sim.Simulator(lidar={"beams": "many"})
    with rejects(TypeError, "unexpected keyword argument 'lidar.colums'"):
        eco.sim.SimConfig(lidar={"colums": 10})
    simulator = eco.sim.Simulator(frames=2, lidar={"columns": 100})
    with rejects(IndexError, "index 2", "2 frames"):
        simulator[2]
    assert simulator[-1][1].shape[1] == 3


# --- files ------------------------------------------------------------------------------------

def test_missing_and_broken_files_name_the_file(tmp_path):
    with rejects(eco.io.Error, "nowhere"):
        eco.io.KittiSequence(tmp_path / "nowhere")
    assert issubclass(eco.io.Error, OSError)
    broken = tmp_path / "broken.ply"
    broken.write_text("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nend_header\n1\n")
    with rejects(eco.io.Error, "broken.ply"):
        eco.io.read_ply(broken)
    poses = tmp_path / "poses.txt"
    poses.write_text("1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 zero 0 1 0 0 0 0 1 0\n")
    with rejects(eco.io.Error, "poses.txt", "line 2"):
        eco.io.read_kitti_poses(poses)
    with rejects(ValueError, "intensity", r"\(3,\)"):
        eco.io.write_ply(tmp_path / "x.ply", GOOD_POINTS, intensity=np.zeros(2))

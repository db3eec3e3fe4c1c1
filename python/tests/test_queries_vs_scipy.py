"""KNN, radius and box answers equal scipy's cKDTree on the held points, after every frame of a
simulated drive, in both re-centring modes and both insert policies."""

import numpy as np
import pytest

import eco
from scipy_oracle import check_against_scipy, sorted_rows


@pytest.mark.parametrize("recentring", [eco.Recentring.Quantised, eco.Recentring.Exact])
@pytest.mark.parametrize("policy", [eco.InsertPolicy.AllInBox, eco.InsertPolicy.ShiftInOnly])
def test_every_frame_matches_scipy(small_drive, recentring, policy):
    tree = eco.EgoOctree(box_side=16.0, leaf_capacity=8, recentring=recentring, insert_policy=policy)
    rng = np.random.default_rng(11)
    rebuilt = 0
    for index, (pose, points) in enumerate(small_drive):
        stats = tree.update(pose, points)
        rebuilt += stats.rebuilt_subtrees + stats.relinked_subtrees
        assert tree.frame_count == index + 1
        assert tree.check_invariants() == ""
        check_against_scipy(tree, rng)
    assert rebuilt > 0, "the drive never re-centred the tree"
    assert len(tree) > 1000


def test_float64_and_float32_scans_give_the_same_tree(small_drive):
    a, b = eco.EgoOctree(insert_policy="AllInBox"), eco.EgoOctree(insert_policy="AllInBox")
    for pose, points in list(small_drive)[:4]:
        a.update(pose, points)
        b.update(pose, points.astype(np.float64))
    np.testing.assert_array_equal(sorted_rows(a.points()), sorted_rows(b.points()))


def test_relative_updates_follow_the_same_path(small_drive):
    absolute = eco.EgoOctree(insert_policy="AllInBox")
    relative = eco.EgoOctree(insert_policy="AllInBox")
    previous = np.eye(4)
    for pose, points in list(small_drive)[:5]:
        absolute.update(pose, points)
        relative.update_relative(np.linalg.inv(previous) @ pose, points)
        previous = pose
        np.testing.assert_allclose(relative.pose, absolute.pose, atol=1e-9)
        assert len(relative) == len(absolute)


def test_fewer_points_than_k_pad_with_nan_at_infinity():
    tree = eco.EgoOctree(insert_policy="AllInBox")
    tree.update(np.eye(4), np.array([[1.0, 0.0, 0.0], [0.0, 2.0, 0.0]], dtype=np.float32))
    points, sq_dists = tree.knn([0.0, 0.0, 0.0], 4)
    np.testing.assert_array_equal(sq_dists, [1.0, 4.0, np.inf, np.inf])
    np.testing.assert_array_equal(points[:2], [[1.0, 0.0, 0.0], [0.0, 2.0, 0.0]])
    assert np.isnan(points[2:]).all()


def test_voxelize_and_keys_agree_with_the_held_points(small_drive):
    tree = eco.EgoOctree(insert_policy="AllInBox")
    for pose, points in list(small_drive)[:3]:
        tree.update(pose, points)
    held = tree.points()
    keys = tree.voxel_keys(0.5)
    assert keys.dtype == np.int64
    # every held point falls in a listed voxel, and every listed voxel holds one
    held_keys = np.unique(np.floor(held / 0.5).astype(np.int64), axis=0)
    np.testing.assert_array_equal(keys, held_keys)
    np.testing.assert_allclose(tree.voxelize(0.5), (keys + 0.5) * 0.5)
    centre = tree.pose[:3, 3]
    np.testing.assert_allclose(tree.voxelize(0.5, frame="Ego") + centre, (keys + 0.5) * 0.5, atol=1e-9)


def test_empty_batches_and_an_empty_tree():
    tree = eco.EgoOctree()
    points, sq_dists = tree.knn(np.zeros((0, 3)), 3)
    assert points.shape == (0, 3, 3) and sq_dists.shape == (0, 3)
    assert tree.radius(np.zeros((0, 3), dtype=np.float32), 1.0) == []
    points, sq_dists = tree.knn([1.0, 2.0, 3.0], 2)  # nothing held yet
    assert np.isnan(points).all() and np.isinf(sq_dists).all()
    assert tree.points().shape == (0, 3) and tree.voxelize(1.0).shape == (0, 3)
    assert tree.ego_box is None and len(tree) == 0


def test_workers_share_a_batch_without_changing_the_answers(small_drive):
    tree = eco.EgoOctree(insert_policy="AllInBox")
    for pose, points in list(small_drive)[:3]:
        tree.update(pose, points)
    queries = pose[:3, 3] + np.random.default_rng(4).uniform(-9, 9, size=(301, 3))
    one = tree.knn(queries, 7)
    for workers in (2, 3, -1, 1000):
        many = tree.knn(queries, 7, workers=workers)
        np.testing.assert_array_equal(many[0], one[0])
        np.testing.assert_array_equal(many[1], one[1])
        for (a_points, a_sq), (b_points, b_sq) in zip(tree.radius(queries, 1.5),
                                                      tree.radius(queries, 1.5, workers=workers)):
            np.testing.assert_array_equal(a_points, b_points)
            np.testing.assert_array_equal(a_sq, b_sq)

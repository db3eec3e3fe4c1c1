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


def test_k_is_clamped_to_the_points_held():
    tree = eco.EgoOctree(insert_policy="AllInBox")
    tree.update(np.eye(4), np.array([[1.0, 0.0, 0.0], [0.0, 2.0, 0.0]], dtype=np.float32))
    points, sq_dists = tree.knn([0.0, 0.0, 0.0], 4)
    np.testing.assert_array_equal(sq_dists, [1.0, 4.0])
    np.testing.assert_array_equal(points, [[1.0, 0.0, 0.0], [0.0, 2.0, 0.0]])
    # a k far above the held count allocates nothing k-sized (10**9 columns would be 24 GB)
    points, sq_dists = tree.knn(np.zeros((3, 3)), 10**9)
    assert points.shape == (3, 2, 3) and sq_dists.shape == (3, 2)
    np.testing.assert_array_equal(sq_dists, [[1.0, 4.0]] * 3)


def test_queries_take_any_array_like_as_numpy_does(small_drive):
    tree = eco.EgoOctree(insert_policy="AllInBox")
    pose, points = next(iter(small_drive))
    tree.update(pose, points)
    base = tree.points()[:40] + 0.03
    expected = tree.knn(np.ascontiguousarray(base, dtype=np.float64), 3)
    wide = np.zeros((40, 5))
    wide[:, 1:4] = base
    variants = {
        "strided view": wide[:, 1:4],
        "fortran order": np.asfortranarray(base),
        "reversed rows": base[::-1][::-1],
        "list of lists": base.tolist(),
        "float32 copy": base.astype(np.float32),
    }
    for name, queries in variants.items():
        got = tree.knn(queries, 3)
        tol = 1e-5 if name == "float32 copy" else 0
        for want, have in zip(expected, got):
            np.testing.assert_allclose(have, want, atol=tol, err_msg=name)
    # the pose's translation as one (1, 3) query: a strided view of a (4, 4) array
    points, _ = tree.knn(tree.pose[:3, 3][None, :], 1)
    assert points.shape == (1, 1, 3)
    counts = tree.knn(np.arange(12).reshape(4, 3), 2)[1].shape  # integers are coordinates too
    assert counts == (4, 2)


def test_scans_take_any_array_like_and_match_the_float32_scan(small_drive):
    frames = list(small_drive)[:2]
    reference = eco.EgoOctree(insert_policy="AllInBox")
    strided = eco.EgoOctree(insert_policy="AllInBox")
    for pose, points in frames:
        reference.update(pose, np.ascontiguousarray(points, dtype=np.float32))
        wide = np.zeros((len(points), 4), dtype=np.float32)
        wide[:, :3] = points
        strided.update(pose, wide[:, :3])  # KITTI's x, y, z of an (N, 4) scan, not copied by the caller
    np.testing.assert_array_equal(np.sort(strided.points(), axis=0), np.sort(reference.points(), axis=0))


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
    assert points.shape == (0, 0, 3) and sq_dists.shape == (0, 0)
    assert tree.radius(np.zeros((0, 3), dtype=np.float32), 1.0) == []
    points, sq_dists = tree.knn([1.0, 2.0, 3.0], 2)  # nothing held yet
    assert points.shape == (0, 3) and sq_dists.shape == (0,)
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


def test_sensor_frame_and_oriented_boxes_match_numpy(small_drive):
    """Frame.Sensor answers are the world's turned into the sensor's axes; an oriented box holds
    what numpy finds by turning every held point into the box's axes."""
    tree = eco.EgoOctree(insert_policy="AllInBox")
    for pose, points in list(small_drive)[:4]:
        tree.update(pose, points)
    pose = tree.pose
    held = tree.points()
    in_sensor = (held - pose[:3, 3]) @ pose[:3, :3]
    lo, hi = np.array([-6.0, -8.0, -3.0]), np.array([9.0, 7.0, 2.0])
    inside = np.all((in_sensor >= lo - 1e-9) & (in_sensor <= hi + 1e-9), axis=1)
    got = tree.box(lo, hi, eco.Frame.Sensor)
    assert len(got) == inside.sum() > 0
    np.testing.assert_allclose(sorted_rows(got), sorted_rows(in_sensor[inside]), atol=1e-9)
    # the same box placed in the world by the sensor's pose
    world = tree.oriented_box(pose, lo, hi)
    np.testing.assert_allclose(sorted_rows(world), sorted_rows(held[inside]), atol=1e-9)
    points, sq_dists = tree.knn([3.0, 0.0, 0.0], 5, eco.Frame.Sensor)
    np.testing.assert_allclose(np.sum((points - [3.0, 0.0, 0.0]) ** 2, axis=1), sq_dists, atol=1e-9)
    with pytest.raises(ValueError, match="box_pose"):
        tree.oriented_box(np.diag([2.0, 1.0, 1.0, 1.0]), lo, hi)


def test_a_budget_and_a_lookahead_show_in_the_update_stats(small_drive):
    tree = eco.EgoOctree(region={"shape": "ball", "radius": 8.0, "lookahead": 0.5, "max_points": 3000})
    for index, (pose, points) in enumerate(list(small_drive)[:6]):
        stats = tree.update(pose, points)
        assert len(tree) <= 3000
        # 30 m/s asks 15 m more: the ball grows to the cube's half side, then the budget scales it
        full = 8.0 if index == 0 else 10.0
        assert stats.region.radius == pytest.approx(full * stats.region.scale)
    assert stats.region.scale < 1.0 and stats.over_budget > 0
    assert stats.region.speed > 0.0

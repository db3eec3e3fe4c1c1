"""Per-point ids, intensities and times from Python: stored with their points through a simulated
drive, returned by knn/radius (return_ids=True), box and points (attributes=True), checked
against a brute force kept in Python and against scipy's cKDTree; the age limit in seconds; and
bad attribute arrays refused by name with the tree unchanged."""

import numpy as np
import pytest
from scipy.spatial import cKDTree

import eco

ALL = eco.KeptAttributes(ids=True, intensity=True, time=True)
START = 1.7e9  # a Unix time: far from what a float offset holds


def attributes_of(index, count, rng):
    """Unique ids per frame, random intensities, times sweeping a 0.1 s frame."""
    ids = np.arange(count, dtype=np.uint32) + np.uint32(index * 1_000_000)
    intensities = rng.uniform(0.0, 255.0, count).astype(np.float32)
    times = START + 0.1 * index + np.linspace(0.0, 0.1, count, endpoint=False)
    return ids, intensities, times


def test_attributes_come_back_with_every_query_through_a_drive(small_drive):
    tree = eco.EgoOctree(box_side=16.0, leaf_capacity=8, attributes=ALL)
    rng = np.random.default_rng(3)
    given = {}  # id -> (world point in double, intensity, time)
    boxed = 0
    for index, (pose, points) in enumerate(small_drive):
        ids, intensities, times = attributes_of(index, len(points), rng)
        tree.update(pose, points, ids=ids, intensities=intensities, times=times)
        world = points.astype(np.float64) @ pose[:3, :3].T + pose[:3, 3]
        for i in range(len(points)):
            given[int(ids[i])] = (world[i], intensities[i], times[i])
        assert tree.check_invariants() == ""

        held, attributes = tree.points(attributes=True)
        assert set(attributes) == {"ids", "intensities", "times"}
        held_ids = attributes["ids"]
        assert held_ids.dtype == np.uint32 and attributes["intensities"].dtype == np.float32
        assert attributes["times"].dtype == np.float64
        assert len(np.unique(held_ids)) == len(held) == len(tree)
        expected = [given[int(i)] for i in held_ids]
        np.testing.assert_allclose(held, [e[0] for e in expected], atol=1e-3)  # float storage
        np.testing.assert_array_equal(attributes["intensities"], [e[1] for e in expected])
        np.testing.assert_allclose(attributes["times"], [e[2] for e in expected], rtol=0, atol=1e-5)

        # knn and radius by id against cKDTree on the held points
        point_of = dict(zip(held_ids.tolist(), held))
        kd = cKDTree(held)
        queries = tree.pose[:3, 3] + rng.uniform(-10.0, 10.0, size=(20, 3))
        sq_dists, knn_ids = tree.knn(queries, 6, return_ids=True)
        assert sq_dists.shape == knn_ids.shape == (20, 6) and knn_ids.dtype == np.uint32
        dist, _ = kd.query(queries, k=6)
        np.testing.assert_allclose(sq_dists, dist**2, rtol=1e-12)
        for q, row_ids, row_sq in zip(queries, knn_ids, sq_dists):
            found = np.array([point_of[int(i)] for i in row_ids])
            np.testing.assert_allclose(((found - q) ** 2).sum(axis=1), row_sq, rtol=1e-9)
        for q in queries[:5]:
            r_sq, r_ids = tree.radius(q, 2.5, return_ids=True)
            assert np.all(np.diff(r_sq) >= 0)
            want = held_ids[kd.query_ball_point(q, 2.5)]
            assert sorted(r_ids.tolist()) == sorted(want.tolist())
        lo, hi = tree.pose[:3, 3] - [3.0, 2.0, 3.0], tree.pose[:3, 3] + [1.0, 4.0, 2.0]
        in_box, box_attributes = tree.box(lo, hi, attributes=True)
        inside = np.all((held >= lo) & (held <= hi), axis=1)
        assert sorted(box_attributes["ids"].tolist()) == sorted(held_ids[inside].tolist())
        boxed += len(in_box)
        np.testing.assert_array_equal(in_box, np.reshape([point_of[int(i)] for i in box_attributes["ids"]], (-1, 3)))


    assert boxed > 100, "the boxes held too little to test"


def test_knn_ids_are_ckdtree_indices_when_the_ids_are_row_numbers():
    """How the two conventions relate: with ids = row numbers of the cloud given, knn's ids are
    cKDTree.query's idx and its sq_dists the squares of cKDTree's dists."""
    rng = np.random.default_rng(9)
    cloud = rng.uniform(-8.0, 8.0, size=(3000, 3)).astype(np.float32)
    tree = eco.EgoOctree(attributes={"ids": True})
    tree.update(np.eye(4), cloud, ids=np.arange(len(cloud)))
    queries = rng.uniform(-8.0, 8.0, size=(50, 3))
    sq_dists, ids = tree.knn(queries, 4, return_ids=True)
    dists, idx = cKDTree(cloud.astype(np.float64)).query(queries, k=4)
    np.testing.assert_array_equal(ids, idx)
    np.testing.assert_allclose(np.sqrt(sq_dists), dists, rtol=1e-12)
    one_sq, one_ids = tree.knn(queries[0], 4, return_ids=True)  # one (3,) query: (k,) arrays
    np.testing.assert_array_equal(one_ids, idx[0])


def test_the_age_limit_in_seconds_drops_what_is_older_than_the_latest_time_less_the_limit():
    tree = eco.EgoOctree(attributes={"time": True}, max_age_seconds=0.35)
    rng = np.random.default_rng(4)
    latest, aged, refused = 0.0, 0, 0
    for index in range(12):
        points = rng.uniform(-5.0, 5.0, size=(200, 3)).astype(np.float32)
        times = START + 0.1 * index + rng.uniform(0.0, 0.1, 200)
        times[:5] -= 1.0  # older than the limit when they arrive: refused
        stats = tree.update(np.eye(4), points, times=times)
        latest = max(latest, times.max())
        aged += stats.aged_out
        refused += stats.skipped_by_age
        _, attributes = tree.points(attributes=True)
        assert attributes["times"].min() >= latest - 0.35 - 1e-5
    assert aged > 0 and refused == 12 * 5
    held_times = tree.points(attributes=True)[1]["times"]
    assert held_times.max() == pytest.approx(latest, abs=1e-5)


def _tree_with_a_frame():
    tree = eco.EgoOctree(attributes=ALL)
    points = np.random.default_rng(1).uniform(-5.0, 5.0, size=(100, 3)).astype(np.float32)
    ids, intensities, times = attributes_of(0, 100, np.random.default_rng(2))
    tree.update(np.eye(4), points, ids=ids, intensities=intensities, times=times)
    return tree, points, ids, intensities, times


@pytest.mark.parametrize("change, error, words", [
    (lambda a: {**a, "ids": a["ids"][:-1]}, ValueError, ["ids", "(100,)"]),
    (lambda a: {**a, "ids": a["ids"].astype(np.float64)}, TypeError, ["ids", "integers"]),
    (lambda a: {**a, "ids": a["ids"].astype(np.int64) - 1}, ValueError, ["ids", "-1"]),
    (lambda a: {**a, "ids": a["ids"].astype(np.int64) + 2**32}, ValueError, ["ids", "[0, 4294967295]"]),
    (lambda a: {**a, "ids": a["ids"].reshape(50, 2)}, ValueError, ["ids", "(50, 2)"]),
    (lambda a: {**a, "ids": None}, ValueError, ["ids", "attributes.ids"]),
    (lambda a: {**a, "intensities": a["intensities"][:3]}, ValueError, ["intensities"]),
    (lambda a: {**a, "intensities": np.array(["x"] * 100)}, TypeError, ["intensities"]),
    (lambda a: {**a, "intensities": None}, ValueError, ["intensities", "attributes.intensity"]),
    (lambda a: {**a, "times": np.where(np.arange(100) == 7, -1.0, a["times"])}, ValueError, ["times[7]", ">= 0"]),
    (lambda a: {**a, "times": np.where(np.arange(100) == 3, np.nan, a["times"])}, ValueError, ["times[3]", "finite"]),
    (lambda a: {**a, "times": np.full(100, np.inf)}, ValueError, ["times[0]"]),
    (lambda a: {**a, "times": a["times"].astype(np.complex128)}, TypeError, ["times"]),
    (lambda a: {**a, "times": None}, ValueError, ["times", "attributes.time"]),
])
def test_bad_attribute_arrays_are_refused_by_name_and_the_tree_is_unchanged(change, error, words):
    tree, points, ids, intensities, times = _tree_with_a_frame()
    before_points, before = tree.points(attributes=True)
    frames = tree.frame_count
    arrays = change({"ids": ids, "intensities": intensities, "times": times + 0.1})
    with pytest.raises(error) as raised:
        tree.update(np.eye(4), points, **arrays)
    for word in words:
        assert word in str(raised.value), str(raised.value)
    after_points, after = tree.points(attributes=True)
    np.testing.assert_array_equal(after_points, before_points)
    for name in before:
        np.testing.assert_array_equal(after[name], before[name])
    assert tree.frame_count == frames


def test_ids_asked_of_a_tree_that_keeps_none_are_refused():
    tree = eco.EgoOctree()
    tree.update(np.eye(4), np.ones((4, 3), dtype=np.float32), ids=np.arange(4))  # not kept: ignored
    with pytest.raises(ValueError, match="attributes.ids"):
        tree.knn([0.0, 0.0, 0.0], 2, return_ids=True)
    with pytest.raises(ValueError, match="attributes.ids"):
        tree.radius([0.0, 0.0, 0.0], 2.0, return_ids=True)
    points, attributes = tree.points(attributes=True)
    assert len(points) == 4 and attributes == {}

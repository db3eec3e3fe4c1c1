"""Snapshots from Python: tree.snapshot() answers with the tree's query methods (same names,
arguments and return types) as the tree did when it was taken, whatever the tree does after, and
Python threads query snapshots while the tree updates."""

import threading

import numpy as np
import pytest

import eco


def _answers(m, queries):
    """Every query's answer as plain arrays, to compare a snapshot with the tree it came from."""
    lo, hi = queries[0] - 3.0, queries[0] + 3.0
    return [
        *m.knn(queries, 4),
        *m.radius(queries[0], 2.0),
        m.box(lo, hi),
        m.voxel_keys(0.4),
        m.voxelize(0.4),
        m.points(),
        np.array([len(m), m.size, m.frame_count, m.stats().points, m.time_origin]),
        m.pose,
        m.precision_origin,
        *m.ego_box,
    ]


def _assert_same(a, b):
    assert len(a) == len(b)
    for x, y in zip(a, b):
        np.testing.assert_array_equal(x, y)


def test_a_snapshot_answers_as_its_frame_did_after_the_tree_moves_on(small_drive):
    frames = list(small_drive)[:8]
    tree = eco.EgoOctree(insert_policy="AllInBox", leaf_capacity=16)
    queries = frames[0][0][:3, 3] + np.random.default_rng(4).uniform(-6, 6, size=(50, 3))
    published = []
    for pose, points in frames:
        tree.update(pose, points)
        snapshot = tree.snapshot()
        assert isinstance(snapshot, eco.Snapshot)
        _assert_same(_answers(snapshot, queries), _answers(tree, queries))
        published.append((snapshot, _answers(tree, queries)))
    for snapshot, then in published:
        _assert_same(_answers(snapshot, queries), then)
    assert tree.stats().snapshot_bytes > 0
    del published, snapshot
    tree.update(*frames[-1])  # the pages let go are kept spare for one more update's copies
    assert tree.stats().snapshot_bytes == 0


def test_a_snapshot_has_the_trees_query_methods():
    tree = eco.EgoOctree()
    snapshot = tree.snapshot()
    queries = [name for name in dir(tree) if not name.startswith("_")]
    only_tree = {"update", "update_relative", "save", "load", "snapshot", "last_update"}
    for name in queries:
        if name in only_tree:
            assert not hasattr(snapshot, name), name
            continue
        assert hasattr(snapshot, name), name
        same = getattr(eco.EgoOctree, name).__doc__.replace("eco._eco.EgoOctree", "eco._eco.Snapshot")
        assert getattr(eco.Snapshot, name).__doc__ == same, name
    assert repr(snapshot) == "Snapshot(points=0, frame=0)"


def test_snapshot_queries_check_their_arguments_as_the_trees_do(small_drive):
    tree = eco.EgoOctree(insert_policy="AllInBox")
    pose, points = next(iter(small_drive))
    tree.update(pose, points)
    snapshot = tree.snapshot()
    for m in (tree, snapshot):
        with pytest.raises(ValueError, match="k = 0 must be >= 1"):
            m.knn(np.zeros(3), 0)
        with pytest.raises(ValueError, match="return_ids=True needs ids kept"):
            m.knn(np.zeros(3), 1, return_ids=True)
        with pytest.raises(ValueError, match="workers"):
            m.radius(np.zeros(3), 1.0, workers=0)


def test_threads_query_snapshots_while_the_tree_updates(small_drive):
    frames = list(small_drive)[:10]
    queries = frames[0][0][:3, 3] + np.random.default_rng(2).uniform(-6, 6, size=(100, 3))
    serial = eco.EgoOctree(insert_policy="AllInBox")
    expected = {}  # frame -> the knn distances after it
    for pose, points in frames:
        serial.update(pose, points)
        expected[serial.frame_count] = serial.knn(queries, 3)[1]

    tree = eco.EgoOctree(insert_policy="AllInBox")
    tree.update(*frames[0])
    latest = [tree.snapshot()]
    failures, answered = [], [0]

    def read_until(stop):
        while not stop.is_set():
            snapshot = latest[-1]
            got = snapshot.knn(queries, 3, workers=2)[1]
            if not np.array_equal(got, expected[snapshot.frame_count]):
                failures.append(f"frame {snapshot.frame_count}: a knn answer differs")
            answered[0] += 1

    stop = threading.Event()
    readers = [threading.Thread(target=read_until, args=(stop,)) for _ in range(3)]
    for reader in readers:
        reader.start()
    for pose, points in frames[1:]:
        tree.update(pose, points)
        latest.append(tree.snapshot())
    stop.set()
    for reader in readers:
        reader.join()
    assert failures == []
    assert answered[0] > 0

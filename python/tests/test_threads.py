"""Python threads may share a tree: queries run side by side (the GIL is released), updates run
alone, and every answer is one a serial run could have given."""

import threading

import numpy as np

import eco


def test_queries_and_updates_from_several_threads(small_drive):
    frames = list(small_drive)[:8]
    serial = eco.EgoOctree(insert_policy="AllInBox")
    expected = []  # the knn answers after each frame, frame by frame
    queries = frames[0][0][:3, 3] + np.random.default_rng(2).uniform(-6, 6, size=(200, 3))
    for pose, points in frames:
        serial.update(pose, points)
        expected.append(serial.knn(queries, 3)[1])

    shared = eco.EgoOctree(insert_policy="AllInBox")
    shared.update(*frames[0])
    failures = []

    def query_until(stop):
        while not stop.is_set():
            got = shared.knn(queries, 3)[1]
            if not any(np.array_equal(got, want) for want in expected):
                failures.append("a knn answer matches no frame's")

    stop = threading.Event()
    readers = [threading.Thread(target=query_until, args=(stop,)) for _ in range(3)]
    for reader in readers:
        reader.start()
    for pose, points in frames[1:]:
        shared.update(pose, points)
    stop.set()
    for reader in readers:
        reader.join()
    assert failures == []
    np.testing.assert_array_equal(shared.knn(queries, 3)[1], expected[-1])

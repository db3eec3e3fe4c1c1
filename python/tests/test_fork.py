"""A process forked after queries on threads, as multiprocessing's "fork" start does: the child
queries the tree with workers > 1 and registers frames on an odometry whose map keeps query
threads (threads=2), without hanging, and gets the parent's answers."""

import multiprocessing
import queue

import numpy as np

import eco


def in_forked_child(work):
    """work() in a child forked from this process; its result, or an AssertionError when the child
    failed or hung (killed after a minute)."""
    context = multiprocessing.get_context("fork")
    results = context.Queue()

    def child():
        try:
            results.put(("ok", work()))
        except BaseException as e:  # noqa: BLE001 - everything goes back to the parent
            results.put(("failed", repr(e)))

    process = context.Process(target=child)
    process.start()
    try:  # read before joining: a child exits only once what it put is in the pipe
        status, value = results.get(timeout=60)
    except queue.Empty:
        process.kill()
        raise AssertionError("the forked child hung") from None
    finally:
        process.join(60)
    assert status == "ok" and process.exitcode == 0, value
    return value


def test_a_child_queries_with_workers_after_the_parent_did(small_drive):
    tree = eco.EgoOctree()
    for pose, points in list(small_drive)[:5]:
        tree.update(pose, points)
    queries = np.random.default_rng(3).uniform(-8, 8, size=(3000, 3)) + pose[:3, 3]
    parent = tree.knn(queries, 4, workers=2)
    child = in_forked_child(lambda: tree.knn(queries, 4, workers=2))
    np.testing.assert_array_equal(child[0], parent[0])
    np.testing.assert_array_equal(child[1], parent[1])


def test_a_child_registers_frames_on_an_odometry_with_query_threads():
    simulator = eco.sim.Simulator(frames=6, seed=4)
    frames = list(simulator)

    def odometry_after(count):
        odo = eco.odometry.Odometry(map="eco", threads=2)
        odo.set_start(simulator.pose(0))
        for _, points in frames[:count]:
            odo.register_frame(points)
        return odo

    parent = odometry_after(3)  # its map's helper thread waits for the next batch

    def go_on():
        for _, points in frames[3:]:
            parent.register_frame(points)
        return parent.poses

    poses = in_forked_child(go_on)
    np.testing.assert_array_equal(poses, odometry_after(6).poses)

"""Checks an EgoOctree's answers against scipy.spatial.cKDTree built on the points it holds.

Every comparison is exact: the same points, the same squared distances up to the rounding of
cKDTree's square root, and the same sets for radius and box queries.
"""

import numpy as np
from scipy.spatial import cKDTree

import eco


def sorted_rows(points):
    points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    return points[np.lexsort(points.T[::-1])]


def query_points(tree, held, rng, count):
    """Some held points (exact hits, distance 0) and random points in and around the box."""
    centre = tree.pose[:3, 3]
    side = tree.config.box_side
    out = centre + rng.uniform(-0.7 * side, 0.7 * side, size=(count, 3))
    if len(held):
        hits = rng.integers(0, len(held), size=count // 3)
        out[: len(hits)] = held[hits]
    return out


def check_knn(tree, kd, held, queries, k):
    points, sq_dists = tree.knn(queries, k)
    found = min(k, len(held))  # k is clamped to the points held
    assert points.shape == (len(queries), found, 3) and sq_dists.shape == (len(queries), found)
    if found == 0:
        return
    # cKDTree gives one more neighbour, to tell a clean k-th distance from a tie.
    dist, index = kd.query(queries, k=found + 1 if found < len(held) else found)
    dist = dist.reshape(len(queries), -1)
    index = index.reshape(len(queries), -1)
    np.testing.assert_allclose(sq_dists[:, :found], dist[:, :found] ** 2, rtol=1e-12, atol=1e-24)
    for q, got, got_sq, want_dist, want_index in zip(queries, points, sq_dists, dist, index):
        got = got[:found]
        # every point returned is held, and its distance is the one reported
        assert (kd.query(got)[0] == 0).all()
        np.testing.assert_array_equal(((got - q) ** 2).sum(axis=1), got_sq[:found])
        assert (np.diff(got_sq[:found]) >= 0).all(), "not nearest first"
        tie_at_k = want_dist.shape[0] > found and want_dist[found] == want_dist[found - 1]
        if not tie_at_k:
            np.testing.assert_array_equal(sorted_rows(got), sorted_rows(held[want_index[:found]]))


def check_radius(tree, kd, held, queries, radius):
    answers = tree.radius(queries, radius)
    assert len(answers) == len(queries)
    for q, (points, sq_dists), want in zip(queries, answers, kd.query_ball_point(queries, radius)):
        np.testing.assert_array_equal(sorted_rows(points), sorted_rows(held[want]))
        assert (np.diff(sq_dists) >= 0).all(), "not nearest first"
        assert (sq_dists <= radius * radius).all()


def check_box(tree, held, lo, hi):
    inside = np.all((held >= lo) & (held <= hi), axis=1)
    np.testing.assert_array_equal(sorted_rows(tree.box(lo, hi)), sorted_rows(held[inside]))


def check_against_scipy(tree, rng, queries=30):
    """Every query kind, world frame, against cKDTree on tree.points(); then the ego frame."""
    held = tree.points()
    assert held.shape == (len(tree), 3)
    lo, hi = tree.ego_box
    assert np.all((held >= lo) & (held < hi)), "a held point is outside the half-open ego box"
    kd = cKDTree(held)
    qs = query_points(tree, held, rng, queries)
    for k in (1, 5, 17):
        check_knn(tree, kd, held, qs, k)
    for radius in (0.5, 2.0, 0.15 * tree.config.box_side):
        check_radius(tree, kd, held, qs[:10], radius)
    corners = query_points(tree, held, rng, 8)
    for a, b in zip(corners[0::2], corners[1::2]):
        check_box(tree, held, np.minimum(a, b), np.maximum(a, b))
    # The ego frame differs from the world by a translation: the same answers up to rounding.
    centre = tree.pose[:3, 3]
    world_points, world_sq = tree.knn(qs, 5)
    ego_points, ego_sq = tree.knn(qs - centre, 5, frame=eco.Frame.Ego)
    np.testing.assert_allclose(ego_sq, world_sq, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(ego_points + centre, world_points, atol=1e-6)


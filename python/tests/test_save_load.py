"""tree.save(path) and eco.EgoOctree.load(path): the loaded tree answers as the saved one did and,
fed the same frames, stays identical; a file that is not a map raises naming the path and byte."""

import numpy as np
import pytest

import eco


def test_a_loaded_tree_answers_and_goes_on_as_the_saved_one(small_drive, tmp_path):
    frames = list(small_drive)
    config = {"density_cap": {"cell_size": 0.2, "max_points": 2}, "attributes": {"ids": True}}
    tree = eco.EgoOctree(config)
    rng = np.random.default_rng(4)
    for t, (pose, points) in enumerate(frames[:10]):
        tree.update(pose, points, ids=np.arange(len(points), dtype=np.uint32) + 100000 * t)
    path = tmp_path / "map.eco"
    tree.save(path)  # os.PathLike
    loaded = eco.EgoOctree.load(str(path))
    assert loaded.frame_count == tree.frame_count == 10
    assert loaded.config.density_cap.max_points == 2
    for t, (pose, points) in enumerate(frames[10:], start=10):
        ids = np.arange(len(points), dtype=np.uint32) + 100000 * t
        tree.update(pose, points, ids=ids)
        loaded.update(pose, points, ids=ids)
        assert loaded.check_invariants() == ""
        held, held_attributes = tree.points(attributes=True)
        got, got_attributes = loaded.points(attributes=True)
        np.testing.assert_array_equal(got, held)
        np.testing.assert_array_equal(got_attributes["ids"], held_attributes["ids"])
        queries = pose[:3, 3] + rng.uniform(-8, 8, size=(50, 3))
        for want, have in zip(tree.knn(queries, 5), loaded.knn(queries, 5)):
            np.testing.assert_array_equal(have, want)


def test_a_file_that_is_not_a_map_raises_naming_it(tmp_path):
    path = tmp_path / "not-a-map.eco"
    path.write_bytes(b"this is not a map at all, not even close")
    with pytest.raises(RuntimeError, match="not-a-map.eco: byte 0: not a map file"):
        eco.EgoOctree.load(path)
    tree = eco.EgoOctree()
    tree.save(tmp_path / "empty.eco")
    cut = (tmp_path / "empty.eco").read_bytes()[:-1]
    (tmp_path / "cut.eco").write_bytes(cut)
    with pytest.raises(RuntimeError, match="cut.eco: byte 12: .*truncated"):
        eco.EgoOctree.load(tmp_path / "cut.eco")
    with pytest.raises(RuntimeError, match="cannot create"):
        tree.save(tmp_path / "no" / "such" / "folder.eco")

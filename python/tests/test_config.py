"""Config mirrors eco::Config field for field: keyword construction, attributes, to_dict, pickle,
and the tree keeps what it was given. The records the library returns, and the docstrings."""

import inspect
import json
import pickle

import numpy as np
import pytest

import eco

# One non-default value per field (the C++ struct's fields, in order).
CHANGED = {
    "box_side": 31.5,
    "leaf_capacity": 12,
    "min_cell_size": 0.125,
    "recentring": eco.Recentring.Exact,
    "quantum_levels": 4,
    "insert_policy": eco.InsertPolicy.AllInBox,
    "density_cap": eco.DensityCap(cell_size=0.2, max_points=3),
    "max_age_frames": 40,
    "max_age_seconds": 2.5,
    "attributes": eco.KeptAttributes(ids=True, intensity=True, time=True),
    "clearing": eco.FreeSpaceClearing(enabled=True, margin=0.5, arrivals=True),
    "sensor": eco.SensorModel(vertical_fov_min=-15.0, vertical_fov_max=15.0, vertical_resolution=2.0,
                              horizontal_resolution=0.4, max_range=100.0),
    "region": eco.Region(shape=eco.RegionShape.oriented_box, ahead=8.0, behind=2.0, left=3.0, right=3.0, up=2.0,
                         down=1.5, turn_with=eco.TurnWith.full),
    "voxel_size": 0.25,
}


# What a field's changed value needs of the others to be valid.
NEEDS = {"max_age_seconds": {"attributes": eco.KeptAttributes(time=True)}}


def test_defaults_are_the_cpp_defaults():
    assert eco.Config().to_dict() == {
        "box_side": 20.0,
        "leaf_capacity": 128,
        "min_cell_size": 0.05,
        "recentring": "Quantised",
        "quantum_levels": 3,
        "insert_policy": "AllInBox",
        "density_cap": {"cell_size": 0.0, "max_points": 0},
        "max_age_frames": 0,
        "max_age_seconds": 0.0,
        "attributes": {"ids": False, "intensity": False, "time": False},
        "clearing": {"enabled": False, "margin": 0.3, "arrivals": True},
        "sensor": {"vertical_fov_min": -24.9, "vertical_fov_max": 2.0, "vertical_resolution": 0.42,
                   "horizontal_resolution": 0.2, "max_range": 100.0},
        "region": {"shape": "cube", "radius": 0.0, "ahead": 0.0, "behind": 0.0, "left": 0.0, "right": 0.0,
                   "up": 0.0, "down": 0.0, "turn_with": "yaw", "lookahead": 0.0, "frame_period": 0.1,
                   "max_points": 0},
        "voxel_size": 0.1,
    }


def test_fields_are_the_cpp_fields_in_order():
    assert list(eco.Config().to_dict()) == list(CHANGED)


@pytest.mark.parametrize("name", list(CHANGED))
def test_each_field_round_trips(name):
    value = CHANGED[name]
    by_keyword = eco.Config(**NEEDS.get(name, {}), **{name: value})
    assert getattr(by_keyword, name) == value
    by_attribute = eco.Config(**NEEDS.get(name, {}))
    setattr(by_attribute, name, value)
    assert by_attribute == by_keyword
    assert eco.Config(**by_keyword.to_dict()) == by_keyword
    assert eco.Config(**json.loads(json.dumps(by_keyword.to_dict()))) == by_keyword
    assert pickle.loads(pickle.dumps(by_keyword)) == by_keyword
    assert eco.EgoOctree(by_keyword).config == by_keyword
    assert eco.EgoOctree(**NEEDS.get(name, {}), **{name: value}).config == by_keyword
    if name != "recentring":  # unchanged fields keep their defaults
        assert by_keyword.recentring == eco.Recentring.Quantised


def test_all_fields_together():
    config = eco.Config(**{**CHANGED, "max_age_frames": 0})  # an age limit in frames or in seconds
    assert config.to_dict()["density_cap"] == {"cell_size": 0.2, "max_points": 3}
    assert eco.EgoOctree(config=config).config == config
    assert "leaf_capacity=12" in repr(config) and "Recentring.Exact" in repr(config)


def test_enums_by_name_in_any_case_and_nested_records_as_dicts():
    config = eco.Config(recentring="exact", insert_policy="ALLINBOX",
                        density_cap={"cell_size": 0.1, "max_points": 2})
    assert config.recentring == eco.Recentring.Exact
    assert config.insert_policy == eco.InsertPolicy.AllInBox
    assert config.density_cap == eco.DensityCap(cell_size=0.1, max_points=2)
    config.density_cap = None  # None: the defaults, i.e. off
    assert config.density_cap.max_points == 0


def test_a_region_that_turns_with_the_sensor():
    # a box ahead of the sensor, turned by its heading: a point 5 m ahead is held, 5 m behind is not
    tree = eco.EgoOctree(region={"shape": "oriented_box", "ahead": 8, "behind": 2, "left": 3, "right": 3, "up": 2,
                                 "down": 2})
    facing_y = np.array([[0, -1, 0, 0], [1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], dtype=float)  # heading +90 degrees
    tree.update(facing_y, np.array([[5, 0, 0], [-5, 0, 0]], dtype=np.float32))  # sensor frame: ahead, behind
    np.testing.assert_allclose(tree.points(), [[0.0, 5.0, 0.0]], atol=1e-6)
    with pytest.raises(ValueError, match="region.radius = 12 is invalid: makes a region that reaches 12 m"):
        eco.Config(region={"shape": "ball", "radius": 12})
    with pytest.raises(ValueError, match="insert_policy = ShiftInOnly is invalid"):
        eco.Config(insert_policy="ShiftInOnly", region={"shape": "ball", "radius": 5})


def test_nested_fields_assign_in_place():
    config = eco.Config()
    config.density_cap.cell_size = 0.3
    config.density_cap.max_points = 5
    assert config.to_dict()["density_cap"] == {"cell_size": 0.3, "max_points": 5}


def test_tree_config_is_a_copy():
    tree = eco.EgoOctree(box_side=10.0)
    copy = tree.config
    copy.box_side = 99.0
    assert tree.config.box_side == 10.0


def test_derived_values():
    config = eco.Config(box_side=21.0, quantum_levels=3, voxel_size=0.0)
    assert config.quantum == pytest.approx(3.0, rel=1e-8)
    assert config.root_side == pytest.approx(24.0, rel=1e-8)
    aligned = eco.Config(box_side=21.0, quantum_levels=3)  # voxel_size 0.1: q = 0.1 * 2^5
    assert aligned.quantum == 3.2 and aligned.root_side == 25.6
    assert eco.Config(recentring="Exact").quantum == 0.0
    assert config.max_depth > 0


def test_simulator_config_round_trips():
    config = eco.sim.SimConfig(seed=5, frames=3, lidar={"beams": 16}, city={"cars_per_intersection": 2.5})
    assert config.lidar.beams == 16 and config.city.cars_per_intersection == 2.5
    assert eco.sim.SimConfig(**config.to_dict()) == config
    assert pickle.loads(pickle.dumps(config)) == config
    assert eco.sim.Simulator(config).config == config
    assert eco.sim.Simulator(seed=5, frames=3, lidar={"beams": 16}, city={"cars_per_intersection": 2.5}).config == config


def test_results_are_records():
    tree = eco.EgoOctree(insert_policy="AllInBox")
    update = tree.update([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]],
                         [[1.0, 2.0, 3.0], [float("nan"), 0.0, 0.0], [50.0, 0.0, 0.0]])
    assert update.to_dict() == tree.last_update.to_dict()
    assert (update.scan_points, update.inserted, update.skipped_nonfinite, update.skipped_by_policy) == (3, 1, 1, 1)
    stats = tree.stats()
    assert stats.points == 1 and stats.leaves == 1 and stats.bytes > 0
    assert set(stats.to_dict()) == {
        "points", "nodes", "leaves", "mean_leaf_depth", "max_leaf_depth", "bytes", "snapshot_bytes"
    }
    with pytest.raises(AttributeError):
        stats.points = 3


def public_members(module):
    for name in module.__all__:
        value = getattr(module, name)
        if inspect.ismodule(value):
            continue
        yield f"{module.__name__}.{name}", value
        if inspect.isclass(value):
            is_enum = hasattr(value, "__members__")  # pybind11's own name/value need no doc
            for attr, member in vars(value).items():
                if attr.startswith("_") or isinstance(member, value) or (is_enum and attr in ("name", "value")):
                    continue
                yield f"{module.__name__}.{name}.{attr}", member


@pytest.mark.parametrize("module", [eco, eco.io, eco.sim], ids=lambda m: m.__name__)
def test_everything_public_has_a_docstring(module):
    for name, value in public_members(module):
        assert (inspect.getdoc(value) or "").strip(), f"{name} has no docstring"
    assert module.__doc__.strip()


# --- the field table (include/eco/config_fields.hpp), as C++, the eco command and config.json use it

def _kwargs(name, value):
    """Config keyword arguments setting one table field (dotted names are nested records)."""
    if "." in name:
        record, field = name.split(".")
        return {record: {field: value}}
    return {name: value}


def _bad_values(field):
    """Values the field must refuse, from its kind and range alone (as tests/bench/config_surfaces_test.cpp)."""
    if field["kind"] == "choice":
        return ["Sideways", ""]
    if field["kind"] == "switch":
        return ["true", 1, None]
    lo, hi = field["lo"], field["hi"]
    if field["kind"] == "count":
        out = [int(lo) - 1, "3"]
        if hi != float("inf"):
            out.append(int(hi) * 2 + 1)
        return out
    out = [float("nan"), float("inf"), lo if field["lo_open"] else lo - 1, "abc"]
    if hi != float("inf"):
        out.append(hi * 2 + 1)
    return out


def test_the_table_lists_the_python_fields_with_their_docs():
    table = eco.config_fields()
    flat = []
    for name, value in eco.Config().to_dict().items():
        flat += [f"{name}.{k}" for k in value] if isinstance(value, dict) else [name]
    assert [f["name"] for f in table] == flat
    for f in table:
        if "." in f["name"]:
            record, field = f["name"].split(".")
            attribute = getattr(type(getattr(eco.Config(), record)), field)
        else:
            attribute = getattr(eco.Config, f["name"])
        assert f["doc"] in attribute.__doc__ and f["range"] in attribute.__doc__, f["name"]
        assert f["kind"] in ("real", "count", "choice", "switch")


def test_every_field_takes_its_default_text_and_refuses_what_cpp_refuses():
    for f in eco.config_fields():
        if f["kind"] == "choice":
            default = f["default"]
        elif f["kind"] == "switch":
            default = f["default"] == "true"
        elif f["kind"] == "count":
            default = int(f["default"])
        else:
            default = float(f["default"])
        eco.Config(**_kwargs(f["name"], default))  # taken
        for bad in _bad_values(f):
            with pytest.raises((TypeError, ValueError)) as error:
                eco.Config(**_kwargs(f["name"], bad))
            assert f["name"] in str(error.value), (f["name"], bad, str(error.value))


def test_a_config_json_section_is_a_config():
    """config.json's "config" (what every eco command writes) has Config's shape and spellings."""
    written = {"box_side": 18.0, "leaf_capacity": 32, "min_cell_size": 0.05, "recentring": "Quantised",
               "quantum_levels": 3, "insert_policy": "AllInBox",
               "density_cap": {"cell_size": 0.2, "max_points": 1}, "max_age_frames": 0,
               "max_age_seconds": 0.0, "attributes": {"ids": True, "intensity": False, "time": False},
               "clearing": {"enabled": True, "margin": 0.3, "arrivals": True},
               "sensor": {"vertical_fov_min": -24.9, "vertical_fov_max": 2.0, "vertical_resolution": 0.42,
                          "horizontal_resolution": 0.2, "max_range": 100.0},
               "region": {"shape": "ball", "radius": 8.0, "ahead": 0.0, "behind": 0.0, "left": 0.0, "right": 0.0,
                          "up": 0.0, "down": 0.0, "turn_with": "yaw", "lookahead": 1.5, "frame_period": 0.1,
                          "max_points": 50000},
               "voxel_size": 0.2}
    config = eco.Config(**json.loads(json.dumps(written)))
    assert config.to_dict() == written

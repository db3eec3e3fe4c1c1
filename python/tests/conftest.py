"""Shared fixtures: a small simulated drive, and where the real frames are."""

import os
from pathlib import Path

import pytest

import eco

SOURCE_DIR = Path(os.environ.get("ECO_SOURCE_DIR", Path(__file__).resolve().parents[2]))


def pytest_report_header(config):
    return f"eco {eco.__version__} from {eco.__file__}"


def pytest_sessionstart(session):
    """Under ctest, the package tested must be the build's, not an older one installed."""
    expected = os.environ.get("ECO_EXPECT_PACKAGE")
    if expected and Path(eco.__file__).resolve().parent != Path(expected).resolve():
        raise pytest.UsageError(f"testing eco from {eco.__file__}, not the build's {expected}")


@pytest.fixture(scope="session")
def small_drive():
    """A short, sparse drive (32 beams, 500 columns) down a street at 3 m per frame, so the box
    sheds and takes in a lot every frame."""
    return eco.sim.Simulator(frames=20, speed=30.0, seed=7, lidar={"beams": 32, "columns": 500})


def shared_data_dir():
    """$ECO_DATA_DIR, else shared/data in the nearest folder above the checkout that has one."""
    if os.environ.get("ECO_DATA_DIR"):
        return Path(os.environ["ECO_DATA_DIR"])
    for folder in SOURCE_DIR.resolve().parents:
        if (folder / "shared" / "data").is_dir():
            return folder / "shared" / "data"
    return SOURCE_DIR.resolve().parent / "shared" / "data"


@pytest.fixture
def shared_dataset():
    """shared_dataset(name) -> its folder, or skips the test saying where it looked."""

    def find(name):
        folder = shared_data_dir() / name
        if not (folder / "velodyne").is_dir():
            pytest.skip(f"real data absent: {folder} not found (set ECO_DATA_DIR)")
        return folder

    return find

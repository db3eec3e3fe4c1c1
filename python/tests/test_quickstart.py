"""The Python examples run: the quickstart and the odometry write their plots, the scipy
comparison prints its ratios."""

import subprocess
import sys

from conftest import SOURCE_DIR

EXAMPLES = SOURCE_DIR / "examples" / "python"


def run(script, *args):
    result = subprocess.run([sys.executable, str(EXAMPLES / script), *args],
                            capture_output=True, text=True, timeout=300, check=False)
    assert result.returncode == 0, result.stderr
    return result.stdout


def test_quickstart_writes_its_plot(tmp_path):
    plot = tmp_path / "quickstart.png"
    out = run("quickstart.py", "--frames", "12", "--out", str(plot))
    assert "12 frames" in out and "knn: 1000 queries" in out
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_scipy_comparison_prints_its_ratios():
    out = run("versus_scipy.py", "--frames", "3", "--queries", "50")
    assert "map upkeep" in out and out.count("x\n") == 3


def test_odometry_example_tracks_the_drive_and_writes_its_plot(tmp_path):
    plot = tmp_path / "odometry.png"
    out = run("odometry.py", "--frames", "15", "--out", str(plot))
    assert out.count("ms a frame") == 3 and "ATE" in out  # eco, eco_ball, voxel_hash
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"

"""examples/python/quickstart.py runs and writes its plot."""

import subprocess
import sys

from conftest import SOURCE_DIR


def test_quickstart_writes_its_plot(tmp_path):
    plot = tmp_path / "quickstart.png"
    result = subprocess.run(
        [sys.executable, str(SOURCE_DIR / "examples" / "python" / "quickstart.py"),
         "--frames", "12", "--out", str(plot)],
        capture_output=True, text=True, timeout=300, check=False)
    assert result.returncode == 0, result.stderr
    assert "12 frames" in result.stdout and "knn: 1000 queries" in result.stdout
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"

#!/usr/bin/env bash
# The install route of the README, checked: a fresh virtual environment (with Debian's site
# packages: numpy, setuptools), pip installs ./python offline, and the installed package — not
# the build tree's — runs the quickstart. With BUILD_DIR, setup.py configures the package as
# always but takes the module that tree built (ECO_CMAKE_BUILD_DIR) rather than compile it again.
# Usage: pip_install_check.sh PYTHON SOURCE_DIR WORK_DIR [BUILD_DIR]
set -euo pipefail
python=$1 source=$2 work=$3
if [ -n "${4:-}" ]; then export ECO_CMAKE_BUILD_DIR=$4; fi
rm -rf "$work"
"$python" -m venv --system-site-packages "$work/venv"
env -u PYTHONPATH "$work/venv/bin/python" -m pip install --no-build-isolation --no-index \
  --disable-pip-version-check "$source/python"
cd "$work"
location=$(env -u PYTHONPATH "$work/venv/bin/python" -c 'import eco; print(eco.__file__)')
case "$location" in
  "$work/venv/"*) echo "installed at $location" ;;
  *) echo "eco imported from $location, not the virtual environment" >&2; exit 1 ;;
esac
env -u PYTHONPATH MPLBACKEND=Agg "$work/venv/bin/python" "$source/examples/python/quickstart.py" \
  --frames 5 --out "$work/quickstart.png"
test -s "$work/quickstart.png"

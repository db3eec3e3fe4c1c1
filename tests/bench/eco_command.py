"""The eco command as the command-line tests drive it: run in a fresh work folder, its failures
reported with what it printed.

usage (from a test script): CLI, WORK = start(sys.argv); then eco(...), check(...)."""

import os
import shutil
import subprocess
import sys

_CLI = _WORK = None


def start(argv):
    """Takes ECO_CLI and WORK_DIR from the script's arguments and empties WORK_DIR."""
    global _CLI, _WORK
    _CLI, _WORK = argv[1], argv[2]
    shutil.rmtree(_WORK, ignore_errors=True)
    os.makedirs(_WORK)
    return _CLI, _WORK


def eco(*args, ok=True):
    """Runs eco with `args` in the work folder; exits the test unless it succeeds (or, ok=False, fails)."""
    done = subprocess.run([_CLI, *args], capture_output=True, text=True, cwd=_WORK)
    if ok and done.returncode != 0:
        sys.exit(f"eco {' '.join(args)} failed:\n{done.stdout}\n{done.stderr}")
    if not ok and done.returncode == 0:
        sys.exit(f"eco {' '.join(args)} should have failed:\n{done.stdout}")
    return done


def check(condition, message):
    if not condition:
        sys.exit(message)

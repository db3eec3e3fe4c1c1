"""Builds the Python package `eco` with the repository's own CMake (python/CMakeLists.txt).

    python3 -m pip install --no-build-isolation ./python

No download: CMake, a C++20 compiler, Eigen, liblzf, pybind11 and numpy come from Debian
(`make python` installs them and runs the command above). The version is the CMake project's.

ECO_CMAKE_BUILD_DIR=build (a build tree of this repository, `make build`'s) takes the module
built there instead of compiling every source again; the package is configured as without it.
"""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent.parent  # the repository: CMakeLists.txt, src/, include/


def project_version():
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(eco VERSION ([0-9.]+)", text).group(1)


class CMakeExtension(Extension):
    """An extension CMake builds: no sources for setuptools to compile."""

    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        package_dir = Path(self.get_ext_fullpath(ext.name)).resolve().parent
        build_dir = Path(self.build_temp).resolve() / "cmake"
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build_dir),
            "-DCMAKE_BUILD_TYPE=Release",
            "-DECO_BUILD_PYTHON=ON",
            "-DECO_BUILD_TESTS=OFF", "-DECO_BUILD_TOOLS=OFF", "-DECO_BUILD_EXAMPLES=OFF",
            f"-DPython_EXECUTABLE={sys.executable}",
            f"-DECO_PYTHON_PACKAGE_DIR={package_dir}",
        ]
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(configure, check=True)
        built = os.environ.get("ECO_CMAKE_BUILD_DIR")
        if not built:
            subprocess.run(["cmake", "--build", str(build_dir), "--target", "eco_python", "-j", jobs],
                           check=True)
            return
        # a build tree of the repository's made with -DECO_BUILD_PYTHON=ON (make build's): its
        # module, brought up to date there, instead of every source compiled again here
        subprocess.run(["cmake", "--build", built, "--target", "eco_python", "-j", jobs], check=True)
        modules = list((Path(built) / "python" / "eco").glob("_eco*.so"))
        if len(modules) != 1:
            sys.exit(f"ECO_CMAKE_BUILD_DIR={built} holds {len(modules)} modules python/eco/_eco*.so, not one")
        shutil.copy2(modules[0], package_dir / Path(self.get_ext_fullpath(ext.name)).name)


setup(
    version=project_version(),
    ext_modules=[CMakeExtension("eco._eco")],
    cmdclass={"build_ext": CMakeBuild},
)

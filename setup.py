# SPDX-License-Identifier: MIT
"""The build step of the Python package (metadata: pyproject.toml).

As REBOUND's wheel carries its shared library, granflow's carries
libgranflow.so: build_py builds the library with CMake (the project's own
CMakeLists.txt, a Release build in the setuptools build directory) and copies
it into the package beside _lib.py, which loads it first. Everything comes
from the system (Debian's compiler, CMake and -dev packages, as
scripts/deps.sh installs them); nothing is downloaded.

GRANFLOW_CMAKE_BUILD_DIR=DIR uses an existing CMake build directory instead
(it is brought up to date with `cmake --build DIR --target granflow`): the
packaging test uses the build it tests, and a developer saves a second build.
"""
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py

try:
    from wheel.bdist_wheel import bdist_wheel
except ImportError:  # pip install without the wheel package: no bdist_wheel to adjust
    bdist_wheel = None

ROOT = Path(__file__).resolve().parent
LIBRARY = "libgranflow.so"


def project_version():
    """The version of project(granflow VERSION x.y.z) in CMakeLists.txt, as gf_version() says it."""
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(granflow\s+VERSION\s+([0-9][0-9.]*)", text).group(1)


def run(cmd):
    print("granflow setup.py:", " ".join(str(c) for c in cmd), flush=True)
    subprocess.run([str(c) for c in cmd], check=True)


def build_library(build_temp):
    """Builds libgranflow.so with CMake; returns the path of the real file (not the symlink)."""
    given = os.environ.get("GRANFLOW_CMAKE_BUILD_DIR")
    if given:
        build_dir = Path(given).resolve()
        if not (build_dir / "CMakeCache.txt").exists():
            sys.exit(f"GRANFLOW_CMAKE_BUILD_DIR={given}: not a configured CMake build directory (no CMakeCache.txt)")
    else:
        build_dir = Path(build_temp).resolve() / "cmake"
        run(["cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release"])
    jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
    run(["cmake", "--build", build_dir, "--target", "granflow", "-j", jobs])
    lib = (build_dir / LIBRARY).resolve()
    if not lib.is_file():
        sys.exit(f"CMake built no {build_dir / LIBRARY}")
    return lib


class BuildPyWithLibrary(build_py):
    """build_py, then libgranflow.so built by CMake into the package directory."""

    def run(self):
        super().run()
        lib = build_library(self.get_finalized_command("build").build_temp)
        dest = Path(self.build_lib) / "granflow" / LIBRARY
        dest.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(lib, dest)
        os.chmod(dest, 0o755)

    def get_outputs(self, include_bytecode=1):
        return super().get_outputs(include_bytecode) + [str(Path(self.build_lib) / "granflow" / LIBRARY)]


class BinaryDistribution(Distribution):
    """A package with a compiled library: a platform wheel installed to platlib."""

    def has_ext_modules(self):
        return True


commands = {"build_py": BuildPyWithLibrary}
if bdist_wheel is not None:

    class BdistWheelCtypes(bdist_wheel):
        """The library is loaded with ctypes, not imported: any Python 3 on this
        platform can use the wheel (py3-none-<platform>)."""

        def finalize_options(self):
            super().finalize_options()
            self.root_is_pure = False

        def get_tag(self):
            _, _, plat = super().get_tag()
            return "py3", "none", plat

    commands["bdist_wheel"] = BdistWheelCtypes

setup(
    version=project_version(),
    cmdclass=commands,
    distclass=BinaryDistribution,
    # Beside the CMake build directory, not in it.
    options={"build": {"build_base": "build-python"}},
)

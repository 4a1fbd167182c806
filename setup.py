"""Builds the extension pcsim._core with the project's CMake build (python/CMakeLists.txt) for
the interpreter running pip; the version is the one CMakeLists.txt's project() gives."""

import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent
VERSION = re.search(r"project\(pcsim VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text()).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        configure = ["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release", "-DPAGECACHE_BUILD_TESTS=OFF",
                     "-DPAGECACHE_BUILD_BENCHMARKS=OFF", "-DPAGECACHE_BUILD_PYTHON=ON", f"-DPython3_EXECUTABLE={sys.executable}"]
        subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "--build", str(build), "--target", "pcsim_python_core", "-j", jobs], check=True)
        built = next((build / "python" / "pcsim").glob("_core*.so"), None)
        if built is None:
            raise RuntimeError("the CMake build made no pcsim._core (are python3-dev and pybind11-dev installed?)")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built, target)


setup(
    version=VERSION,
    packages=["pcsim"],
    package_dir={"": "python"},
    package_data={"pcsim": ["py.typed", "*.pyi"]},
    ext_modules=[Extension("pcsim._core", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
)

"""Builds the collide Python module with CMake (docs/python.md).

`pip install --no-build-isolation .` runs this: CMake configures the repository with
COLLIDE_BUILD_PYTHON=ON for the Python that runs pip, builds the `collide_python` target (the core,
the scene library and the pybind11 extension) and the extension lands in the package `collide`.
Nothing is downloaded: CMake finds pybind11, GLM, Qhull, nlohmann-json and tinyobjloader among
Debian's packages (scripts/install-deps --python).
"""
import os
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        target = Path(self.get_ext_fullpath(ext.name)).resolve()
        build_dir = Path(self.build_temp).resolve() / "cmake"
        build_dir.mkdir(parents=True, exist_ok=True)
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
            "-DCOLLIDE_BUILD_PYTHON=ON", "-DCOLLIDE_BUILD_TESTS=OFF", "-DCOLLIDE_BUILD_TOOLS=OFF",
            "-DCOLLIDE_INSTALL=OFF", f"-DPython_EXECUTABLE={sys.executable}",
        ]
        if subprocess.run(["ninja", "--version"], capture_output=True).returncode == 0:
            configure += ["-G", "Ninja"]
        subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "collide_python", "-j", jobs], check=True)
        built = next((build_dir / "python" / "collide").glob("_collide*.so"))
        target.parent.mkdir(parents=True, exist_ok=True)
        self.copy_file(str(built), str(target))


setup(ext_modules=[CMakeExtension("collide._collide")], cmdclass={"build_ext": CMakeBuild})
